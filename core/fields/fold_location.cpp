#include "core/fields/fold_location.h"

#include <algorithm>
#include <cmath>

#include "core/mesh/cell_rings.h"

namespace facehex {

FoldLocation fold_location(const VolumeMesh& mesh, const Eigen::MatrixXd& uvw, const Eigen::MatrixXi& fixed,
                           const std::vector<int>& folded, int rings) {
  FoldLocation location;
  location.folded = static_cast<int>(folded.size());
  location.rings = rings;
  if (folded.empty() || fixed.rows() != uvw.rows()) return location;
  for (int cut = 0; cut < 4; ++cut) {
    const int field = cut / 2;
    const double end = cut % 2;
    std::vector<char> on_cut(uvw.rows(), 0);
    for (Eigen::Index v = 0; v < uvw.rows(); ++v) on_cut[v] = fixed(v, field) != 0 && uvw(v, field) == end;
    const std::vector<char> near = within_cell_rings(mesh, std::move(on_cut), rings);
    for (int t : folded) {
      bool touches = false;
      for (int i = 0; i < node_count(mesh.types[t]); ++i) touches |= near[mesh.C(t, i)] != 0;
      location.near_cut[cut] += touches;
    }
  }
  return location;
}

std::string fold_location_text(const FoldLocation& location) {
  if (location.folded == 0) return "";
  const auto most = std::max_element(location.near_cut.begin(), location.near_cut.end());
  if (2 * *most < location.folded) return "";
  static const char* const kCuts[] = {"posterior cut at u = 0", "posterior cut at u = 1", "bottom cut (v = 0)",
                                      "top cut (v = 1)"};
  static const char* const kOptions[] = {"--posterior-cut", "--posterior-cut", "--bottom-cut", "--top-cut"};
  const auto cut = most - location.near_cut.begin();
  return "; " + std::to_string(static_cast<int>(std::lround(100.0 * *most / location.folded))) +
         " % of the folded tets lie within " + std::to_string(location.rings) + " cells of the " + kCuts[cut] +
         ", which a CT's model is cut at elsewhere with " + kOptions[cut];
}

}  // namespace facehex

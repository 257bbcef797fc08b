#pragma once
// Where a parameterization's folds lie against the cuts its fields are pinned on: a model's posterior cuts (u = 0 and
// u = 1), bottom cut (v = 0) and top cut (v = 1), which the user of a segmented CT can place elsewhere. Folds that
// crowd against one cut say where to look (a cut over thin tissue, or one running close along a bone surface); folds
// on the bone and skin sides are everywhere in a thin face and say little.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"

namespace facehex {

struct FoldLocation {
  int folded = 0;                 // the folded tets looked at
  std::array<int, 4> near_cut{};  // of them, those with a vertex within `rings` cell rings of cut u0, u1, v0, v1
  int rings = 0;
};

// mesh: the parameterized tets; uvw #V x 3 and fixed #V x 3 (nonzero where a constraint pins the field) as for
// parameterization_health; folded: ids of the folded tets (ParamHealth::folded_tets). A vertex lies on a cut where its
// field is pinned to that cut's end value (0 or 1; a feature's values lie between).
FoldLocation fold_location(const VolumeMesh& mesh, const Eigen::MatrixXd& uvw, const Eigen::MatrixXi& fixed,
                           const std::vector<int>& folded, int rings);

// "; 78 % of the folded tets lie within 4 cells of the top cut (v = 1), which a CT's model is cut at elsewhere with
// --top-cut" for the cut holding at least half of them (the most), or empty.
std::string fold_location_text(const FoldLocation& location);

}  // namespace facehex

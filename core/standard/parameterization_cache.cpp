#include "core/standard/parameterization_cache.h"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/fields/orthogonalize.h"
#include "core/io/mesh_io.h"
#include "core/util/error.h"
#include "core/util/text_file.h"

namespace facehex {
namespace {

constexpr const char* kFormat = "facehex-parameterization-cache";
constexpr int kVersion = 1;

// 64-bit FNV-1a.
class Fingerprint {
 public:
  void add(const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) hash_ = (hash_ ^ p[i]) * 1099511628211ull;
  }
  template <typename Matrix>
  void add_matrix(const Matrix& m) {
    const long long shape[2] = {static_cast<long long>(m.rows()), static_cast<long long>(m.cols())};
    add(shape, sizeof shape);
    add(m.data(), sizeof(typename Matrix::Scalar) * static_cast<size_t>(m.size()));
  }
  void add_text(const std::string& s) { add(s.data(), s.size() + 1); }
  std::string hex() const {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash_));
    return text;
  }

 private:
  std::uint64_t hash_ = 14695981039346656037ull;
};

std::string json_path(const std::string& vtu_path) {
  return std::filesystem::path(vtu_path).replace_extension(".json").string();
}

}  // namespace

std::string parameterization_cache_path(const std::string& standard_mesh) {
  return std::filesystem::path(standard_mesh).replace_extension(".param.vtu").string();
}

std::string parameterization_fingerprint(const TetDomain& domain, const ConstraintSet& set,
                                         const HarmonicFieldsOptions& options) {
  Fingerprint f;
  f.add_text(std::string(kFormat) + " " + std::to_string(kVersion));
  f.add_matrix(domain.V);
  f.add_matrix(domain.T);
  f.add_matrix(domain.side_mask);
  f.add_text(to_json(set));
  f.add(&options.orthogonality_iterations, sizeof options.orthogonality_iterations);
  f.add(options.order.data(), sizeof(int) * options.order.size());
  return f.hex();
}

void write_parameterization_cache(const std::string& path, const TetDomain& domain, const ModelParameterization& p,
                                  const ConstraintSet& set, const HarmonicFieldsOptions& options) {
  VolumeMesh m = VolumeMesh::from_tets(p.V, p.T);
  m.point_data["uvw"] = p.fields.uvw;
  m.point_data["uvw_initial"] = p.fields.uvw_initial;
  if (domain.side_mask.size() > 0) m.point_data[kSideMaskArray] = domain.side_mask.cast<double>();
  write_volume_mesh(path, m);
  const nlohmann::json meta = {{"format", kFormat},
                               {"version", kVersion},
                               {"fingerprint", parameterization_fingerprint(domain, set, options)},
                               {"domain", domain.description},
                               {"hex_vertices", domain.hex_vertices},
                               {"tets", p.T.rows()},
                               {"inverted_parametric_tets", p.health.inverted}};
  write_text_file(json_path(path), meta.dump(2) + "\n");
}

std::optional<ModelParameterization> read_parameterization_cache(const std::string& path, const TetDomain& domain,
                                                                 const ConstraintSet& set,
                                                                 const HarmonicFieldsOptions& options,
                                                                 std::string* why_not) {
  auto refuse = [&](const std::string& reason) -> std::optional<ModelParameterization> {
    if (why_not) *why_not = reason;
    return std::nullopt;
  };
  if (!std::filesystem::exists(path) || !std::filesystem::exists(json_path(path))) return refuse("");
  try {
    const nlohmann::json meta = nlohmann::json::parse(read_text_file(json_path(path)));
    if (meta.value("format", "") != kFormat || meta.value("version", 0) != kVersion)
      return refuse(json_path(path) + ": not a parameterization cache of this version");
    if (meta.value("fingerprint", "") != parameterization_fingerprint(domain, set, options))
      return refuse(path + ": made from another standard mesh, constraint set or field options");
    const VolumeMesh m = read_volume_mesh(path);
    if (!m.is_tet_mesh() || m.V != domain.V || m.tets() != domain.T || !m.point_data.count("uvw") ||
        !m.point_data.count("uvw_initial") || m.point_data.at("uvw").cols() != 3)
      return refuse(path + ": its tets or fields do not match its fingerprint");
    HarmonicFieldsResult fields;
    fields.uvw = m.point_data.at("uvw");
    fields.uvw_initial = m.point_data.at("uvw_initial");
    const GradientMatrix G = gradient_operator(domain.V, domain.T);
    for (int f = 0; f < 3; ++f) {
      fields.gradients[f] = tet_gradients(G, fields.uvw.col(f));
      fields.gradients_initial[f] = tet_gradients(G, fields.uvw_initial.col(f));
    }
    fields.angles = angle_statistics(gradient_angles(fields.gradients));
    fields.angles_initial = angle_statistics(gradient_angles(fields.gradients_initial));
    return parameterization_of(domain.V, domain.T, resolve_constraints(set, domain.V, domain.T, domain.side_mask, path),
                               std::move(fields));
  } catch (const std::exception& e) {
    return refuse(std::string("unreadable: ") + e.what());
  }
}

}  // namespace facehex

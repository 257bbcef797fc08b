#include "ui/model_loading.h"

#include "core/mesh_check.h"
#include "core/quality/hex_quality.h"
#include "core/resources.h"
#include "core/side_mask.h"
#include "core/standard/closed_domain.h"
#include "core/synthetic_shell.h"
#include "core/tetgen/tetrahedralize.h"
#include "core/tet_topology.h"

#include <QFileInfo>
#include <filesystem>

namespace facehex::gui {
namespace fs = std::filesystem;
namespace {

std::vector<char> boundary_of(const StandardDomain& d) {
  return boundary_vertex_flags(static_cast<int>(d.V.rows()), boundary_faces(d.T).F);
}

// A tet model as its own parameterization domain.
LoadedModel tet_model(VolumeMesh mesh) {
  LoadedModel m;
  m.domain.V = mesh.V;
  m.domain.T = mesh.tets();
  m.domain.side_mask = side_mask_of(mesh);
  m.domain.description = "the model's own tets";
  m.boundary = boundary_of(m.domain);
  m.mesh = std::move(mesh);
  return m;
}

void set_constraints(LoadedModel& m, const std::string& path) {
  if (!path.empty() && fs::exists(path)) {
    m.constraints.set = read_constraint_set(path);
    m.constraintsPath = QString::fromStdString(path);
  } else if (m.domain.side_mask.size() > 0) {
    m.constraints.set = side_constraints();
  }
  m.constraints.visible.assign(m.constraints.set.constraints.size(), true);
}

}  // namespace

LoadedModel load_patient(const std::string& path, const MeshReadOptions& options) {
  VolumeMesh mesh = read_volume_mesh(path, options);
  check_and_orient_tet_mesh(mesh, path);
  LoadedModel m = tet_model(std::move(mesh));
  m.path = QString::fromStdString(path);
  m.name = QFileInfo(m.path).fileName();
  fs::path constraints = fs::path(path).replace_extension(".json");
  if (!fs::exists(constraints)) constraints = fs::path(path).parent_path() / "constraints.json";
  set_constraints(m, constraints.string());
  return m;
}

LoadedModel load_standard(const std::string& name_or_path) {
  const BundledModel b = find_standard(name_or_path);
  LoadedModel m;
  m.mesh = read_volume_mesh(b.mesh);
  m.domain = closed_domain(m.mesh);  // the CLI's default domain: openings filled
  m.boundary = boundary_of(m.domain);
  m.quality = element_quality(m.mesh);
  m.path = QString::fromStdString(b.mesh);
  m.name = QString::fromStdString(b.name);
  set_constraints(m, b.constraints);
  return m;
}

LoadedModel demo_patient() {
  if (!bundled_patients().empty()) {
    const BundledModel b = default_patient();
    LoadedModel m = load_patient(b.mesh);
    m.name = QString::fromStdString(b.name);
    return m;
  }
  // The phantom the core's end-to-end tests map the bundled standard onto.
  SyntheticShellOptions shell;
  shell.edge_length = 6.0;
  TetrahedralizeOptions options;
  options.target_edge_length = shell.edge_length;
  TetrahedralizeResult r = tetrahedralize(synthetic_shell_surface(shell), options);
  const Eigen::VectorXi sides = (r.boundary_labels.array() - 1).matrix();  // labels are side + 1
  r.mesh.point_data[kSideMaskArray] =
      side_mask_from_faces(r.mesh.num_vertices(), r.boundary_faces, sides).cast<double>();
  const std::string name = "synthetic shell (phantom patient)";
  check_and_orient_tet_mesh(r.mesh, name);
  LoadedModel m = tet_model(std::move(r.mesh));
  m.name = QString::fromStdString(name);
  set_constraints(m, "");  // its six sides
  return m;
}

}  // namespace facehex::gui

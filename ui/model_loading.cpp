#include "ui/model_loading.h"

#include <QFileInfo>
#include <filesystem>

#include "core/face/automatic_constraints.h"
#include "core/io/mesh_io.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/side_mask.h"
#include "core/mesh/synthetic_shell.h"
#include "core/mesh/tet_topology.h"
#include "core/quality/hex_quality.h"
#include "core/segment/patient_input.h"
#include "core/standard/closed_domain.h"
#include "core/tetgen/tetrahedralize.h"
#include "core/util/resources.h"

namespace facehex::gui {
namespace fs = std::filesystem;
namespace {

std::vector<char> boundary_of(const TetDomain& d) {
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

// The constraints a model opens with: those of `path` if it exists; else, with side labels, the six sides and, when
// `feature_values` is given, the facial features (automatic_constraints) unless they cannot be placed; else none.
// Returns which, for the status bar.
QString set_constraints(LoadedModel& m, const std::string& path, const std::map<std::string, double>* feature_values) {
  QString what = QObject::tr("no constraints (the model has no side labels)");
  if (!path.empty() && fs::exists(path)) {
    m.constraints.set = read_constraint_set(path);
    m.constraintsPath = QString::fromStdString(path);
    what = QObject::tr("constraints from %1").arg(QFileInfo(m.constraintsPath).fileName());
  } else if (m.domain.side_mask.size() > 0) {
    m.constraints.set = side_constraints();
    what = QObject::tr("the six sides");
    if (feature_values) {
      try {
        m.constraints.set = automatic_constraints(m.domain.V, m.domain.side_mask, *feature_values);
        what = QObject::tr("the six sides and %1 facial features").arg(feature_specs().size());
      } catch (const std::exception& e) {
        what += QObject::tr(", no facial features (%1)").arg(QString::fromStdString(e.what()));
      }
    }
  }
  m.constraints.visible.assign(m.constraints.set.constraints.size(), true);
  return what;
}

}  // namespace

LoadedModel load_patient(const std::string& path, const SegmentOptions& segment_options,
                         const std::map<std::string, double>& feature_values, const ProgressCallback& progress,
                         QString& constraints_note) {
  PatientTetModel patient = load_patient_model(path, segment_options, progress);
  LoadedModel m = tet_model(std::move(patient.mesh));
  m.segmentation = patient.segmentation;
  m.path = QString::fromStdString(path);
  m.name = QFileInfo(m.path).fileName();
  fs::path constraints = fs::path(path).replace_extension(".json");
  if (!fs::exists(constraints)) constraints = fs::path(path).parent_path() / "constraints.json";
  constraints_note = set_constraints(m, constraints.string(), &feature_values);
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
  set_constraints(m, b.constraints, nullptr);
  return m;
}

LoadedModel demo_patient(const std::map<std::string, double>& feature_values, QString& constraints_note) {
  if (!bundled_patients().empty()) {
    const BundledModel b = default_patient();
    LoadedModel m = load_patient(b.mesh, SegmentOptions{}, feature_values, {}, constraints_note);
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
  constraints_note = set_constraints(m, "", &feature_values);
  return m;
}

}  // namespace facehex::gui

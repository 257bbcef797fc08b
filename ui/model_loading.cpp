#include "ui/model_loading.h"

#include <QFileInfo>

#include "core/mesh/tet_topology.h"
#include "core/quality/hex_quality.h"
#include "core/util/resources.h"

namespace facehex::gui {
namespace {

std::vector<char> boundary_of(const TetDomain& d) {
  return boundary_vertex_flags(static_cast<int>(d.V.rows()), boundary_faces(d.T).F);
}

LoadedModel from_setup(PatientSetup p, QString& constraints_note) {
  LoadedModel m;
  m.boundary = boundary_of(p.domain);
  m.domain = std::move(p.domain);
  m.mesh = std::move(p.mesh);
  m.segmentation = std::move(p.segmentation);
  m.path = QString::fromStdString(p.path);
  m.name = QFileInfo(m.path).fileName();
  m.constraintsPath = QString::fromStdString(p.constraints_path);
  m.constraints.set = std::move(p.constraints);
  m.constraints.visible.assign(m.constraints.set.constraints.size(), true);
  m.constraints.landmarks = std::move(p.landmarks);
  constraints_note = QString::fromStdString(p.constraints_note);
  return m;
}

}  // namespace

LoadedModel load_patient(const std::string& path, const SegmentOptions& segment_options,
                         const std::map<std::string, double>* feature_values, const ProgressCallback& progress,
                         QString& constraints_note) {
  return from_setup(facehex::load_patient(path, segment_options, "", feature_values, progress), constraints_note);
}

LoadedModel load_standard(const std::string& name_or_path) {
  StandardSetup s = facehex::load_standard(name_or_path);
  LoadedModel m;
  m.boundary = boundary_of(s.domain);
  m.domain = std::move(s.domain);
  m.quality = element_quality(s.mesh);
  m.mesh = std::move(s.mesh);
  m.path = QString::fromStdString(s.path);
  m.name = QString::fromStdString(s.name);
  m.constraintsPath = QString::fromStdString(s.constraints_path);
  m.constraints.set = std::move(s.constraints);
  m.constraints.visible.assign(m.constraints.set.constraints.size(), true);
  return m;
}

LoadedModel demo_patient(const std::map<std::string, double>* feature_values, QString& constraints_note) {
  if (!bundled_patients().empty()) {
    const BundledModel b = default_patient();
    LoadedModel m = load_patient(b.mesh, SegmentOptions{}, feature_values, {}, constraints_note);
    m.name = QString::fromStdString(b.name);
    return m;
  }
  LoadedModel m =
      from_setup(patient_from_mesh(synthetic_shell_patient(6.0), "synthetic shell (phantom patient)", feature_values),
                 constraints_note);
  m.path.clear();  // made in memory: no file to name or to look for a cache beside
  return m;
}

StandardSetup standard_setup(const LoadedModel& standard) {
  StandardSetup s;
  s.name = standard.name.toStdString();
  s.path = standard.path.toStdString();
  s.mesh = standard.mesh;
  s.constraints = standard.constraints.set;
  s.constraints_path = standard.source();
  s.domain = standard.domain;
  return s;
}

PatientSetup patient_setup(const LoadedModel& patient) {
  PatientSetup p;
  p.path = (patient.path.isEmpty() ? patient.name : patient.path).toStdString();
  p.mesh = patient.mesh;
  p.segmentation = patient.segmentation;
  p.domain = patient.domain;
  p.constraints = patient.constraints.set;
  p.constraints_path = patient.constraintsPath.toStdString();
  p.landmarks = patient.constraints.landmarks;
  return p;
}

}  // namespace facehex::gui

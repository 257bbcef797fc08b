#include "core/workflow/transfer.h"

#include "core/io/fe_sets.h"
#include "core/io/mesh_io.h"
#include "core/quality/hex_quality.h"
#include "core/standard/parameterization_cache.h"

namespace facehex {
namespace {

// The fields of a parameterization at the mesh's vertices (the first rows of the parameterized domain).
void attach_fields(VolumeMesh& mesh, const ModelParameterization& p) {
  const Eigen::Index n = mesh.num_vertices();
  const Eigen::MatrixXd uvw = p.fields.uvw.topRows(n);
  mesh.point_data["u"] = uvw.col(0);
  mesh.point_data["v"] = uvw.col(1);
  mesh.point_data["w"] = uvw.col(2);
  mesh.point_data["uvw"] = uvw;
  mesh.point_data["uvw_initial"] = p.fields.uvw_initial.topRows(n);
  mesh.point_data["fixed_uvw"] = p.fixed.topRows(n).cast<double>();
}

}  // namespace

TransferResult transfer(const StandardSetup& standard, const PatientSetup& patient, const TransferOptions& options,
                        const ProgressCallback& progress) {
  TransferResult r;
  const std::optional<ModelParameterization> cached =
      cached_parameterization(standard.path, standard.domain, standard.constraints, options.fields, &r.cache_note);
  r.run = run_transfer(standard.mesh, standard.domain, standard.constraints, standard.source(), patient.mesh,
                       patient.constraints, patient.source(), options, sub_progress(progress, 0.0, 0.97),
                       cached ? &*cached : nullptr);
  if (cached) r.run.standard_parameterization_source = parameterization_cache_path(standard.path);
  report_progress(progress, "quality", 0.97);
  r.patient_hex = decorate_patient_hex(r.run, standard.mesh);
  r.standard_quality = quality_report(standard.mesh, nullptr);
  r.plain_mapping_quality = quality_report(r.run.mapped_hex, &standard.mesh);
  r.patient_quality = quality_report(r.run.patient_hex, &standard.mesh);
  r.distance = side_vertex_distances(r.run, standard.mesh);
  report_progress(progress, "quality", 1.0);
  return r;
}

VolumeMesh with_quality(VolumeMesh mesh) {
  const ElementQuality q = element_quality(mesh);
  mesh.cell_data["shape"] = q.shape;
  mesh.cell_data["scaled_jacobian"] = q.scaled_jacobian;
  return mesh;
}

VolumeMesh decorate_patient_hex(const TransferRun& run, const VolumeMesh& standard) {
  VolumeMesh hex = with_quality(run.patient_hex);
  hex.point_data["moved_from_mapping"] = moved_from_mapping(run);
  hex.cell_data["dihedral_change"] = cell_dihedral_change(standard, hex);
  hex.point_data["uvw"] = hex_vertex_uvw(run, standard.num_vertices());
  const auto mask = standard.point_data.find(kSideMaskArray);
  if (mask != standard.point_data.end()) hex.point_data[kSideMaskArray] = mask->second;
  attach_fe_arrays(hex);
  return hex;
}

VolumeMesh standard_with_fields(const VolumeMesh& standard, const ModelParameterization& p) {
  VolumeMesh m = with_quality(standard);
  attach_fields(m, p);
  return m;
}

VolumeMesh parameterized_tet_mesh(const ModelParameterization& p, const VolumeMesh* source) {
  VolumeMesh m = VolumeMesh::from_tets(p.V, p.T);
  if (source && source->num_vertices() == p.V.rows()) m.point_data = source->point_data;  // same vertices
  attach_fields(m, p);
  for (int f = 0; f < 3; ++f) {
    m.cell_data[std::string("grad_") + kFieldNames[f]] = p.fields.gradients[f];
    m.cell_data[std::string("grad_") + kFieldNames[f] + "_initial"] = p.fields.gradients_initial[f];
  }
  return m;
}

MeshWriteOptions parameterized_model_writing() {
  MeshWriteOptions options;
  for (int f = 0; f < 3; ++f) {
    options.single_precision_arrays.insert(std::string("grad_") + kFieldNames[f]);
    options.single_precision_arrays.insert(std::string("grad_") + kFieldNames[f] + "_initial");
  }
  return options;
}

int exit_code(const QualitySummary& result) {
  return result.inverted + result.degenerate == 0 ? 0 : kExitUnusableCells;
}

}  // namespace facehex

#include "core/segment/patient_input.h"

#include "core/io/mesh_io.h"

namespace facehex {

PatientTetModel load_patient_model(const std::string& path, const SegmentOptions& options,
                                   const ProgressCallback& progress) {
  PatientTetModel model;
  if (is_ct_input(path)) {
    model.mesh = build_patient_model_from_file(path, options, progress);
  } else {
    MeshReadOptions read;
    read.target_edge_length = options.tets.target_edge_length;
    model.mesh = read_volume_mesh(path, read);
  }
  model.check = check_and_orient_tet_mesh(model.mesh, path);
  return model;
}

}  // namespace facehex

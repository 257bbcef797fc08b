#include "core/segment/patient_input.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/io/mesh_io.h"
#include "core/segment/ct_volume.h"
#include "core/util/memory_errors.h"

namespace facehex {

PatientTetModel load_patient_model(const std::string& path, const SegmentOptions& options,
                                   const ProgressCallback& progress) {
  return naming_memory_errors(path, "read or segment it", [&] {
    PatientTetModel model;
    if (is_ct_input(path)) {
      report_progress(progress, "segmentation: reading the CT", 0.0);
      PatientModel segmented = build_patient_model(read_ct_volume(path, options.orientation), options, progress);
      model.mesh = std::move(segmented.mesh);
      CtSegmentation as_used{segmented.options, segmented.thresholds, segmented.cuts, segmented.repair};
      as_used.options.tets.target_edge_length = segmented.edge_length;
      as_used.options.coarsen_above_tets = 0;
      model.segmentation = as_used;
    } else {
      MeshReadOptions read;
      read.target_edge_length = options.tets.target_edge_length;
      model.mesh = read_volume_mesh(path, read);
    }
    model.check = check_and_orient_tet_mesh(model.mesh, path);
    return model;
  });
}

std::string segmentation_summary(const CtSegmentation& segmentation) {
  const TissueThresholds& thresholds = segmentation.thresholds;
  const FaceCuts& cuts = segmentation.cuts;
  std::ostringstream text;
  text << std::fixed << std::setprecision(1) << "skin threshold " << thresholds.skin << ", bone threshold "
       << thresholds.bone << " (file units); ";
  if (cuts.turn.degrees != 0)
    text << "head turned " << cuts.turn.degrees << " deg about the vertical axis through x " << cuts.turn.axis.x()
         << ", y " << cuts.turn.axis.y() << "; cuts (mm, head frame, --head-turn 0 for the CT's): ";
  else
    text << "cuts (mm, segmentation frame): ";
  text << "top z " << cuts.top_z << ", bottom z " << cuts.bottom_z << ", posterior y " << cuts.posterior_y
       << ", mid-plane x " << cuts.centre_x;
  if (std::isfinite(cuts.jaw_z)) text << ", jaw cut rising to z " << cuts.jaw_z << " at the posterior cut";
  if (cuts.anatomy) text << "; found: " << face_anatomy_text(*cuts.anatomy);
  text << "; tets of edge length " << segmentation.options.tets.target_edge_length << " mm";
  if (!segmentation.repair.empty()) text << "; repaired: " << segmentation.repair;
  return text.str();
}

}  // namespace facehex

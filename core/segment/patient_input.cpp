#include "core/segment/patient_input.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/face/face_landmarks.h"
#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/segment/ct_volume.h"
#include "core/util/memory_errors.h"

namespace facehex {
namespace {

// Why the landmarks of a segmented model cannot be found or are implausible, or none.
std::optional<std::string> landmarks_problem(const VolumeMesh& mesh, const std::string& path) {
  try {
    check_plausible(find_face_landmarks(mesh.V, side_mask_of(mesh), landmark_options_for(mesh, path)),
                    "give them with --landmarks FILE");
    return std::nullopt;
  } catch (const Error& e) {
    return e.problem();
  }
}

// The CT segmented in its own frame; when its face's anatomy or the landmarks on its model are not found there, no
// pitch was given and the hard palate slopes kMinHeadPitch or more, segmented again with the head pitched back by the
// palate's slope, and that model taken if its landmarks are found.
PatientModel segment_ct(const std::string& path, const SegmentOptions& options, const ProgressCallback& progress) {
  const CtVolume ct = read_ct_volume(path, options.orientation, options.dicom_series);
  const auto pitch_worth_trying = [&](const std::optional<double>& palate) {
    return !options.cuts.head_pitch && palate && std::abs(*palate) >= kMinHeadPitch;
  };
  std::optional<PatientModel> model;
  std::optional<FaceNotFound> not_found;
  std::string problem;  // what went wrong in the CT's own frame
  std::optional<double> palate;
  try {
    model = build_patient_model(ct, options, progress);
    palate = model->cuts.palate_pitch;
    if (!pitch_worth_trying(palate)) return std::move(*model);
    const std::optional<std::string> landmarks = landmarks_problem(model->mesh, path);
    if (!landmarks) return std::move(*model);
    problem = "the landmarks were not found in the CT's frame (" + *landmarks + ")";
  } catch (const FaceNotFound& e) {
    if (!pitch_worth_trying(e.palate_pitch)) throw;
    not_found = e;
    palate = e.palate_pitch;
    problem = "the face was not found in the CT's frame (" + e.problem() + ")";
  }
  std::ostringstream how;
  how << std::fixed << std::setprecision(1) << "the head pitched back by " << *palate
      << " degrees, the hard palate's slope";
  SegmentOptions again = options;
  again.cuts.head_pitch = *palate;
  std::string second_problem;
  try {
    PatientModel pitched = build_patient_model(ct, again, progress);
    const std::optional<std::string> landmarks = landmarks_problem(pitched.mesh, path);
    if (!landmarks) {
      const std::string note = problem + "; segmented again with " + how.str() + " (--head-pitch sets it)";
      pitched.repair = pitched.repair.empty() ? note : note + "; " + pitched.repair;
      pitched.cuts.palate_pitch = palate;  // as found in the CT's frame, which the note names
      return pitched;
    }
    second_problem = "its landmarks: " + *landmarks;
  } catch (const Error& e) {
    second_problem = e.problem();
  }
  if (model) return std::move(*model);  // the first model, whose landmarks' problem the transfer reports
  throw Error(not_found->subject(), not_found->problem() + "; nor with " + how.str() + " (" + second_problem +
                                        "); --head-pitch sets the pitch");
}

}  // namespace

PatientTetModel load_patient_model(const std::string& path, const SegmentOptions& options,
                                   const ProgressCallback& progress) {
  return naming_memory_errors(path, "read or segment it", [&] {
    PatientTetModel model;
    if (is_ct_input(path)) {
      report_progress(progress, "segmentation: reading the CT", 0.0);
      PatientModel segmented = segment_ct(path, options, progress);
      model.mesh = std::move(segmented.mesh);
      model.segmentation = CtSegmentation{segmented.options,
                                          segmented.thresholds,
                                          segmented.cuts,
                                          segmented.repair,
                                          segmented.edge_length,
                                          segmented.edge_length_rule,
                                          segmented.gantry_tilt_degrees,
                                          segmented.noise};
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
  text << std::fixed << std::setprecision(1);
  if (segmentation.gantry_tilt_degrees != 0)
    text << "slices resampled upright from a gantry tilt of " << segmentation.gantry_tilt_degrees << " deg; ";
  const CtNoise& noise = segmentation.noise;
  if (noise.blur > 0)
    text << "the CT's noise " << noise.sigma << " (file units, " << 100 * noise.sigma / noise.contrast
         << " % of its air to soft-tissue contrast): blurred by " << noise.blur << " mm first, to about "
         << noise.sigma_after << " (--denoise sets the blur, 0 for none); ";
  text << "skin threshold " << thresholds.skin << ", bone threshold " << thresholds.bone << " (file units); ";
  if (cuts.turn.degrees != 0)
    text << "head turned " << cuts.turn.degrees << " deg about the vertical axis through x " << cuts.turn.axis.x()
         << ", y " << cuts.turn.axis.y() << "; ";
  if (cuts.turn.pitch != 0)
    text << "head pitched " << cuts.turn.pitch << " deg (chin " << (cuts.turn.pitch > 0 ? "raised" : "lowered")
         << ") about the lateral axis through y " << cuts.turn.axis.y() << ", z " << cuts.turn.axis_z << "; ";
  if (cuts.turn.turned())
    text << "cuts (mm, head frame, --head-turn 0 --head-pitch 0 for the CT's): ";
  else
    text << "cuts (mm, segmentation frame): ";
  const auto tilted = [&](double slope) {
    if (slope != 0) text << " at the mid-plane, tilted " << std::atan(slope) * 180 / M_PI << " deg with the head";
  };
  text << "top z " << cuts.top_z;
  tilted(cuts.top_slope);
  text << ", bottom z " << cuts.bottom_z;
  tilted(cuts.bottom_slope);
  text << ", posterior y " << cuts.posterior_y;
  if (cuts.posterior_at_scan_edge)
    text << " (in front of where the scan ends across the head, y " << *cuts.scan_edge_y
         << (cuts.scan_edge_at_disc ? ", at the edge of its reconstruction disc)" : ")");
  else if (cuts.posterior_slope != 0)
    text << " at the mid-plane, turned " << cuts.posterior_turn_degrees() << " deg to pass in front of both ears";
  text << ", mid-plane x " << cuts.centre_x;
  if (std::isfinite(cuts.jaw_z)) text << ", jaw cut rising to z " << cuts.jaw_z << " at the posterior cut";
  if (std::isfinite(cuts.section_end_z)) text << ", the face region's section whole up to z " << cuts.section_end_z;
  if (cuts.anatomy) text << "; found: " << face_anatomy_text(*cuts.anatomy);
  if (cuts.palate_pitch)
    text << "; hard palate " << std::abs(*cuts.palate_pitch) << " deg " << (*cuts.palate_pitch >= 0 ? "up" : "down")
         << " to the front";
  text << "; tets of edge length " << segmentation.edge_length << " mm";
  if (!segmentation.edge_length_rule.empty())
    text << " (" << segmentation.edge_length_rule << "; --edge-length sets it)";
  if (!segmentation.repair.empty()) text << "; repaired: " << segmentation.repair;
  return text.str();
}

}  // namespace facehex

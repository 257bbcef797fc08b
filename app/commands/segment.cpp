#include <algorithm>
#include <iostream>
#include <optional>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "app/transfer_options.h"
#include "core/face/face_landmarks.h"
#include "core/io/mesh_io.h"
#include "core/mesh/sides.h"
#include "core/segment/ct_volume.h"
#include "core/segment/patient_input.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace facehex::cli {

int cmd_segment(const Argv& argv) {
  Args args("segment",
            "From a head CT (MetaImage, NIfTI, NRRD, or a DICOM folder) to the labelled patient tet model of the "
            "facial soft tissue: thresholds from the histogram, cavities closed, cut at the forehead, below the chin "
            "and in front of the ears, six sides labelled (point data side_mask). See docs/segmentation.md.");
  args.positional("CT", "CT volume file or DICOM folder").option("output", "output tet model (.vtu)");
  args.option("edge-length",
              std::string("target mean edge length of the tets (mm; default: ") + default_edge_length_help() + ")");
  args.option("write-landmarks",
              "find the facial landmarks on the model's skin, check them, and write them to this file (.json, or 3D "
              "Slicer .mrk.json)");
  add_segment_options(args);
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw UsageError("facehex segment", "missing -o OUTPUT");
  check_volume_mesh_output(args.get("output"));
  if (args.has("write-landmarks")) check_writable_file(args.get("write-landmarks"));
  const SegmentOptions options = segment_options(args);
  if (!is_ct_input(args.get("CT")))
    throw Error(args.get("CT"), "not a CT volume (.mhd, .mha, .nii, .nii.gz, .nrrd, or a DICOM folder)");
  const PatientTetModel patient = read_patient_model(args.get("CT"), options);
  const VolumeMesh& model = patient.mesh;
  const Eigen::VectorXi mask = side_mask_of(model);
  // The landmarks are found and checked before anything is written: a set that fails leaves no output behind.
  std::optional<FaceLandmarks> landmarks;
  if (args.has("write-landmarks")) {
    landmarks = find_face_landmarks(model.V, mask, landmark_options_for(model, args.get("CT")));
    std::cout << landmarks_text(*landmarks, "  ");
    check_plausible(*landmarks,
                    "give them with --landmarks FILE to run or constraints, or segment without --write-landmarks");
  }
  write_volume_mesh(args.get("output"), model);
  std::cout << model.num_vertices() << " vertices, " << model.num_cells() << " tets; side vertices:";
  for (int s = 0; s < kNumSides; ++s)
    std::cout << " " << kSideNames[s] << " " << std::count_if(mask.data(), mask.data() + mask.size(), [&](int m) {
      return (m & side_bit(static_cast<Side>(s))) != 0;
    });
  std::cout << "\nwrote " << args.get("output") << "\n";
  if (landmarks) {
    write_landmark_file(args.get("write-landmarks"), named_landmarks(*landmarks), landmarks->scan_frame);
    std::cout << "wrote " << args.get("write-landmarks") << "\n";
  }
  return 0;
}

}  // namespace facehex::cli

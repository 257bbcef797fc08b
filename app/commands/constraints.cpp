#include <iostream>
#include <optional>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "core/face/automatic_constraints.h"
#include "core/face/landmark_file.h"
#include "core/io/mesh_io.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/standard/own_feature_values.h"
#include "core/util/atomic_file.h"
#include "core/util/error.h"
#include "core/util/resources.h"

namespace facehex::cli {

int cmd_constraints(const Argv& argv) {
  Args args("constraints",
            "Writes the constraint set of a model with side labels: its six sides and the feature constraints at its "
            "facial landmarks (mid-sagittal line, eyebrow, below-nose and middle lip lines). Feature values come "
            "from the standard's set, or with --own-values from this model's own harmonic fields (to build a "
            "standard's set). Landmark positions are printed for checking.");
  args.positional("MODEL", "tet model or hex-dominant standard with side_mask")
      .option("output", "output constraint-set JSON")
      .option("standard", "standard whose feature values to use", "artisynth-refface")
      .option("band", "slab width (mm) selecting feature vertices", "2")
      .option("landmarks",
              "facial landmarks (.json, or 3D Slicer .mrk.json) to place the features at instead of "
              "those found")
      .option("write-landmarks", "write the landmarks used to this file (.json, or 3D Slicer .mrk.json)")
      .flag("own-values", "take the feature values from the model's own fields (for a standard)");
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw UsageError("facehex constraints", "missing -o OUTPUT");
  check_writable_file(args.get("output"));
  if (args.has("write-landmarks")) check_writable_file(args.get("write-landmarks"));
  const std::string path = args.get("MODEL");
  const VolumeMesh mesh = read_volume_mesh(path);
  const Eigen::VectorXi mask = side_mask_of(mesh);
  FaceLandmarks landmarks;
  const std::optional<FaceLandmarks> given =
      args.has("landmarks")
          ? std::optional<FaceLandmarks>(landmarks_from(
                read_landmark_file(args.get("landmarks"), scan_frame(mesh, path)), args.get("landmarks")))
          : std::nullopt;
  const std::map<std::string, double> values =
      args.has("own-values") ? own_feature_values(mesh, args.number("band", 0.01, 50), path)
                             : feature_values(read_constraint_set(find_standard(args.get("standard")).constraints));
  const ConstraintSet set = automatic_constraints(mesh.V, mask, landmark_options_for(mesh, path), values,
                                                  args.number("band", 0.01, 50), &landmarks, given ? &*given : nullptr);
  write_constraint_set(args.get("output"), set);
  if (args.has("write-landmarks"))
    write_landmark_file(args.get("write-landmarks"), named_landmarks(landmarks), landmarks.scan_frame);
  std::cout << "mid-sagittal plane " << mid_sagittal_plane_text(landmarks.plane) << " (" << landmarks.plane_source
            << ")\n";
  std::cout << landmarks_text(landmarks, "");
  for (const auto& c : set.constraints)
    if (!c.select.side) std::cout << c.name << ": " << kFieldNames[c.field] << " = " << c.value << "\n";
  std::cout << "wrote " << args.get("output")
            << (args.has("write-landmarks") ? " and " + args.get("write-landmarks") : "") << "\n";
  return 0;
}

}  // namespace facehex::cli

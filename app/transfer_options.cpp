#include "app/transfer_options.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>

#include "app/terminal_progress.h"
#include "core/face/automatic_constraints.h"
#include "core/face/landmark_file.h"
#include "core/util/error.h"
#include "core/util/resources.h"

namespace facehex::cli {
namespace {

// The thresholds and cuts a CT was segmented with, and the options that change them, on stderr.
void print_segmentation(const CtSegmentation& segmentation) {
  std::cerr << "segmentation: " << segmentation_summary(segmentation)
            << "\n  (change with --skin, --bone, --head-turn, --head-pitch, --top-cut, --bottom-cut, --posterior-cut, "
               "--mid-plane)\n";
}

// The value of an option that is either on or off.
bool on_or_off(const Args& args, const std::string& name) {
  const std::string value = args.get(name);
  if (value != "on" && value != "off") throw UsageError("--" + name, "expects on or off, got '" + value + "'");
  return value == "on";
}

}  // namespace

void add_field_options(Args& args) {
  args.option("iterations", "orthogonality-improvement iterations (paper: 6)", "6")
      .option("order", "orthogonalization order: basic, second, third field (e.g. wuv)", "wuv");
}

void add_segment_options(Args& args) {
  args.option("skin", "skin threshold in the file's units (default: from the histogram)")
      .option("bone", "bone threshold in the file's units (default: from the histogram)")
      .option("anterior",
              "voxel axis the face looks to: +x -x +y -y +z -z (default: from a DICOM series' orientation, else +y)")
      .option("superior", "voxel axis towards the top of the head (default: from a DICOM series, else +z)")
      .option("series",
              "the series to read from a DICOM folder that holds several: its number in the list the error prints, or "
              "its SeriesInstanceUID (default: the folder's only series)")
      .option("head-turn",
              "degrees the head is turned about the vertical axis in the scanner, towards +x from +y; the cuts are "
              "placed in the head frame turned back by it, and the model stays in the CT's frame (default: from the "
              "head's mirror symmetry, none under 2; 0: the CT's own frame)")
      .option("head-pitch",
              "degrees the head is pitched (nodding) about the lateral axis in the scanner, positive with the chin "
              "raised; the cuts are placed in the head frame pitched back by it, and the model stays in the CT's frame "
              "(default: the CT's own frame, or the hard palate's slope when the face or its landmarks are not found "
              "there and it slopes 5 degrees or more; 0: the CT's own frame only)")
      .option("top-cut",
              "height z (mm, head frame: the segmentation frame unless the head is turned or pitched) of the top cut "
              "(default: "
              "--brow-clearance above the glabella)")
      .option("bottom-cut",
              "height z (mm) of the bottom cut (default: --chin-clearance below the menton, the chin's lowest bone)")
      .option("posterior-cut",
              "y (mm) of the posterior cut, a coronal plane (default: a vertical plane --ear-clearance in front of "
              "both tragi, else of the auricles' front edges)")
      .option("mid-plane", "x (mm) of the plane between the u0 and u1 ends (default: the face's mirror-symmetry plane)")
      .option("brow-clearance", "mm from the glabella (brow ridge) up to the top cut", "15")
      .option("chin-clearance", "mm from the menton (the chin's lowest bone) down to the bottom cut", "15")
      .option("ear-clearance", "mm from the front of the ears (the tragi) forward to the posterior cut", "9")
      .option("min-thickness", "mm below the skin always in the model", "3")
      .option("max-depth", "mm below the skin beyond which nothing is in the model", "25")
      .option("bone-gap", "mm: gaps in the bone narrower than twice this (teeth) still hide the tissue behind", "5")
      .option("cavity-closing",
              "mm: openings (nostrils, lips, eyelids) narrower than twice this are closed; lips further apart (an open "
              "mouth) are closed by raising it to half their gap and 1 mm, which the summary says",
              "4")
      .option("smoothing", "mm, Gaussian blur of the model mask before its surface is taken", "1.5")
      .option("denoise",
              "mm, Gaussian blur of the CT before it is segmented (0: none; default: the blur that brings a noisy "
              "CT's measured voxel noise down to a diagnostic CT's, none for a CT that quiet)")
      .option("skin-objects",
              "on: objects lying on the skin's front above the nose tip (a head strap, thick tape) are found by their "
              "edges in the CT and the landmarks there read on the skin under them; off: the landmarks are read on "
              "the skin as segmented, an object's front included",
              "on");
}

void add_transfer_options(Args& args) {
  args.option("standard", "bundled standard name or a hex mesh file", "artisynth-refface")
      .option("standard-constraints",
              "constraint set of the standard, or automatic: placed by the rules of a patient's, valued by its own "
              "fields (default: the one bundled with it)")
      .option("edge-length",
              std::string("target edge length (mm) when the patient is a closed surface or a CT (default: ") +
                  default_edge_length_help() + ")")
      .option("standard-domain",
              "tet domain of the standard: closed (openings filled) or auxiliary (paper: split hexes only)", "closed")
      .flag("allow-inverted", "continue even if the patient parameterization has inverted tets")
      .option("skin-correspondence",
              "registered: the standard's skin registered onto the patient's decides the fields there (the features "
              "at found landmarks are left out; landmarks given with --landmarks pull the registration; where it "
              "gives no usable map, the features are used and the report says why); features: the paper's, the "
              "fields free on the skin but for the feature lines at the landmarks",
              "registered")
      .flag("hold-skin",
            "with --skin-correspondence registered: the shape relaxation keeps the standard's skin vertices at their "
            "registered correspondents instead of sliding them along the skin (correspondence before cell shape)")
      .option("pull-found-landmarks",
              "with --skin-correspondence registered: on: the landmarks found (or estimated) on the patient pull the "
              "registration towards the standard's, as landmarks given with --landmarks do, and the shape relaxation "
              "keeps the standard's landmarks where the mapping put them, so that its eyes, nose and mouth land on the "
              "patient's (report.json feature_landing); off: the registration follows the skin's shape alone (cells "
              "closer to the standard's shape where the patient's proportions differ from it)",
              "on")
      .option("landmarks-not-pulled",
              "with --skin-correspondence registered: landmarks that pull the registration in no case, found, "
              "estimated or given, by name, comma-separated (e.g. \"glabella,nasion\"; the names of `facehex segment "
              "--write-landmarks`)")
      .option("shape-relaxation",
              "after the mapping, move vertices along the patient towards the standard's cell shapes; where the "
              "mapping distorted a cell, its target moves this fraction of that distortion towards an ideal cell (0: "
              "the standard's own shapes); off: the paper's plain mapping",
              "1")
      .option("shape-tether",
              "with the shape relaxation: how strongly each vertex is held where the mapping put it (the registered "
              "skin's and the landmarks' correspondence): sliding one edge length along the patient costs this much "
              "of a corner's shape energy; 0: vertices slide freely towards the standard's shapes",
              "0.2");
  add_field_options(args);
  add_segment_options(args);
}

std::string default_edge_length_help() {
  const SegmentOptions defaults;
  std::ostringstream text;
  text << defaults.tets.target_edge_length << ", or a CT's coarsest voxel spacing up to " << kMostScanEdgeLength
       << ", or coarser for a CT whose model would have more than " << std::fixed << std::setprecision(0)
       << defaults.coarsen_above_tets << " tets";
  return text.str();
}

HarmonicFieldsOptions field_options(const Args& args) {
  HarmonicFieldsOptions o;
  o.orthogonality_iterations = args.integer("iterations", 0, 100);
  const std::string order = args.get("order");
  if (order.size() != 3 || std::set<char>(order.begin(), order.end()) != std::set<char>{'u', 'v', 'w'})
    throw UsageError("--order", "expects a permutation of u, v, w such as wuv, got '" + order + "'");
  for (int i = 0; i < 3; ++i) o.order[i] = order[i] - 'u';
  return o;
}

SegmentOptions segment_options(const Args& args) {
  SegmentOptions o;
  if (args.has("skin")) o.skin_threshold = args.number("skin");
  if (args.has("bone")) o.bone_threshold = args.number("bone");
  o.orientation.anterior = args.get("anterior");
  o.orientation.superior = args.get("superior");
  o.dicom_series = args.get("series");
  if (args.has("edge-length")) {
    o.tets.target_edge_length = args.number("edge-length", kLeastEdgeLength, kMostEdgeLength);
    o.coarsen_above_tets = 0;
    o.follow_scan_spacing = false;
  }
  const auto finite = [&](const std::string& name) {
    const double x = args.number(name);
    if (!std::isfinite(x))
      throw UsageError("--" + name, "expects a finite number of millimetres, got '" + args.get(name) + "'");
    return x;
  };
  const auto not_negative = [&](const std::string& name) {
    const double x = finite(name);
    if (x < 0) throw UsageError("--" + name, "expects a distance of 0 mm or more, got '" + args.get(name) + "'");
    return x;
  };
  FaceCutOptions& cuts = o.cuts;
  if (args.has("head-turn")) cuts.head_turn = args.number("head-turn", -45, 45);
  if (args.has("head-pitch")) cuts.head_pitch = args.number("head-pitch", -45, 45);
  if (args.has("top-cut")) cuts.top_z = finite("top-cut");
  if (args.has("bottom-cut")) cuts.bottom_z = finite("bottom-cut");
  if (args.has("posterior-cut")) cuts.posterior_y = finite("posterior-cut");
  if (args.has("mid-plane")) cuts.centre_x = finite("mid-plane");
  cuts.brow_clearance = not_negative("brow-clearance");
  cuts.chin_clearance = not_negative("chin-clearance");
  cuts.ear_clearance = not_negative("ear-clearance");
  o.min_thickness = not_negative("min-thickness");
  o.max_depth = not_negative("max-depth");
  if (o.max_depth == 0) throw UsageError("--max-depth", "expects a depth above 0 mm");
  o.bone_gap_radius = not_negative("bone-gap");
  o.cavity_closing_radius = not_negative("cavity-closing");
  o.smoothing_sigma = not_negative("smoothing");
  if (args.has("denoise")) o.denoising_blur = not_negative("denoise");
  o.find_skin_objects = on_or_off(args, "skin-objects");
  return o;
}

TransferOptions transfer_options(const Args& args) {
  TransferOptions o;
  o.fields = field_options(args);
  o.allow_inverted_parameterization = args.has("allow-inverted");
  const std::string correspondence = args.get("skin-correspondence");
  if (correspondence == "registered")
    o.skin_correspondence = SkinCorrespondence::registered;
  else if (correspondence == "features")
    o.skin_correspondence = SkinCorrespondence::features;
  else
    throw UsageError("--skin-correspondence", "expects registered or features, got '" + correspondence + "'");
  o.hold_registered_skin = args.has("hold-skin");
  o.pull_found_landmarks = on_or_off(args, "pull-found-landmarks");
  o.landmarks_not_pulled = split_commas(args.get("landmarks-not-pulled"));
  for (const std::string& name : o.landmarks_not_pulled)
    if (!is_landmark_name(name))
      throw UsageError("--landmarks-not-pulled",
                       "'" + name + "' is no landmark FaceHex knows (" + landmark_names_text() + ")");
  const std::string relaxation = args.get("shape-relaxation");
  o.shape_relaxation = relaxation != "off";
  if (o.shape_relaxation) {
    o.relaxation_towards_ideal = args.number("shape-relaxation");
    if (!(o.relaxation_towards_ideal >= 0 && o.relaxation_towards_ideal <= 1))
      throw UsageError("--shape-relaxation", "expects off or a fraction from 0 to 1, got '" + relaxation + "'");
  }
  o.relaxation_tether = args.number("shape-tether", 0, 1000);
  return o;
}

void check_transfer_options(const Args& args) {
  transfer_options(args);
  segment_options(args);
  find_standard(args.get("standard"));
  check_standard_domain_kind(args.get("standard-domain"));
}

StandardSetup standard_setup(const Args& args) {
  std::cerr << "reading the standard " << args.get("standard") << "\n";
  return load_standard(args.get("standard"), args.get("standard-constraints"), args.get("standard-domain"));
}

PatientTetModel read_patient_model(const std::string& path, const SegmentOptions& segment) {
  if (is_ct_input(path)) std::cerr << "segmenting the facial soft tissue from the CT " << path << "\n";
  TerminalProgress progress;
  PatientTetModel model = load_patient_model(path, segment, progress.callback());
  progress.finish();
  if (model.segmentation) print_segmentation(*model.segmentation);
  if (model.check.reoriented) std::cerr << "note: " << path << ": all tets were negatively oriented; flipped\n";
  return model;
}

PatientSetup cli_patient(const std::string& path, const SegmentOptions& segment, const std::string& constraints_file,
                         const ConstraintSet& standard_constraints, const std::string& constraints_hint,
                         const std::string& landmarks_file, bool features_required) {
  const std::map<std::string, double> values = feature_values(standard_constraints);
  PatientSetup p = setup_patient(read_patient_model(path, segment), path, constraints_file, &values, landmarks_file);
  const bool has_sides = p.domain.side_mask.size() > 0;
  if (!p.features_problem.empty() && (features_required || !has_sides || !landmarks_file.empty()))
    throw Error(landmarks_file.empty() ? path : landmarks_file,
                "the facial feature constraints cannot be placed (" + p.features_problem +
                    "); give the patient's landmarks with --landmarks FILE or its constraint set with " +
                    constraints_hint);
  std::cerr << p.constraints_note << "\n";
  if (!p.features_problem.empty())
    std::cerr << "note: the registered skin places the face without them; should it fail, give the landmarks with "
                 "--landmarks FILE\n";
  if (p.landmarks) std::cerr << landmarks_text(*p.landmarks, "  ");
  return p;
}

CliTransfer cli_transfer(const Args& args, const std::string& patient, const std::string& patient_constraints,
                         const std::string& constraints_hint, const std::string& landmarks_file) {
  const TransferOptions options = transfer_options(args);
  CliTransfer t;
  t.standard = standard_setup(args);
  std::cerr << "reading the patient " << patient << "\n";
  t.patient = cli_patient(patient, segment_options(args), patient_constraints, t.standard.constraints, constraints_hint,
                          landmarks_file, options.skin_correspondence == SkinCorrespondence::features);
  TerminalProgress progress;
  t.result = transfer(t.standard, t.patient, options, progress.callback());
  progress.finish();
  if (!t.result.patient_openings.empty())
    std::cerr << "note: the patient model's " << t.result.patient_openings << " as the standard's are\n";
  if (!t.result.cache_note.empty())
    std::cerr << "note: " << t.result.cache_note << "; the standard's parameterization was computed instead (expected "
              << "with --standard-domain, --standard-constraints, --iterations or --order; after editing a bundled "
              << "standard, refresh it with facehex standards --write-cache)\n";
  return t;
}

}  // namespace facehex::cli

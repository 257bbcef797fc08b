#include "core/evaluation/correspondence_benchmark.h"

#include <unistd.h>

#include <Eigen/QR>
#include <algorithm>
#include <filesystem>

#include "core/evaluation/standard_remesh.h"
#include "core/evaluation/warp_volume.h"
#include "core/face/automatic_constraints.h"
#include "core/face/face_landmarks.h"
#include "core/io/mesh_io.h"
#include "core/mesh/ct_landmarks.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/mesh/sides.h"
#include "core/mesh/skin_points.h"
#include "core/quality/hex_quality.h"
#include "core/quality/surface_distance.h"
#include "core/segment/ct_volume.h"
#include "core/standard/standard_features.h"
#include "core/util/error.h"
#include "core/util/stopwatch.h"
#include "core/workflow/transfer.h"

namespace facehex {
namespace {

namespace fs = std::filesystem;

// A CT warp's ramp (mm) from its flat end slices to the full warp (smooth_warp.h), and the smallest det J a warp may
// have about the patient (the CT's head, a model's box).
constexpr double kCtEndRamp = 30.0;
constexpr double kMinWarpJacobian = 0.2;

// Rows of V whose side mask has the skin's bit.
Eigen::MatrixXd skin_side_points(const VolumeMesh& mesh) {
  const Eigen::VectorXi mask = side_mask_of(mesh);
  std::vector<int> rows;
  for (int v = 0; v < mask.size(); ++v)
    if (mask(v) & side_bit(W1)) rows.push_back(v);
  Eigen::MatrixXd P(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t i = 0; i < rows.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = mesh.V.row(rows[i]);
  return P;
}

// The chin: the most anterior skin point within 10 mm of the mid-sagittal plane 12-45 mm below the lower lip.
Eigen::Vector3d chin_point(const Eigen::MatrixXd& skin, const FaceLandmarks& lm) {
  const double lip_z = lm.points.at("labrale inferius").z();
  Eigen::Vector3d best = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  for (Eigen::Index i = 0; i < skin.rows(); ++i) {
    const Eigen::Vector3d p = skin.row(i).transpose();
    if (std::abs(p.x() - lm.plane.x) <= 10 && p.z() <= lip_z - 12 && p.z() >= lip_z - 45 && !(p.y() <= best.y()))
      best = p;
  }
  if (!std::isfinite(best.y())) throw Error("landmarks", "no chin found below the lower lip of the face");
  return best;
}

// A patient model moved by a warp, with what its segmentation read in the CT moved with it, as a warped CT's would be
// read: the landmarks (core/mesh/ct_landmarks.h) and the skin's points (core/mesh/skin_points.h) moved, the
// mid-sagittal plane (core/mesh/mid_sagittal_plane.h) the least-squares plane through its points over the model's
// extent moved. Objects on the skin, stored as a profile in the model's head frame, are not moved: a model that has
// them is refused.
VolumeMesh warped_patient_model(VolumeMesh mesh, const SmoothWarp& warp, const std::string& source) {
  if (std::optional<MidSagittalPlane> plane = mid_sagittal_plane(mesh, source)) {
    const Eigen::Vector3d lower = mesh.V.colwise().minCoeff().transpose(),
                          upper = mesh.V.colwise().maxCoeff().transpose();
    constexpr int kSamples = 11;  // per axis
    Eigen::MatrixXd A(kSamples * kSamples, 3);
    Eigen::VectorXd x(kSamples * kSamples);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> moved;
    for (int a = 0; a < kSamples; ++a)
      for (int b = 0; b < kSamples; ++b) {
        const double y = lower.y() + (upper.y() - lower.y()) * a / (kSamples - 1);
        const double z = lower.z() + (upper.z() - lower.z()) * b / (kSamples - 1);
        moved.push_back(warp.apply(Eigen::Vector3d(plane->x_at(y, z), y, z)));
        mean += moved.back() / static_cast<double>(kSamples * kSamples);
      }
    for (size_t i = 0; i < moved.size(); ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      A.row(row) << 1, moved[i].z() - mean.z(), moved[i].y() - mean.y();
      x(row) = moved[i].x();
    }
    const Eigen::Vector3d fit = A.colPivHouseholderQr().solve(x);
    plane->x = fit(0), plane->slope = fit(1), plane->turn = fit(2), plane->z = mean.z(), plane->y = mean.y();
    set_mid_sagittal_plane(mesh, *plane);
  }
  if (std::optional<Eigen::MatrixXd> points = skin_points(mesh, source))
    set_skin_points(mesh, warp.apply_rows(*points));
  mesh.V = warp.apply_rows(mesh.V);
  if (std::optional<CtLandmarks> carried = ct_landmarks(mesh, source)) {
    if (!carried->skin_objects.empty())
      throw Error(source, "a model with objects on its skin (a strap, tape) cannot be warped for the benchmark");
    const auto move = [&](std::optional<CtLandmark>& l) {
      if (l) l->point = warp.apply(l->point);
    };
    for (auto& l : carried->tragi) move(l);
    for (auto& l : carried->eye_corners) move(l);
    for (auto& l : carried->mouth_corners) move(l);
    move(carried->stomion);
    move(carried->bony_menton);
    set_ct_landmarks(mesh, *carried);
  }
  return mesh;
}

// The landmarks moved by a warp (their plane as it was).
FaceLandmarks warped_landmarks(FaceLandmarks landmarks, const SmoothWarp& warp) {
  for (auto& [name, point] : landmarks.points) point = warp.apply(point);
  return landmarks;
}

// The patient's feature constraints at `landmarks`, which the registered transfer takes as given pairs: the transfer
// then sees the true landmarks instead of those found on the model (CorrespondenceOptions::true_landmarks).
void give_landmarks(PatientSetup& patient, FaceLandmarks landmarks, const std::map<std::string, double>& values) {
  patient.constraints = side_constraints();
  for (const Constraint& c : feature_constraints(landmarks, values, kFeatureBand).constraints)
    patient.constraints.constraints.push_back(c);
  patient.features_problem.clear();
  landmarks.given = true;
  patient.landmarks = std::move(landmarks);
}

// A warped patient (--true-landmarks) given its original's landmarks moved by the warp, on its own mid-sagittal plane
// where it has one (a warp bends a plane). `whose` names the original for the error when it has none.
void give_moved_landmarks(PatientSetup& warped, const PatientSetup& original, const SmoothWarp& warp,
                          const std::string& whose, const std::map<std::string, double>& values) {
  if (!original.landmarks)
    throw Error("benchmark", "--true-landmarks needs the landmarks of " + whose + ", and none were found (" +
                                 original.features_problem + ")");
  FaceLandmarks moved = warped_landmarks(*original.landmarks, warp);
  if (warped.landmarks) moved.plane = warped.landmarks->plane;
  give_landmarks(warped, std::move(moved), values);
}

// One transfer through the workflow and its errors against `truth`.
CorrespondenceCaseResult measure(const StandardSetup& standard, const PatientSetup& patient,
                                 const Eigen::MatrixXd& truth, const std::vector<VertexRegion>& regions,
                                 const CorrespondenceBenchmarkOptions& options, const ProgressCallback& progress,
                                 TransferResult* kept = nullptr) {
  CorrespondenceCaseResult r;
  if (options.transfer.skin_correspondence == SkinCorrespondence::features && !patient.features_problem.empty())
    throw Error(patient.path, "the facial feature constraints cannot be placed (" + patient.features_problem + ")");
  Stopwatch clock;
  TransferOptions measuring = options.transfer;
  measuring.allow_inverted_parameterization = true;
  TransferResult t = transfer(standard, patient, measuring, progress);
  r.seconds = clock.lap();
  r.patient_tets = patient.mesh.num_cells();
  r.vertex_error = vertex_errors(t.patient_hex.V, truth);
  r.error = correspondence_error(r.vertex_error, regions);
  r.mapping_error = correspondence_error(vertex_errors(t.run.mapped_hex.V, truth), regions);
  r.skin_split = skin_error_split(standard.mesh, t.patient_hex.V, truth);
  const DistanceSummary moved = summarize_distances(moved_from_mapping(t.run));
  r.moved_by_relaxation_mean = moved.mean;
  r.moved_by_relaxation_max = moved.max;
  r.inverted = t.patient_quality.summary.inverted + t.patient_quality.summary.degenerate;
  r.inverted_after_mapping = t.plain_mapping_quality.summary.inverted + t.plain_mapping_quality.summary.degenerate;
  for (const char* stage : {"shape_relaxation", "untangle"})
    if (t.run.seconds.count(stage)) r.shape_solver_seconds += t.run.seconds.at(stage);
  r.folded_parametric_tets = t.run.patient.health.inverted + t.run.patient.health.degenerate;
  r.shape_mean = t.patient_quality.summary.shape_mean;
  r.standard_shape_mean = t.standard_quality.summary.shape_mean;
  VolumeMesh landed = t.patient_hex;
  landed.V = truth;
  r.truth_shape_mean = summarize(landed, element_quality(landed)).shape_mean;
  r.dihedral_change_mean = t.patient_quality.distortion.mean_deg;
  r.registered_skin = t.registration.has_value();
  r.registered_failure = t.registered_failure;
  if (kept) *kept = std::move(t);
  return r;
}

// The standard's landmarks as its own constraint set places its features (each feature plane's point is its
// landmark), so that "true landmarks" put a model's features where the standard's are, whatever the finder does; the
// finder's points where the set has no such plane (standard_features.h: the corners of its open eyes and mouth at
// their rims' ends).
FaceLandmarks standard_feature_landmarks(const StandardSetup& standard) {
  FaceLandmarks l = standard_features(standard.mesh).landmarks;
  for (const FeatureSpec& spec : feature_specs())
    for (const Constraint& c : standard.constraints.constraints)
      if (c.name == spec.name && c.select.plane) {
        if (spec.field == 0)
          l.plane.x = c.select.plane->point.x();
        else
          l.points[spec.landmark] = c.select.plane->point;
      }
  return l;
}

// How far each landmark found on `patient` lies from the same landmark of `reference` moved by `warp`
// (CorrespondenceCaseResult::landmark_shift), or why none were found (landmarks_problem).
void measure_landmark_shifts(const FaceLandmarks& reference, const PatientSetup& patient, const SmoothWarp& warp,
                             CorrespondenceCaseResult& r) {
  if (!patient.landmarks) {
    r.landmarks_problem = patient.features_problem;
    return;
  }
  for (const auto& [name, point] : reference.points) {
    const auto found = patient.landmarks->points.find(name);
    if (found != patient.landmarks->points.end()) r.landmark_shift[name] = (found->second - warp.apply(point)).norm();
  }
}

// The CT case's input shifts (CorrespondenceCaseResult::landmark_shift, cut_shift).
void measure_input_shifts(const PatientSetup& original, const PatientSetup& warped, const SmoothWarp& warp,
                          CorrespondenceCaseResult& r) {
  // Landmarks given to the warped CT (the original's moved by the warp) were not found there: nothing to compare.
  const bool given = warped.landmarks && warped.landmarks->given;
  if (original.landmarks && !given)
    measure_landmark_shifts(*original.landmarks, warped, warp, r);
  else if (!warped.landmarks)
    r.landmarks_problem = warped.features_problem;
  if (!original.segmentation || !warped.segmentation || !original.landmarks) return;
  const FaceCuts &a = original.segmentation->cuts, &b = warped.segmentation->cuts;
  const auto& points = original.landmarks->points;
  auto where = points.find("nasion");
  if (where == points.end()) where = points.find("pronasale");
  if (where == points.end()) return;
  const Eigen::Vector3d at = a.turn.to_head(where->second);
  // Each cut: the axis it is a plane of constant value along (in its CT's head frame), the original's and the warped
  // CT's values.
  const std::vector<std::tuple<std::string, int, double, double>> cuts = {
      {"top", 2, a.top_z, b.top_z},
      {"bottom", 2, a.bottom_z, b.bottom_z},
      {"posterior", 1, a.posterior_y, b.posterior_y},
      {"mid-sagittal", 0, a.centre_x, b.centre_x}};
  for (const auto& [name, axis, original_value, warped_value] : cuts) {
    Eigen::Vector3d on_cut = at;
    on_cut(axis) = original_value;
    r.cut_shift[name] = warped_value - b.turn.to_head(warp.apply(a.turn.to_model(on_cut)))(axis);
  }
}

}  // namespace

SmoothWarp face_warp(const std::string& name, const VolumeMesh& face) {
  const Eigen::MatrixXd skin = skin_side_points(face);
  const Eigen::Vector3d centre = face.V.colwise().mean().transpose();
  if (name.rfind("random-", 0) == 0) {
    std::uint64_t seed = 0;
    try {
      seed = std::stoull(name.substr(7));
    } catch (const std::exception&) {
      throw Error("--warps", "expects random-SEED with a whole number SEED, got '" + name + "'");
    }
    return random_warp(seed, centre, skin);
  }
  if (name == "chin" || name == "nose") {
    const FaceLandmarks lm = find_face_landmarks(face.V, side_mask_of(face));
    if (name == "chin") return local_warp(chin_point(skin, lm), Eigen::Vector3d(0, 8, 0), 20.0);
    const Eigen::Vector3d tip = lm.points.at("pronasale"), root = lm.points.at("nasion");
    return local_warp(tip, 0.2 * (tip - root), 15.0);
  }
  throw Error("--warps", "expects random-SEED, chin or nose, got '" + name + "'");
}

bool is_standard_model_name(const std::string& name) {
  return name == "split" || name.rfind("open-", 0) == 0 || name.rfind("closed-", 0) == 0;
}

VolumeMesh standard_model(const std::string& name, const VolumeMesh& standard) {
  if (name == "split") return split_hex_model(standard);
  for (const bool closed : {false, true}) {
    const std::string prefix = closed ? "closed-" : "open-";
    if (name.rfind(prefix, 0) != 0) continue;
    double edge = 0;
    try {
      edge = std::stod(name.substr(prefix.size()));
    } catch (const std::exception&) {
    }
    if (!(edge > 0)) throw Error("--models", "expects an edge length in mm after '" + prefix + "', got '" + name + "'");
    return tetgen_remesh(standard, closed, edge);
  }
  throw Error("--models", "expects split, open-E or closed-E (E: edge length in mm), got '" + name + "'");
}

std::vector<CorrespondenceCaseResult> run_correspondence_benchmark(const StandardSetup& standard,
                                                                   const CorrespondenceBenchmarkOptions& options,
                                                                   const CaseCallback& on_case,
                                                                   const ProgressCallback& progress,
                                                                   const ResultCallback& on_result) {
  const std::vector<VertexRegion> regions = correspondence_regions(standard.mesh);
  const std::map<std::string, double> values = feature_values(standard.constraints);
  const FaceLandmarks standard_landmarks = standard_feature_landmarks(standard);
  std::vector<std::pair<std::string, SmoothWarp>> warps;
  for (const std::string& w : options.warps) warps.emplace_back(w, face_warp(w, standard.mesh));

  struct Planned {
    std::string kind, name, model, warp;  // model/warp: names; CT cases: model = the file
    int ct_seed = -1;                     // -1: the CT as it is
  };
  std::vector<Planned> plan;
  if (options.self_maps)
    for (const std::string& m : options.models) plan.push_back({"self-map", m, m, ""});
  for (const std::string& m : options.deformation_models)
    if (!is_standard_model_name(m) && !fs::is_regular_file(m))
      throw Error("--deformation-models",
                  "expects split, open-E, closed-E (E: edge length in mm) or a patient's tet "
                  "model file, got '" +
                      m + "' (no such file)");
  for (const auto& [w, warp] : warps)
    for (const std::string& m : options.deformation_models)
      plan.push_back({"deformation", w + " on " + (is_standard_model_name(m) ? m : fs::path(m).stem().string()), m, w});
  for (const std::string& ct : options.cts) {
    const std::string stem = fs::path(ct).filename().string();
    for (const std::uint64_t seed : options.ct_seeds)
      plan.push_back({"ct", stem + " warp " + std::to_string(seed), ct, "", static_cast<int>(seed)});
  }

  std::map<std::string, VolumeMesh> models;  // made once, warped per case
  const auto model = [&](const std::string& name) -> const VolumeMesh& {
    auto it = models.find(name);
    if (it == models.end()) it = models.emplace(name, standard_model(name, standard.mesh)).first;
    return it->second;
  };
  // Per CT file and per patient model file: the patient as it is and its transfer, the truth's basis.
  std::map<std::string, std::pair<PatientSetup, TransferResult>> ct_originals, model_originals;
  const auto kept_model = [&](const Planned& p, const VolumeMesh& mesh) {
    if (options.keep_patients.empty()) return;
    std::string file = p.kind + "-" + p.name;
    std::replace(file.begin(), file.end(), ' ', '-');
    write_volume_mesh((fs::path(options.keep_patients) / (file + ".vtu")).string(), mesh);
  };

  std::vector<CorrespondenceCaseResult> results;
  for (size_t i = 0; i < plan.size(); ++i) {
    const Planned& p = plan[i];
    if (on_case) on_case(static_cast<int>(i), static_cast<int>(plan.size()), p.kind + ": " + p.name);
    CorrespondenceCaseResult r;
    try {
      if (p.kind == "deformation" && !is_standard_model_name(p.model)) {
        Stopwatch clock;
        if (!model_originals.count(p.model)) {
          PatientSetup setup = patient_from_mesh(read_volume_mesh(p.model), p.model, &values);
          TransferResult t;
          measure(standard, setup, standard.mesh.V, regions, options, progress, &t);
          model_originals.emplace(p.model, std::make_pair(std::move(setup), std::move(t)));
        }
        const PatientSetup& original_setup = model_originals.at(p.model).first;
        const Eigen::MatrixXd& original = model_originals.at(p.model).second.patient_hex.V;
        const SmoothWarp warp = face_warp(p.warp, original_setup.mesh);
        const Eigen::Vector3d lower = original_setup.mesh.V.colwise().minCoeff().transpose(),
                              upper = original_setup.mesh.V.colwise().maxCoeff().transpose();
        if (min_jacobian_determinant(warp, lower, upper, 41) <= kMinWarpJacobian)
          throw Error("benchmark", p.name + ": the warp " + warp_description(warp) +
                                       " is not safely invertible about the model; choose another warp");
        VolumeMesh mesh = warped_patient_model(original_setup.mesh, warp, p.model);
        kept_model(p, mesh);
        PatientSetup patient = patient_from_mesh(std::move(mesh), p.kind + " " + p.name, &values);
        if (options.true_landmarks)
          give_moved_landmarks(patient, original_setup, warp, fs::path(p.model).filename().string() + " as it is",
                               values);
        const Eigen::MatrixXd truth = warp.apply_rows(original);
        r = measure(standard, patient, truth, regions, options, progress);
        if (!options.true_landmarks && original_setup.landmarks)
          measure_landmark_shifts(*original_setup.landmarks, patient, warp, r);
        r.seconds = clock.lap();
        r.warp_mean = (truth - original).rowwise().norm().mean();
        r.warp = warp_description(warp);
        r.model = p.model;
      } else if (p.kind != "ct") {
        VolumeMesh mesh = model(p.model);
        SmoothWarp warp;  // identity
        for (const auto& [w, candidate] : warps)
          if (w == p.warp) warp = candidate;
        mesh.V = warp.apply_rows(mesh.V);
        kept_model(p, mesh);
        const Eigen::MatrixXd truth = warp.apply_rows(standard.mesh.V);
        PatientSetup patient = patient_from_mesh(std::move(mesh), p.kind + " " + p.name, &values);
        if (options.true_landmarks) {
          FaceLandmarks moved = warped_landmarks(standard_landmarks, warp);
          moved.plane.x = warp.apply(Eigen::Vector3d(standard_landmarks.plane.x, 0, 0)).x();
          give_landmarks(patient, std::move(moved), values);
        }
        r = measure(standard, patient, truth, regions, options, progress);
        if (!options.true_landmarks) measure_landmark_shifts(standard_landmarks, patient, warp, r);
        r.warp_mean = (truth - standard.mesh.V).rowwise().norm().mean();
        if (!p.warp.empty()) r.warp = warp_description(warp);
        r.model = p.model;
      } else {
        Stopwatch clock;
        if (!ct_originals.count(p.model)) {
          PatientSetup setup = load_patient(p.model, options.segment, "", &values, progress);
          TransferResult t;
          measure(standard, setup, standard.mesh.V, regions, options, progress, &t);
          setup.mesh = VolumeMesh();  // only its landmarks and cuts are kept
          setup.domain = TetDomain();
          ct_originals.emplace(p.model, std::make_pair(std::move(setup), std::move(t)));
        }
        const PatientSetup& original_setup = ct_originals.at(p.model).first;
        const TransferResult& original = ct_originals.at(p.model).second;
        const CtVolume ct = read_ct_volume(p.model);
        // The scan's first and last slices stay flat: where a field of view ends is no anatomy, and a transfer
        // cannot follow a warp that bends them (the face region found ends at the scan's end slices). A pitch tilts
        // them, as pitching the head in the scanner would, and a pitched warp keeps them tilted: flattened within a
        // ramp, a pitch of a few degrees across the whole scan folds it.
        const GridGeometry& grid = ct.intensity.geometry;
        const CtWarpFrame frame = ct_warp_frame(ct.intensity);
        SmoothWarp warp =
            random_warp(static_cast<std::uint64_t>(p.ct_seed), frame.centre, frame.anchors, options.ct_ranges);
        if (!warp.tilts_slices()) warp = warp.with_flat_levels(grid.lower(2), grid.upper(2), kCtEndRamp);
        // Checked where the head is (the original's face region and the ramp's length around it, within the scan): a
        // wide scan's far corners, all air, may fold in the ramps, where the slices' tilt grows with the distance.
        const Eigen::Vector3d scan_lower(grid.lower(0), grid.lower(1), grid.lower(2)),
            scan_upper(grid.upper(0), grid.upper(1), grid.upper(2));
        const Eigen::Vector3d head_lower =
            (original.patient_hex.V.colwise().minCoeff().transpose().array() - kCtEndRamp).max(scan_lower.array());
        const Eigen::Vector3d head_upper =
            (original.patient_hex.V.colwise().maxCoeff().transpose().array() + kCtEndRamp).min(scan_upper.array());
        if (min_jacobian_determinant(warp, head_lower, head_upper, 41) <= kMinWarpJacobian)
          throw Error("benchmark", p.name + ": the warp " + warp_description(warp) +
                                       " is not safely invertible about the head; choose other --ct-ranges");
        r.warp = warp_description(warp);
        const bool keep = !options.keep_patients.empty();
        const fs::path file =
            keep ? fs::path(options.keep_patients) /
                       (fs::path(p.model).stem().string() + "-warp-" + std::to_string(p.ct_seed) + ".mha")
                 : fs::temp_directory_path() /
                       ("facehex-correspondence-" + std::to_string(::getpid()) + "-" + std::to_string(i) + ".mha");
        write_ct_volume(file.string(), CtVolume{warp_volume(ct.intensity, warp), ct.source + " (warped)"});
        PatientSetup warped;
        try {
          warped = load_patient(file.string(), options.segment, "", &values, progress);
        } catch (...) {
          if (!keep) fs::remove(file);
          throw;
        }
        if (!keep) fs::remove(file);
        if (options.true_landmarks)
          give_moved_landmarks(warped, original_setup, warp, fs::path(p.model).filename().string() + " as it is",
                               values);
        const Eigen::MatrixXd truth = warp.apply_rows(original.patient_hex.V);
        r = measure(standard, warped, truth, regions, options, progress);
        measure_input_shifts(original_setup, warped, warp, r);
        r.seconds = clock.lap();
        r.warp_mean = (truth - original.patient_hex.V).rowwise().norm().mean();
        r.warp = warp_description(warp);
        r.model = p.model;
      }
    } catch (const Error& e) {
      r.failure = e.what();
    }
    r.kind = p.kind;
    r.name = p.name;
    if (on_result) on_result(r);
    results.push_back(std::move(r));
  }
  return results;
}

}  // namespace facehex

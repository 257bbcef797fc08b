#pragma once
// Known-answer transfers of a standard, run through the workflow (core/workflow/transfer.h) as `facehex run` runs
// them, and how far each vertex landed from where it should:
//  - self-map: the standard onto tet models of its own volume (standard_remesh.h); the answer is the identity;
//  - deformation: the same models under smooth invertible warps (smooth_warp.h) with known seeds, plus a chin moved
//    forward and a longer nose; the answer is the warped standard. Also on a patient's tet model (a segmented CT's,
//    whose mouth and eyes are a real face's): the answer is the warp applied to the transfer onto the model as it is;
//  - CT equivariance: a CT and warped copies of it (warp_volume.h), drawn about the CT's own face-on skin
//    (ct_warp_frame: the same warps whatever the code under test finds), whose first and last slices stay flat
//    (where a scan ends is no anatomy); the answer is the warp applied to the original CT's result (segmentation
//    noise included).
// Each patient is constrained by the workflow's one policy (patient_from_mesh / load_patient: its sides and the
// facial features at its landmarks).
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/evaluation/correspondence_error.h"
#include "core/evaluation/smooth_warp.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/segment/soft_tissue.h"
#include "core/workflow/standard_setup.h"

namespace facehex {

struct CorrespondenceBenchmarkOptions {
  // allow_inverted_parameterization is set by the benchmark: a patient whose fields fold is measured (and its folded
  // parametric tets counted) rather than refused.
  TransferOptions transfer;
  SegmentOptions segment;  // for the CTs
  // Tet models of the standard's volume by name: "split" (hexes split, openings open), "open-E" and "closed-E"
  // (TetGen re-meshes at E mm of the open and of the closed volume).
  std::vector<std::string> models = {"split", "open-3", "closed-3"};
  // The self-maps run on every model; each warp runs on each of deformation_models: models of the standard by name,
  // or patients' tet model files (with side labels, as `facehex run` takes them), whose warps are drawn about their
  // own skin and landmarks (face_warp) and whose answer is the warp applied to the transfer onto the model as it is.
  bool self_maps = true;
  std::vector<std::string> deformation_models = {"closed-3"};
  // Warps by name: "random-SEED" (random_warp with the default ranges), "chin" (the chin moved 8 mm forward), "nose"
  // (the nose tip moved along the nasion-pronasale line by 20 % of that length).
  std::vector<std::string> warps = {"random-1", "random-2", "chin", "nose"};
  // Place a self-map's or deformation's feature constraints at the standard's landmarks moved by the warp, and a
  // warped CT's at the original CT's landmarks moved by the warp, instead of at the landmarks found on the model:
  // separates the landmark finder's error from the rest.
  bool true_landmarks = false;
  // CT files; each runs once as it is and once under each CT warp seed (ct_ranges).
  std::vector<std::string> cts;
  std::vector<std::uint64_t> ct_seeds = {1, 2};
  RandomWarpRanges ct_ranges = {0.08, 0.04, 4, 4.0, 25.0, 40.0};
  // When set, each case's patient is kept in this folder to rerun or inspect it by hand: a self-map's or deformation's
  // tet model as KIND-CASE.vtu (spaces as '-', e.g. deformation-nose-on-closed-3.vtu), a warped CT as
  // STEM-warp-SEED.mha; otherwise a warped CT is a temporary file.
  std::string keep_patients;
};

struct CorrespondenceCaseResult {
  std::string kind;     // "self-map", "deformation", "ct"
  std::string name;     // e.g. "nose on closed-3"
  std::string model;    // the patient model's description
  std::string warp;     // warp_description, or empty
  std::string failure;  // the error that stopped this case, or empty
  int patient_tets = 0;
  CorrespondenceError error;          // of the result
  CorrespondenceError mapping_error;  // of the plain mapping, before relaxation and repair
  SkinErrorSplit skin_split;          // of the result, across and along the true skin
  Eigen::VectorXd vertex_error;       // #Vs, mm, of the result
  double warp_mean = 0;               // mm the warp moves the standard's vertices (the error of doing nothing)
  double moved_by_relaxation_mean = 0, moved_by_relaxation_max = 0;  // mm, relaxation and repair together
  int inverted = 0;                                                  // inverted or degenerate cells of the result
  int inverted_after_mapping = 0;  // inverted or degenerate cells of the plain mapping, which the shape solver takes
  int folded_parametric_tets = 0;  // the patient's parametric tets inverted or degenerate (param_health.h)
  double shape_mean = 0, standard_shape_mean = 0, dihedral_change_mean = 0;
  // The mean shape of the standard's cells at the true positions: what a transfer that lands exactly would have (the
  // standard's own on a self-map; a warp changes it).
  double truth_shape_mean = 0;
  double seconds = 0;               // the transfer (and the CT's segmentation)
  double shape_solver_seconds = 0;  // of which the shape relaxation and the repair
  // How far the landmark finder's points, a transfer's input, lie from where they should: on a self-map or a
  // deformation (without true_landmarks), from the standard's own landmarks (those its constraint set places its
  // features at) moved by the warp; on a CT case, from the warp of what the finder found on the original. Per
  // landmark found on both: the distance (mm). CT cases also compare the segmentation's cuts: per cut
  // ("top", "bottom", "posterior", "mid-sagittal"): the warped CT's plane minus the warp of the original's, along its
  // normal (mm, signed; each plane in its CT's head frame, core/mesh/head_turn.h), at the original's nasion (the
  // pronasale when there is none) moved onto that plane.
  std::map<std::string, double> landmark_shift, cut_shift;
  std::string landmarks_problem;   // why no landmarks were found on the model (empty when they were, or were given)
  bool registered_skin = false;    // the transfer used the registered skin
  std::string registered_failure;  // why it used the feature lines though the registered skin was asked for
};

// Which case is next (index of count) and its name, before it runs; `progress` hears of its stages; `on_result`
// gets each case's result as it is measured.
using CaseCallback = std::function<void(int index, int count, const std::string& name)>;
using ResultCallback = std::function<void(const CorrespondenceCaseResult& result)>;

// Runs every case; a case that throws facehex::Error is recorded with its failure and the others run on. Throws
// facehex::Error for an unknown model or warp name and when the standard's landmarks cannot be found.
std::vector<CorrespondenceCaseResult> run_correspondence_benchmark(const StandardSetup& standard,
                                                                   const CorrespondenceBenchmarkOptions& options,
                                                                   const CaseCallback& on_case = {},
                                                                   const ProgressCallback& progress = {},
                                                                   const ResultCallback& on_result = {});

// The named warp of CorrespondenceBenchmarkOptions::warps for a face model with side labels (the standard, or a
// patient's tet model), drawn about its own skin and landmarks. Throws facehex::Error("--warps", ...) for a name it
// does not know.
SmoothWarp face_warp(const std::string& name, const VolumeMesh& face);

// The named model of CorrespondenceBenchmarkOptions::models. Throws facehex::Error("--models", ...) otherwise.
VolumeMesh standard_model(const std::string& name, const VolumeMesh& standard);

}  // namespace facehex

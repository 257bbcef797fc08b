#pragma once
// The options of the commands that transfer (run, map, compare, bench) and the CLI's side of a transfer: the
// workflow of core/workflow/ with its notes and progress on the terminal.
#include <string>

#include "app/cli_args.h"
#include "core/workflow/transfer.h"

namespace facehex::cli {

// What --edge-length is when not given, for the help of run, map, compare, bench and segment (from SegmentOptions).
std::string default_edge_length_help();
// The range --edge-length accepts (mm): below it a head has tens of millions of tets, above it no face is left.
constexpr double kLeastEdgeLength = 0.5, kMostEdgeLength = 50;

// --iterations, --order.
void add_field_options(Args& args);
// --skin, --bone, --anterior, --superior, the cut planes and their automatic distances.
void add_segment_options(Args& args);
// --standard, --standard-constraints, --standard-domain, --edge-length, --allow-inverted, --skin-correspondence,
// --shape-relaxation, and
// the field and segmentation options.
void add_transfer_options(Args& args);

HarmonicFieldsOptions field_options(const Args& args);
// Throws facehex::Error naming the option for a non-finite cut, a negative distance or a zero face height.
SegmentOptions segment_options(const Args& args);
TransferOptions transfer_options(const Args& args);
StandardSetup standard_setup(const Args& args);
// Parses every transfer option and finds the standard, so that a bad option fails before any output is made.
void check_transfer_options(const Args& args);

// The patient model of `path` (core/segment/patient_input.h), a CT segmented with its steps on the terminal, its
// segmentation and a reorientation noted on stderr.
PatientTetModel read_patient_model(const std::string& path, const SegmentOptions& segment);

// The patient of `path` (a CT segmented with its steps on the terminal) with its constraints (core/workflow/
// patient_setup.h: `constraints_file`, else a file beside a mesh, else automatic), the choice and the landmarks
// printed on stderr. Without a constraint file the facial features are required when `features_required` (the
// feature lines place the face: without them the standard's eyes, nose and mouth land anywhere), for a model without
// side labels and when the user's landmark file is wrong: then a model where they cannot be found is an error naming
// the option that helps, `constraints_hint` (e.g. "--constraints FILE"). Otherwise (the registered skin places the
// face) it is a note, and the transfer says so if the registered skin fails too.
PatientSetup cli_patient(const std::string& path, const SegmentOptions& segment, const std::string& constraints_file,
                         const ConstraintSet& standard_constraints, const std::string& constraints_hint,
                         const std::string& landmarks_file = "", bool features_required = true);

struct CliTransfer {
  StandardSetup standard;
  PatientSetup patient;
  TransferResult result;
};

// The whole transfer as run, map, compare and bench do it (options parsed by add_transfer_options);
// `constraints_hint`: how the command takes a patient's constraint set, for the error of cli_patient;
// `landmarks_file`: the user's landmarks to place the feature constraints at (core/face/landmark_file.h), or empty.
CliTransfer cli_transfer(const Args& args, const std::string& patient, const std::string& patient_constraints,
                         const std::string& constraints_hint, const std::string& landmarks_file = "");

}  // namespace facehex::cli

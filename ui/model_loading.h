#pragma once
// Models from files, with the core calls the CLI makes (read or segment, check and orient, parameterization domain,
// constraint set). Run on the controller's worker thread; every failure is a facehex::Error naming the file.
#include <map>
#include <string>

#include "core/util/progress.h"
#include "ui/session_model.h"

namespace facehex::gui {

// A patient: a head CT (segmented with `segment_options`, default the CLI's; `progress` hears of it), a tet model or a
// closed surface (core/segment/patient_input.h). Its constraints: NAME.json beside it, else constraints.json in its
// folder (the bundled patients' layout); else, when it has side labels, those `facehex run` places
// (core/automatic_constraints.h): the six sides and the facial features valued by `feature_values` (the standard's), or
// the six sides alone when the features cannot be placed; else none. `constraints_note` says which, and why no
// features, for the status bar.
LoadedModel load_patient(const std::string& path, const SegmentOptions& segment_options,
                         const std::map<std::string, double>& feature_values, const ProgressCallback& progress,
                         QString& constraints_note);

// A bundled standard by name, or a hex-dominant mesh file (constraints found as in core/resources.h), on the CLI's
// default parameterization domain (closed_domain: its openings filled).
LoadedModel load_standard(const std::string& name_or_path);

// The bundled sample patient (constrained as load_patient does); while none is bundled, the synthetic face-like shell
// of core/synthetic_shell.h (tetrahedralized, sides labelled, constrained likewise).
LoadedModel demo_patient(const std::map<std::string, double>& feature_values, QString& constraints_note);

}  // namespace facehex::gui

#pragma once
// Models for the session, from the workflow both front ends share (core/workflow/): the patient and the standard set
// up as `facehex run` sets them up, and back from the session's edited models to the workflow's inputs. Loading runs
// on the controller's worker thread; every failure is a facehex::Error naming the file.
#include <map>
#include <string>

#include "core/util/progress.h"
#include "core/workflow/patient_setup.h"
#include "core/workflow/standard_setup.h"
#include "ui/session_model.h"

namespace facehex::gui {

// A patient: a head CT (segmented with `segment_options`; `progress` hears of it), a tet model or a closed surface,
// constrained by the workflow's policy (core/workflow/patient_setup.h) with the standard's `feature_values` (none:
// only the six sides). `constraints_note` says which constraints, and why no features, for the status bar.
LoadedModel load_patient(const std::string& path, const SegmentOptions& segment_options,
                         const std::map<std::string, double>* feature_values, const ProgressCallback& progress,
                         QString& constraints_note);

// A bundled standard by name, or a hex-dominant mesh file, on the workflow's default domain (its openings filled).
LoadedModel load_standard(const std::string& name_or_path);

// The bundled sample patient (constrained as load_patient does); while none is bundled, the synthetic face-like shell
// of core/workflow/patient_setup.h.
LoadedModel demo_patient(const std::map<std::string, double>* feature_values, QString& constraints_note);

// The workflow's inputs from the session's models as edited.
StandardSetup standard_setup(const LoadedModel& standard);
PatientSetup patient_setup(const LoadedModel& patient);

}  // namespace facehex::gui

#pragma once
// The main states of a session, reached by script the way a user reaches them (move the plane widget, compute,
// transfer, pick a display), for `facehex-gui --screenshot` and the GUI tests.
#include <QString>
#include <QStringList>
#include <optional>

namespace facehex::gui {

class MainWindow;

// Ct: a freshly opened CT, segmented, with its sides and automatic constraints (opened from the bundled CT when no
// patient is given, see defaultPatient). Segmentation: that, with File > Segment again's dialog open, showing the
// thresholds and cuts the segmentation found. Messages: the transfer with the message log open at its outcome.
// Landmarks: the patient's landmarks on its skin, the glabella dragged 5 mm down and its eyebrow line following.
enum class ScriptedState { Loaded, Plane, Fields, Glyphs, Transfer, Quality, Ct, Segmentation, Messages, Landmarks };
QStringList scriptedStateNames();  // "loaded", "plane", ...
std::optional<ScriptedState> scriptedStateFromName(const QString& name);

// The patient a state opens when none is given: the bundled CT for Ct and Segmentation, else empty (the bundled
// demo).
QString defaultPatient(ScriptedState state);

// Opens the inputs and waits: the standard (a bundled name or a file; empty: the bundled default) and the patient
// (a CT is segmented; empty: the bundled demo patient). False if one failed (the window's error reporter has been
// told why).
bool openInputs(MainWindow& window, const QString& patient, const QString& standard);

// Brings the window to `state`, computing the fields or the transfer (and waiting) unless the session has them, and
// sets the display to show that state. False if a computation failed (reported as above).
bool driveToState(MainWindow& window, ScriptedState state);

}  // namespace facehex::gui

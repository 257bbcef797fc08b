// facehex-gui: the desktop application.
//   facehex-gui [PATIENT] [--standard NAME]                   opens the window (no patient: only the standard)
//   facehex-gui --screenshot FILE [--state STATE] [PATIENT] [--standard NAME]
//       opens the inputs (default: the bundled demo; for the state ct, the bundled CT), brings the window to STATE,
//       saves it as PNG and exits.
// PATIENT is a head CT (.mhd, .mha, .nii, .nii.gz, .nrrd, .nhdr or a DICOM folder), a tet model or a closed surface.
#include <QVTKOpenGLNativeWidget.h>

#include <QApplication>
#include <QCommandLineParser>
#include <QEventLoop>
#include <QSurfaceFormat>
#include <QTimer>
#include <iostream>

#include "core/util/allocator_tuning.h"
#include "ui/autosave.h"
#include "ui/main_window.h"
#include "ui/scripted_states.h"
#include "ui/transfer_controller.h"

namespace {

using namespace facehex::gui;

int screenshot(MainWindow& window, const QString& file, const QString& stateName, const QString& patient,
               const QString& standard) {
  const std::optional<ScriptedState> state = scriptedStateFromName(stateName);
  if (!state) {
    std::cerr << "facehex-gui: unknown --state '" << stateName.toStdString()
              << "' (one of: " << scriptedStateNames().join(", ").toStdString() << ")\n";
    return 2;
  }
  window.setErrorReporter([](const QString& message) { std::cerr << message.toStdString() << "\n"; });
  window.autosave()->setEnabled(false);  // a scripted session must not replace the user's autosave
  window.show();                         // as it opens on this screen, not as the user's last session left it
  if (!openInputs(window, patient.isEmpty() ? defaultPatient(*state) : patient, standard) ||
      !driveToState(window, *state))
    return 1;
  QEventLoop settle;  // let the layout and the GL widgets settle before grabbing
  QTimer::singleShot(300, &settle, &QEventLoop::quit);
  settle.exec();
  if (!window.saveScreenshot(file)) return 1;
  std::cout << "wrote " << file.toStdString() << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  facehex::keep_freed_memory_for_reuse();
  // QVTKOpenGLNativeWidget needs its OpenGL format (core profile, depth, alpha) before the application exists.
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  QApplication::setApplicationName("FaceHex");
  QApplication::setOrganizationName("FaceHex");
  QApplication::setApplicationVersion(FACEHEX_VERSION);

  QCommandLineParser parser;
  parser.setApplicationDescription("Patient-specific hexahedral meshes of the facial soft tissue.");
  parser.addHelpOption();
  parser.addVersionOption();
  const QCommandLineOption screenshotOption("screenshot", "Render the window to FILE (PNG) and exit.", "FILE");
  const QCommandLineOption stateOption("state", "With --screenshot: " + scriptedStateNames().join(", ") + ".", "STATE",
                                       "loaded");
  const QCommandLineOption standardOption("standard", "Bundled standard name or hex mesh file.", "NAME");
  parser.addOptions({screenshotOption, stateOption, standardOption});
  parser.addPositionalArgument("PATIENT",
                               "Head CT (.mhd, .nii, .nrrd, DICOM folder), patient tet model or closed surface "
                               "(default: the bundled demo).");
  parser.process(app);
  const QString patient = parser.positionalArguments().value(0);
  const QString standard = parser.value(standardOption);

  MainWindow window;
  if (parser.isSet(screenshotOption))
    return screenshot(window, parser.value(screenshotOption), parser.value(stateOption), patient, standard);
  window.restoreWindowState();
  window.show();
  if (patient.isEmpty())
    window.controller()->openStandard(standard);
  else
    openInputs(window, patient, standard);
  return app.exec();
}

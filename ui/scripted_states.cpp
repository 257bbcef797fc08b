#include "ui/scripted_states.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QTabWidget>
#include <QTableWidget>

#include "core/util/resources.h"
#include "ui/main_window.h"
#include "ui/model_view.h"
#include "ui/transfer_controller.h"

namespace facehex::gui {
namespace {

const QStringList kNames = {"loaded",  "plane", "fields",       "glyphs",   "transfer",
                            "quality", "ct",    "segmentation", "messages", "landmarks"};

// Runs a job and waits for it; a job that could not start or that failed reports through the window.
bool runAndWait(MainWindow& window, bool started) {
  TransferController* c = window.controller();
  bool ok = started;
  const auto connection = QObject::connect(c, &TransferController::failed, [&ok] { ok = false; });
  c->waitUntilIdle();
  QObject::disconnect(connection);
  return ok;
}

}  // namespace

QStringList scriptedStateNames() { return kNames; }

std::optional<ScriptedState> scriptedStateFromName(const QString& name) {
  const int i = kNames.indexOf(name);
  if (i < 0) return std::nullopt;
  return static_cast<ScriptedState>(i);
}

QString defaultPatient(ScriptedState state) {
  return state == ScriptedState::Ct || state == ScriptedState::Segmentation ? QString::fromStdString(default_ct())
                                                                            : QString();
}

bool openInputs(MainWindow& window, const QString& patient, const QString& standard) {
  TransferController* c = window.controller();
  if (patient.isEmpty()) return runAndWait(window, c->openDemo(standard));
  return runAndWait(window, c->openStandard(standard)) && runAndWait(window, c->openPatient(patient));
}

bool driveToState(MainWindow& window, ScriptedState state) {
  SessionModel* session = window.session();
  TransferController* controller = window.controller();
  auto* analysis = window.findChild<QTabWidget*>("analysisTabs");
  session->setActiveRole(Role::Patient);
  DisplaySettings d;  // each state shows what it is about, whatever came before
  switch (state) {
    case ScriptedState::Loaded:
      break;
    case ScriptedState::Ct:
    case ScriptedState::Segmentation:
      d.showPlane = false;  // the sides and the feature lines, unobstructed
      window.findChild<QTableWidget*>("constraintTable")->scrollToBottom();  // the features come after the sides
      if (state == ScriptedState::Segmentation) {
        if (!session->model(Role::Patient).segmentation) {
          window.reportError(QObject::tr("the segmentation state needs a CT as the patient"));
          return false;
        }
        window.openPatient(session->model(Role::Patient).path);
      }
      break;
    case ScriptedState::Landmarks: {
      d.showPlane = false;
      window.findChild<QTableWidget*>("constraintTable")->scrollToBottom();
      const std::optional<FaceLandmarks>& landmarks = session->landmarks(Role::Patient);
      if (!landmarks) {
        window.reportError(QObject::tr("the landmarks state needs a patient with facial landmarks"));
        return false;
      }
      const Eigen::Vector3d glabella = landmarks->points.at("glabella") - 5.0 * Eigen::Vector3d::UnitZ();
      window.view(Role::Patient)->dragLandmark("glabella", glabella);
      break;
    }
    case ScriptedState::Plane: {
      // A feature line as a user places one: a horizontal plane at the eyebrows, on the skin.
      const LoadedModel& patient = session->model(Role::Patient);
      const Eigen::Vector3d lo = patient.domain.V.colwise().minCoeff(), hi = patient.domain.V.colwise().maxCoeff();
      PlanePose pose = session->plane();
      pose.band = 2.0;
      pose.region = patient.domain.side_mask.size() > 0 ? "w1" : "boundary";
      session->setPlane(pose);
      const Eigen::Vector3d origin(0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), lo.z() + 0.8 * (hi.z() - lo.z()));
      window.view(Role::Patient)->movePlaneWidget(origin, Eigen::Vector3d::UnitZ());
      window.findChild<QLineEdit*>("constraintName")->setText("eyebrow line");
      window.findChild<QComboBox*>("constraintField")->setCurrentIndex(1);
      window.findChild<QDoubleSpinBox*>("constraintValue")->setValue(0.95);
      break;
    }
    case ScriptedState::Fields:
    case ScriptedState::Glyphs:
      if (!session->parameterization(Role::Patient) && !runAndWait(window, controller->computeFields())) return false;
      analysis->setCurrentIndex(0);
      d.showPlane = false;
      d.showConstraints = false;
      d.field = state == ScriptedState::Fields ? 0 : -1;
      d.glyphs = state == ScriptedState::Glyphs ? GlyphMode::After : GlyphMode::Off;
      break;
    case ScriptedState::Transfer:
    case ScriptedState::Quality:
    case ScriptedState::Messages:
      if (!session->transfer() && !runAndWait(window, controller->runTransfer())) return false;
      analysis->setCurrentIndex(state == ScriptedState::Messages ? 2 : 1);
      d.showHex = true;
      d.measure = state == ScriptedState::Quality ? QualityMeasure::ScaledJacobian : QualityMeasure::Shape;
      d.threshold = state == ScriptedState::Quality ? 0.5 : 1.0;
      break;
  }
  session->setDisplay(d);
  return true;
}

}  // namespace facehex::gui

// The desktop application end to end, as a user drives it: the bundled demo (standard and sample patient) is
// opened, a constraint is placed with the plane widget, edits undo and redo; then a small box standard and a bent
// box patient are opened from files, their fields computed and the transfer run on the worker thread, the hex mesh
// exported and read back; bad files give the core's error message and the application keeps running; every
// scripted state renders visible 3D content. (The box pair keeps the computations within seconds and their results
// exactly checkable, whatever the size and state of the bundled models.)
#include "core/error.h"
#include "core/face_landmarks.h"
#include "core/hex_to_tets.h"
#include "core/io/mesh_io.h"
#include "core/quality/hex_quality.h"
#include "core/tet_topology.h"
#include "tests/core/test_meshes.h"
#include "ui/autosave.h"
#include "ui/main_window.h"
#include "ui/model_view.h"
#include "ui/scripted_states.h"
#include "ui/transfer_controller.h"

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFile>
#include <QLineEdit>
#include <QPushButton>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <QVTKOpenGLNativeWidget.h>

using namespace facehex;
using namespace facehex::gui;

class GuiTest : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase();
  void opensTheBundledDemo();
  void planeWidgetPlacesAConstraint();
  void undoAndRedoAConstraintEdit();
  void facialFeaturesAreAButtonAway();
  void cancelStopsTheWorker();
  void opensModelsFromFiles();
  void computesTheFields();
  void scriptedFieldStatesShowTheModels();
  void transfersExportsAndReloads();
  void thresholdIsolatesBadCells();
  void scriptedTransferStatesShowTheModels();
  void badFilesGiveTheCoreMessageAndTheAppKeepsRunning();

 private:
  int constraintCount() const { return int(session()->constraints(Role::Patient).set.constraints.size()); }
  SessionModel* session() const { return window_->session(); }
  QString takeError() { return std::exchange(error_, QString()); }
  void checkStates(const QStringList& states);

  std::unique_ptr<MainWindow> window_;
  QString error_;
  QTemporaryDir dir_;
};

void GuiTest::initTestCase() {
  QVERIFY(dir_.isValid());
  window_ = std::make_unique<MainWindow>();
  window_->setErrorReporter([this](const QString& m) { error_ = m; });
  window_->resize(1400, 900);
  window_->show();
  QVERIFY(QTest::qWaitForWindowExposed(window_.get()));
  QVERIFY2(openInputs(*window_, {}, {}), qPrintable(error_));
}

void GuiTest::opensTheBundledDemo() {
  QVERIFY(session()->hasModel(Role::Standard));
  QVERIFY(session()->hasModel(Role::Patient));
  QVERIFY(session()->model(Role::Patient).mesh.is_tet_mesh());
  QVERIFY(session()->model(Role::Standard).mesh.count(CellType::Hex) > 0);
  QVERIFY(constraintCount() >= 6);  // at least the six shape ends
}

void GuiTest::planeWidgetPlacesAConstraint() {
  session()->setActiveRole(Role::Patient);
  ModelView* view = window_->view(Role::Patient);
  QVERIFY(view->planeWidgetEnabled());
  PlanePose pose = session()->plane();
  pose.band = 2.0;
  pose.region = "boundary";
  session()->setPlane(pose);
  const LoadedModel& m = session()->model(Role::Patient);
  const Eigen::Vector3d lo = m.domain.V.colwise().minCoeff(), hi = m.domain.V.colwise().maxCoeff();
  const Eigen::Vector3d origin = lo + 0.7 * (hi - lo);
  view->movePlaneWidget(origin, Eigen::Vector3d::UnitZ());
  QVERIFY((session()->plane().origin - origin).norm() < 1e-9);
  QVERIFY((session()->plane().normal - Eigen::Vector3d::UnitZ()).norm() < 1e-9);

  // The preview selects what the core selects on the same plane.
  Selection expected;
  expected.plane = PlaneSelection{origin, Eigen::Vector3d::UnitZ(), 2.0, "boundary", std::nullopt, 0.0};
  const std::vector<char> boundary = boundary_vertex_flags(int(m.domain.V.rows()), boundary_faces(m.domain.T).F);
  const std::vector<int> core = select_vertices(expected, m.domain.V, boundary, m.domain.side_mask);
  QVERIFY(!core.empty());
  QCOMPARE(session()->planeSelection(), core);

  // Assign it through the panel, as the user does.
  const int before = constraintCount();
  window_->findChild<QLineEdit*>("constraintName")->setText("eyebrow");
  window_->findChild<QComboBox*>("constraintField")->setCurrentIndex(1);
  window_->findChild<QDoubleSpinBox*>("constraintValue")->setValue(0.7);
  QTest::mouseClick(window_->findChild<QPushButton*>("addFromPlane"), Qt::LeftButton);
  QCOMPARE(constraintCount(), before + 1);
  const Constraint& c = session()->constraints(Role::Patient).set.constraints.back();
  QCOMPARE(QString::fromStdString(c.name), QString("eyebrow"));
  QCOMPARE(c.field, 1);
  QCOMPARE(c.value, 0.7);
  QVERIFY(c.select.plane.has_value());
  QCOMPARE(session()->constraintVertices(Role::Patient, before), core);
}

void GuiTest::undoAndRedoAConstraintEdit() {
  QUndoStack* undo = session()->undoStack();
  const int n = constraintCount();
  const int last = n - 1;
  Constraint renamed = session()->constraints(Role::Patient).set.constraints.at(last);
  renamed.name = "brow line";
  session()->updateConstraint(Role::Patient, last, renamed);
  QCOMPARE(session()->constraints(Role::Patient).set.constraints.at(last).name, std::string("brow line"));
  undo->undo();
  QCOMPARE(session()->constraints(Role::Patient).set.constraints.at(last).name, std::string("eyebrow"));
  undo->redo();
  QCOMPARE(session()->constraints(Role::Patient).set.constraints.at(last).name, std::string("brow line"));
  // Back to the demo's own set (the added feature has no counterpart on the standard).
  undo->undo();
  undo->undo();
  QCOMPARE(constraintCount(), n - 1);
  undo->redo();
  QCOMPARE(constraintCount(), n);
  session()->removeConstraint(Role::Patient, last);
  QCOMPARE(constraintCount(), n - 1);
  // Every edit was autosaved.
  QVERIFY(ConstraintAutosave::exists(Role::Patient));
  QCOMPARE(int(read_constraint_set(ConstraintAutosave::path(Role::Patient).toStdString()).constraints.size()), n - 1);
}

void GuiTest::facialFeaturesAreAButtonAway() {
  const int n = constraintCount();
  window_->findChild<QAction*>("Facial_features")->trigger();
  QVERIFY2(error_.isEmpty(), qPrintable(error_));
  QCOMPARE(constraintCount(), n + int(feature_specs().size()));
  for (int i = n; i < constraintCount(); ++i) QVERIFY(!session()->constraintVertices(Role::Patient, i).empty());
  session()->undoStack()->undo();
  QCOMPARE(constraintCount(), n);
}

void GuiTest::cancelStopsTheWorker() {
  QSignalSpy finished(window_->controller(), &TransferController::finished);
  QVERIFY(window_->controller()->computeFields());
  window_->findChild<QPushButton*>("cancelButton")->click();
  QVERIFY(window_->controller()->waitUntilIdle());
  QCOMPARE(finished.count(), 1);
  const QString status = finished.first().first().toString();
  QVERIFY2(status.endsWith("cancelled"), qPrintable(status));
  QVERIFY(!session()->parameterization(Role::Patient));
  QVERIFY(error_.isEmpty());
}

void GuiTest::opensModelsFromFiles() {
  // The standard: a box of hexes with its six sides; the patient: a finer box split into tets, stretched and bent.
  const VolumeMesh box = test::hex_box(8, 3, 6, 80, 12, 60), fine = test::hex_box(16, 6, 12, 80, 12, 60);
  const QString standard = dir_.filePath("box.vtu");
  write_volume_mesh(standard.toStdString(), box);
  write_constraint_set(dir_.filePath("box.json").toStdString(), side_constraints());
  VolumeMesh bent = VolumeMesh::from_tets(fine.V, split_into_tets(fine).T);
  bent.point_data = fine.point_data;
  for (int v = 0; v < bent.num_vertices(); ++v) {
    const double x = bent.V(v, 0);
    bent.V(v, 0) *= 1.2;
    bent.V(v, 1) += 0.004 * (x - 40) * (x - 40);
  }
  const QString patient = dir_.filePath("bent.vtu");
  write_volume_mesh(patient.toStdString(), bent);
  QVERIFY2(openInputs(*window_, patient, standard), qPrintable(error_));
  QCOMPARE(session()->model(Role::Patient).mesh.num_cells(), bent.num_cells());
  QCOMPARE(session()->model(Role::Standard).mesh.num_cells(), box.num_cells());
  QCOMPARE(int(session()->constraints(Role::Standard).set.constraints.size()), 6);  // box.json, found beside it
}

void GuiTest::computesTheFields() {
  QVERIFY(window_->controller()->computeFields());
  QVERIFY(window_->controller()->busy());
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY2(error_.isEmpty(), qPrintable(error_));
  for (Role r : kRoles) {
    const ModelParameterization* p = session()->parameterization(r);
    QVERIFY(p);
    QCOMPARE(p->V.rows(), session()->model(r).domain.V.rows());
    QVERIFY(p->fields.angles.angles > 0);
  }
  QVERIFY(session()->parameterization(Role::Patient)->health.ok());
}

void GuiTest::scriptedFieldStatesShowTheModels() { checkStates({"loaded", "plane", "fields", "glyphs"}); }

void GuiTest::transfersExportsAndReloads() {
  QVERIFY(window_->controller()->runTransfer());
  QVERIFY(window_->controller()->busy());
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY2(error_.isEmpty(), qPrintable(error_));
  const TransferResult* r = session()->transfer();
  QVERIFY(r);
  QCOMPARE(r->hex.num_cells(), session()->model(Role::Standard).mesh.num_cells());

  const QString path = dir_.filePath("patient_hex.vtu");
  QVERIFY(window_->controller()->exportHex(path));
  const VolumeMesh reloaded = read_volume_mesh(path.toStdString());
  QCOMPARE(reloaded.num_cells(), r->hex.num_cells());
  QCOMPARE(reloaded.num_vertices(), r->hex.num_vertices());
  QCOMPARE(summarize(reloaded, element_quality(reloaded)).inverted, 0);
  QVERIFY(reloaded.cell_data.count("scaled_jacobian"));
  QVERIFY((reloaded.V - r->hex.V).cwiseAbs().maxCoeff() < 1e-9);
}

void GuiTest::thresholdIsolatesBadCells() {
  DisplaySettings d = session()->display();
  d.showHex = true;
  d.measure = QualityMeasure::ScaledJacobian;
  d.threshold = 1.0;
  session()->setDisplay(d);
  ModelView* view = window_->view(Role::Patient);
  QCOMPARE(view->drawnHexCells(), session()->transfer()->hex.num_cells());
  d.threshold = 0.5;
  session()->setDisplay(d);
  const Eigen::VectorXd sj = session()->transfer()->hex.cell_data.at("scaled_jacobian").col(0);
  QCOMPARE(view->drawnHexCells(), int((sj.array() <= 0.5).count()));
  QVERIFY(!view->planeWidgetEnabled());  // the hex display has no plane
  session()->setDisplay(DisplaySettings{});
  QVERIFY(view->planeWidgetEnabled());
}

void GuiTest::scriptedTransferStatesShowTheModels() { checkStates({"transfer", "quality"}); }

void GuiTest::badFilesGiveTheCoreMessageAndTheAppKeepsRunning() {
  const QString garbage = dir_.filePath("garbage.vtu");
  QFile f(garbage);
  QVERIFY(f.open(QIODevice::WriteOnly));
  f.write("this is not a VTK file\n\x01\x02\x03");
  f.close();
  std::string cliMessage;
  try {
    read_volume_mesh(garbage.toStdString());
  } catch (const Error& e) {
    cliMessage = e.what();
  }
  QVERIFY(!cliMessage.empty());

  const int vertices = session()->model(Role::Patient).mesh.num_vertices();
  QVERIFY(window_->controller()->openPatient(garbage));
  QVERIFY(window_->controller()->waitUntilIdle());
  QCOMPARE(takeError(), QString::fromStdString(cliMessage));
  QCOMPARE(session()->model(Role::Patient).mesh.num_vertices(), vertices);  // the old patient stays

  QVERIFY(!window_->controller()->loadConstraints(Role::Patient, garbage, false));
  QVERIFY(takeError().startsWith(garbage));
  QVERIFY(window_->controller()->openPatient(dir_.filePath("missing.vtu")));
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY(takeError().contains("missing.vtu"));
  QVERIFY(window_->isVisible());
  QVERIFY(!window_->controller()->busy());
}

void GuiTest::checkStates(const QStringList& states) {
  // The middle of each 3D view must show something other than the background (a vertical gradient: the same row
  // at the view's left edge is the reference).
  for (const QString& name : states) {
    QVERIFY2(driveToState(*window_, *scriptedStateFromName(name)), qPrintable(error_));
    window_->snapshot();
    for (Role r : kRoles) {
      const QImage image = window_->view(r)->grab().toImage();
      const int row = image.height() / 2;
      const QRgb edge = image.pixel(2, row), middle = image.pixel(image.width() / 2, row);
      QVERIFY2(edge != middle, qPrintable(name + " " + roleName(r) + ": nothing drawn in the middle"));
    }
  }
}

int main(int argc, char** argv) {
  QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
  QApplication app(argc, argv);
  QApplication::setOrganizationName("FaceHexTests");  // keeps the tests' recent files out of the user's settings
  QStandardPaths::setTestModeEnabled(true);           // and their autosaves
  GuiTest test;
  return QTest::qExec(&test, argc, argv);
}

#include "gui_test.moc"

// The desktop application end to end, as a user drives it: the bundled demo (standard and sample patient, with its
// automatic constraints) is opened, a constraint is placed with the plane widget, edits undo and redo, the standard
// is transferred onto the bundled patient; the patient's landmarks are loaded from a file or dragged on the skin (with
// the mouse, too) and its features follow them; the bundled CT is opened and segmented on the worker thread; a small
// box standard and a bent box patient are opened from files, their fields computed and the transfer run, the hex mesh
// exported and read back; bad files give the core's error message and the application keeps running; every scripted
// state renders visible 3D content. (The box pair keeps those computations within seconds and their results exactly
// checkable.) Results are kept: an undo brings back what an edit made stale, and replacing an unexported result asks
// first; the layout holds still and fits a laptop screen; the message log keeps every outcome and shows what a
// message names. Each test opens a new main window and sets up the state it needs (openDemo, openBoxes, ...), so any
// test runs alone: `gui_tests <name>`.
#include <QVTKOpenGLNativeWidget.h>

#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QDoubleSpinBox>
#include <QFile>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSettings>
#include <QSignalSpy>
#include <QSlider>
#include <QStandardPaths>
#include <QStatusBar>
#include <QSurfaceFormat>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <QUndoStack>

#include "core/face/automatic_constraints.h"
#include "core/face/landmark_file.h"
#include "core/io/mesh_io.h"
#include "core/mesh/hex_to_tets.h"
#include "core/mesh/tet_topology.h"
#include "core/quality/hex_quality.h"
#include "core/segment/ct_volume.h"
#include "core/segment/patient_input.h"
#include "core/segment/voxel_grid.h"
#include "core/standard/parameterization_cache.h"
#include "core/standard/standard_features.h"
#include "core/util/error.h"
#include "core/util/resources.h"
#include "tests/core/segment/dicom_writer.h"
#include "tests/core/test_meshes.h"
#include "ui/autosave.h"
#include "ui/main_window.h"
#include "ui/message_log.h"
#include "ui/model_view.h"
#include "ui/scripted_states.h"
#include "ui/segmentation_dialog.h"
#include "ui/transfer_controller.h"

using namespace facehex;
using namespace facehex::gui;

class GuiTest : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase();
  void init();
  void cleanup();
  void opensTheBundledDemo();
  void planeWidgetPlacesAConstraint();
  void undoAndRedoAConstraintEdit();
  void facialFeaturesAreRecomputedByTheButton();
  void landmarkFilePlacesTheFeatures();
  void draggedLandmarkMovesOnTheSkinWithItsFeature();
  void badLandmarkFileIsNamedAndChangesNothing();
  void mouseDragsALandmarkOnTheSkin();
  void cancelStopsTheWorker();
  void computeFieldsReadsTheStandardsCache();
  void transfersTheBundledModelsAndShowsThem();
  void registeredSkinIsAnOptionOfTheTransfer();
  void foundLandmarksCanPullTheRegistration();
  void cancelStopsTheSegmentation();
  void opensAndSegmentsTheBundledCt();
  void segmentationDialogRoundTripsItsOptions();
  void segmentAgainStartsFromWhatWasFoundAndTakesACut();
  void aFailedSegmentationAsksAgainNamingItsSettings();
  void aDicomFolderWithSeveralSeriesAsksWhichToSegment();
  void opensModelsFromFiles();
  void aSmallerModelReplacingALargerOneKeepsThePlaneSelectionValid();
  void computesTheFields();
  void scriptedFieldStatesShowTheModels();
  void transfersExportsAndReloads();
  void exportWritesWhatRunExportWrites();
  void thresholdIsolatesBadCells();
  void badFilesGiveTheCoreMessageAndTheAppKeepsRunning();
  void undoBringsBackTheResultAnEditMadeStale();
  void replacingAnUnexportedResultAsksFirst();
  void headerTextMovesNoWidget();
  void everythingIsReachableOnALaptopScreen();
  void windowLayoutIsKeptBetweenSessions();
  void constraintListShowsAllAutomaticConstraints();
  void messageLogKeepsOutcomesAndShowsWhatTheyName();

 private:
  int constraintCount() const { return int(session()->constraints(Role::Patient).set.constraints.size()); }
  // The patient's constraint of that name, or null.
  const Constraint* patientConstraint(const std::string& name) const;
  // The patient's landmark of that name (it must have it).
  Eigen::Vector3d patientLandmark(const std::string& name) const;
  // After a frame is drawn: every shown landmark has its name, and no two names overlap.
  static bool landmarkNamesAreClear(ModelView* view);
  // Opens a patient on the worker thread and waits; the error it reported, or empty.
  QString openPatient(const QString& path);
  SessionModel* session() const { return window_->session(); }
  QString takeError() { return std::exchange(error_, QString()); }
  void checkStates(const QStringList& states);
  // The states a test starts from, each in the window the test opened: the bundled demo; a box standard and a bent
  // box patient from files; the bundled CT segmented as the patient. False with error_ set when they cannot be made.
  bool openDemo();
  bool openBoxes();
  bool segmentBundledCt();
  bool runTransferAndWait();
  // Answers the next question box (opened by what the test does next) with `answer`; its text goes to question_.
  void answerNextQuestion(QMessageBox::StandardButton answer);
  // The window on a laptop's screen, 1366 x 768 (whatever the test display is), laid out.
  QRect fitToLaptopScreen();

  std::unique_ptr<MainWindow> window_;
  QString error_;
  QString question_;
  QTemporaryDir dir_;
};

void GuiTest::initTestCase() { QVERIFY(dir_.isValid()); }

void GuiTest::init() {
  error_.clear();
  window_ = std::make_unique<MainWindow>();
  window_->setErrorReporter([this](const QString& m) { error_ = m; });
  window_->resize(1400, 900);
  window_->show();
  QVERIFY(QTest::qWaitForWindowExposed(window_.get()));
}

void GuiTest::cleanup() {
  if (window_) window_->controller()->waitUntilIdle();
  window_.reset();
}

bool GuiTest::openDemo() { return openInputs(*window_, {}, {}); }

bool GuiTest::openBoxes() {
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
  return openInputs(*window_, patient, standard);
}

bool GuiTest::segmentBundledCt() { return openDemo() && openPatient(QString::fromStdString(default_ct())).isEmpty(); }

bool GuiTest::runTransferAndWait() {
  return window_->controller()->runTransfer() && window_->controller()->waitUntilIdle(300000) && error_.isEmpty();
}

const Constraint* GuiTest::patientConstraint(const std::string& name) const {
  for (const Constraint& c : session()->constraints(Role::Patient).set.constraints)
    if (c.name == name) return &c;
  return nullptr;
}

Eigen::Vector3d GuiTest::patientLandmark(const std::string& name) const {
  return session()->landmarks(Role::Patient)->points.at(name);
}

bool GuiTest::landmarkNamesAreClear(ModelView* view) {
  view->render();
  const std::vector<QRectF> boxes = view->landmarkLabelBoxes();
  if (int(boxes.size()) != view->shownLandmarks() || boxes.empty()) return false;
  for (size_t i = 0; i < boxes.size(); ++i)
    for (size_t j = i + 1; j < boxes.size(); ++j) {
      const QRectF shared = boxes[i].intersected(boxes[j]);
      if (shared.width() > 0 && shared.height() > 0) return false;
    }
  return true;
}

void GuiTest::answerNextQuestion(QMessageBox::StandardButton answer) {
  question_.clear();
  QTimer::singleShot(200, [this, answer] {
    if (auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget())) {
      question_ = box->text();
      box->button(answer)->click();
    }
  });
}

QRect GuiTest::fitToLaptopScreen() {
  const QRect laptop(0, 0, 1366, 768);
  window_->fitTo(laptop);
  QTest::qWait(300);  // the layout settles
  return laptop;
}

QString GuiTest::openPatient(const QString& path) {
  if (!window_->controller()->openPatient(path)) return "busy";
  window_->controller()->waitUntilIdle();
  return takeError();
}

void GuiTest::opensTheBundledDemo() {
  QVERIFY2(openDemo(), qPrintable(error_));
  QVERIFY(session()->hasModel(Role::Standard));
  QVERIFY(session()->hasModel(Role::Patient));
  QVERIFY(session()->model(Role::Patient).mesh.is_tet_mesh());
  QVERIFY(session()->model(Role::Standard).mesh.count(CellType::Hex) > 0);
  // The constraints `facehex run` places: the six sides and the facial features, valued as the standard's.
  const LoadedModel& patient = session()->model(Role::Patient);
  const ConstraintSet expected =
      automatic_constraints(patient.mesh.V, side_mask_of(patient.mesh), landmark_options_for(patient.mesh, "patient"),
                            feature_values(session()->constraints(Role::Standard).set));
  QCOMPARE(constraintCount(), 6 + int(feature_specs().size()));
  QCOMPARE(to_json(session()->constraints(Role::Patient).set), to_json(expected));
  for (int i = 0; i < constraintCount(); ++i) QVERIFY(!session()->constraintVertices(Role::Patient, i).empty());
}

void GuiTest::planeWidgetPlacesAConstraint() {
  QVERIFY2(openDemo(), qPrintable(error_));
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
  QVERIFY2(openDemo(), qPrintable(error_));
  QUndoStack* undo = session()->undoStack();
  const int n = constraintCount() + 1;
  const int last = n - 1;
  session()->addPlaneConstraint(Role::Patient, "eyebrow", 1, 0.7);
  QCOMPARE(constraintCount(), n);
  Constraint renamed = session()->constraints(Role::Patient).set.constraints.at(last);
  renamed.name = "brow line";
  session()->updateConstraint(Role::Patient, last, renamed);
  QCOMPARE(session()->constraints(Role::Patient).set.constraints.at(last).name, std::string("brow line"));
  undo->undo();
  QCOMPARE(session()->constraints(Role::Patient).set.constraints.at(last).name, std::string("eyebrow"));
  undo->redo();
  QCOMPARE(session()->constraints(Role::Patient).set.constraints.at(last).name, std::string("brow line"));
  // Back to the demo's own set.
  undo->undo();
  undo->undo();
  QCOMPARE(constraintCount(), n - 1);
  undo->redo();
  QCOMPARE(constraintCount(), n);
  // Colours follow the constraint, not its row: deleting the first recolours none of the others.
  auto* table = window_->findChild<QTableWidget*>("constraintTable");
  auto swatches = [&] {
    std::map<std::string, QRgb> colours;
    for (int row = 0; row < table->rowCount(); ++row)
      colours[session()->constraints(Role::Patient).set.constraints.at(row).name] =
          table->item(row, 0)->icon().pixmap(8, 8).toImage().pixel(4, 4);
    return colours;
  };
  const std::map<std::string, QRgb> before = swatches();
  QCOMPARE(before.size(), size_t(n));  // the names are distinct
  session()->removeConstraint(Role::Patient, 0);
  const std::map<std::string, QRgb> after = swatches();
  QCOMPARE(after.size(), size_t(n - 1));
  for (const auto& [name, colour] : after) QVERIFY2(before.at(name) == colour, name.c_str());
  session()->undoStack()->undo();
  session()->removeConstraint(Role::Patient, last);
  QCOMPARE(constraintCount(), n - 1);
  // Every edit was autosaved.
  QVERIFY(ConstraintAutosave::exists(Role::Patient));
  QCOMPARE(int(read_constraint_set(ConstraintAutosave::path(Role::Patient).toStdString()).constraints.size()), n - 1);
}

void GuiTest::facialFeaturesAreRecomputedByTheButton() {
  QVERIFY2(openDemo(), qPrintable(error_));
  // The automatic features are ordinary constraints: delete one, widen the band, and the button places them all
  // again in one undoable edit, replacing those of the same names.
  const int n = constraintCount();
  const std::string eyebrow = feature_specs().at(1).name;
  const double value = patientConstraint(eyebrow)->value;
  session()->removeConstraint(Role::Patient, n - 1);
  QCOMPARE(constraintCount(), n - 1);
  window_->findChild<QDoubleSpinBox*>("bandWidth")->setValue(4.0);
  window_->findChild<QAction*>("Facial_features")->trigger();
  QVERIFY2(error_.isEmpty(), qPrintable(error_));
  QCOMPARE(constraintCount(), n);
  for (const FeatureSpec& spec : feature_specs()) {
    const Constraint* c = patientConstraint(spec.name);
    QVERIFY(c && c->select.plane);
    QCOMPARE(c->select.plane->band, 4.0);
  }
  QCOMPARE(patientConstraint(eyebrow)->value, value);
  for (int i = 0; i < n; ++i) QVERIFY(!session()->constraintVertices(Role::Patient, i).empty());
  session()->undoStack()->undo();
  QCOMPARE(patientConstraint(eyebrow)->select.plane->band, kFeatureBand);
  session()->undoStack()->undo();
  QCOMPARE(constraintCount(), n);
}

void GuiTest::landmarkFilePlacesTheFeatures() {
  QVERIFY2(openDemo(), qPrintable(error_));
  ModelView* view = window_->view(Role::Patient);
  QCOMPARE(view->shownLandmarks(), int(session()->landmarks(Role::Patient)->points.size()));
  QVERIFY(landmarkNamesAreClear(view));
  // The bundled patient's landmarks with the glabella 4 mm lower: the eyebrow line follows the file.
  std::vector<NamedLandmark> given = read_landmark_file(FACEHEX_TEST_DATA_DIR "/landmarks/headsq.json");
  for (NamedLandmark& l : given)
    if (l.name == "glabella") l.position.z() -= 4.0;
  const QString path = dir_.filePath("headsq-lower-brow.mrk.json");
  write_landmark_file(path.toStdString(), given);
  const Eigen::Vector3d glabella = read_landmark_file(path.toStdString()).at(0).position;
  QVERIFY((patientLandmark("glabella") - glabella).norm() > 1.0);

  QVERIFY2(window_->controller()->loadLandmarks(Role::Patient, path, kFeatureBand), qPrintable(error_));
  QVERIFY(session()->landmarks(Role::Patient)->given);
  QVERIFY(landmarkNamesAreClear(view));  // the file's eye corners and tragi too
  QVERIFY((patientLandmark("glabella") - glabella).norm() < 1e-9);
  const Constraint* eyebrow = patientConstraint(feature_specs().at(1).name);
  QVERIFY(eyebrow && eyebrow->select.plane);
  QVERIFY(std::abs(eyebrow->select.plane->normal.dot(glabella - eyebrow->select.plane->point)) < 1e-9);
  const int row = int(eyebrow - session()->constraints(Role::Patient).set.constraints.data());
  QVERIFY(!session()->constraintVertices(Role::Patient, row).empty());
  // The same constraints as the CLI's --landmarks places.
  const std::map<std::string, double> values = feature_values(session()->constraints(Role::Standard).set);
  const PatientSetup cli = setup_patient({session()->model(Role::Patient).mesh, {}, std::nullopt},
                                         default_patient().mesh, "", &values, path.toStdString());
  for (const FeatureSpec& spec : feature_specs()) {
    const auto same = std::find_if(cli.constraints.constraints.begin(), cli.constraints.constraints.end(),
                                   [&](const Constraint& c) { return c.name == spec.name; });
    QVERIFY(same != cli.constraints.constraints.end());
    QCOMPARE(QString::fromStdString(to_json(ConstraintSet{{*same}})),
             QString::fromStdString(to_json(ConstraintSet{{*patientConstraint(spec.name)}})));
  }
  // Saved and undone as the constraints are.
  const QString saved = dir_.filePath("saved.json");
  QVERIFY(window_->controller()->saveLandmarks(Role::Patient, saved));
  QVERIFY((landmarks_from(read_landmark_file(saved.toStdString()), "saved").points.at("glabella") - glabella).norm() <
          1e-9);
  session()->undoStack()->undo();
  QVERIFY(!session()->landmarks(Role::Patient)->given);
  QVERIFY((patientLandmark("glabella") - glabella).norm() > 1.0);
}

void GuiTest::draggedLandmarkMovesOnTheSkinWithItsFeature() {
  QVERIFY2(openDemo(), qPrintable(error_));
  const VolumeMesh& mesh = session()->model(Role::Patient).mesh;
  const Eigen::Vector3d before = patientLandmark("glabella");
  // Dropped 5 mm in front of the skin and 3 mm lower: it lands on the closest skin vertex.
  const Eigen::Vector3d dropped = before + Eigen::Vector3d(0, 5, -3);
  const Eigen::Vector3d onSkin = closest_skin_point(mesh.V, side_mask_of(mesh), dropped);
  QVERIFY((onSkin - dropped).norm() > 1.0);
  window_->view(Role::Patient)->dragLandmark("glabella", dropped);
  QVERIFY2(error_.isEmpty(), qPrintable(error_));
  QVERIFY((patientLandmark("glabella") - onSkin).norm() < 1e-9);
  const Constraint* eyebrow = patientConstraint(feature_specs().at(1).name);
  QVERIFY(std::abs(eyebrow->select.plane->normal.dot(onSkin - eyebrow->select.plane->point)) < 1e-9);
  QVERIFY(std::abs(eyebrow->select.plane->point.z() - before.z()) > 1.0);
  // One undoable edit: the landmark and its feature go back together.
  session()->undoStack()->undo();
  QVERIFY((patientLandmark("glabella") - before).norm() < 1e-9);
  QVERIFY(std::abs(patientConstraint(feature_specs().at(1).name)->select.plane->point.z() - before.z()) < 1e-9);
}

void GuiTest::mouseDragsALandmarkOnTheSkin() {
  // The user's drag, as mouse events on the 3D widget: press on the nose tip's handle, move, release.
  QVERIFY2(openDemo(), qPrintable(error_));
  session()->setActiveRole(Role::Standard);  // no plane widget in the patient's view to catch the press
  ModelView* view = window_->view(Role::Patient);
  view->render();
  QWidget* w = view->renderWidget();
  const Eigen::Vector3d before = patientLandmark("pronasale");
  const QPoint from = view->widgetPosition(before), to = view->widgetPosition(before + Eigen::Vector3d(8, 0, 8));
  auto send = [w](QEvent::Type type, const QPoint& at, Qt::MouseButtons buttons) {
    QMouseEvent e(type, at, w->mapToGlobal(at), Qt::LeftButton, buttons, Qt::NoModifier);
    QApplication::sendEvent(w, &e);
  };
  send(QEvent::MouseMove, from, Qt::NoButton);
  send(QEvent::MouseButtonPress, from, Qt::LeftButton);
  for (int i = 1; i <= 10; ++i) send(QEvent::MouseMove, from + (to - from) * i / 10, Qt::LeftButton);
  send(QEvent::MouseButtonRelease, to, Qt::NoButton);
  QVERIFY2(error_.isEmpty(), qPrintable(error_));
  // It moved up and sideways along the surface, onto a skin vertex.
  const Eigen::Vector3d after = patientLandmark("pronasale");
  QVERIFY(after.z() - before.z() > 3.0 && after.x() - before.x() > 3.0);
  const VolumeMesh& mesh = session()->model(Role::Patient).mesh;
  QCOMPARE((closest_skin_point(mesh.V, side_mask_of(mesh), after) - after).norm(), 0.0);
  QCOMPARE(session()->undoStack()->undoText(), QString("move the pronasale"));
}

void GuiTest::badLandmarkFileIsNamedAndChangesNothing() {
  QVERIFY2(openDemo(), qPrintable(error_));
  const std::string constraints = to_json(session()->constraints(Role::Patient).set);
  const Eigen::Vector3d glabella = patientLandmark("glabella");
  const int edits = session()->undoStack()->count();
  const QString broken = dir_.filePath("broken.json"), partial = dir_.filePath("partial.json");
  QFile f(broken);
  QVERIFY(f.open(QIODevice::WriteOnly));
  f.write("{\"format\": \"facehex-landmarks\", \"landmarks\": [{\"name\": \"glabella\"");
  f.close();
  write_landmark_file(partial.toStdString(), {{"glabella", glabella, LandmarkStatus::given}});
  for (const QString& path : {broken, partial, dir_.filePath("missing.json")}) {
    QVERIFY(!window_->controller()->loadLandmarks(Role::Patient, path, kFeatureBand));
    const QString error = takeError();
    QVERIFY2(error.startsWith(path), qPrintable(error));
    MessageLog* log = window_->messageLog();
    QCOMPARE(log->topLevelItem(log->topLevelItemCount() - 1)->text(1), error);
    QCOMPARE(to_json(session()->constraints(Role::Patient).set), constraints);
    QVERIFY((patientLandmark("glabella") - glabella).norm() == 0);
    QCOMPARE(session()->undoStack()->count(), edits);
  }
}

void GuiTest::computeFieldsReadsTheStandardsCache() {
  QVERIFY2(openDemo(), qPrintable(error_));
  // The bundled standard has its parameterization cached beside it: Compute fields reads it, as the transfer does.
  QSignalSpy finished(window_->controller(), &TransferController::finished);
  QVERIFY(window_->controller()->computeFields());
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY2(error_.isEmpty(), qPrintable(error_));
  const QString status = finished.first().first().toString();
  // "Fields computed: standard ... (from its cache), patient ...": the patient has no cache and is computed.
  QVERIFY2(status.section(", ", 0, 0).contains("standard") && status.section(", ", 0, 0).endsWith("(from its cache)"),
           qPrintable(status));
  QCOMPARE(status.count("from its cache"), 1);
  const LoadedModel& standard = session()->model(Role::Standard);
  const std::optional<ModelParameterization> cached =
      read_parameterization_cache(parameterization_cache_path(standard.path.toStdString()), standard.domain,
                                  standard.constraints.set, HarmonicFieldsOptions{});
  QVERIFY(cached && session()->parameterization(Role::Standard));
  QVERIFY(session()->parameterization(Role::Standard)->fields.uvw == cached->fields.uvw);
}

void GuiTest::cancelStopsTheWorker() {
  QVERIFY2(openDemo(), qPrintable(error_));
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

void GuiTest::transfersTheBundledModelsAndShowsThem() {
  // The bundled standard onto the bundled patient with its automatic constraints, as `facehex run` maps them.
  QVERIFY2(openDemo(), qPrintable(error_));
  QSignalSpy progress(window_->controller(), &TransferController::progress);
  QVERIFY2(runTransferAndWait(), qPrintable(error_));
  QVERIFY(progress.count() > 10);
  for (const char* step : {"mapping vertices", "shape relaxation", "repairing folded cells"})
    QVERIFY2(std::any_of(progress.begin(), progress.end(),
                         [&](const QList<QVariant>& args) { return args.first().toString().contains(step); }),
             step);
  const TransferResult* r = session()->transfer();
  QVERIFY(r);
  const VolumeMesh& standard = session()->model(Role::Standard).mesh;
  QCOMPARE(r->patient_hex.num_cells(), standard.num_cells());
  QCOMPARE(r->patient_hex.count(CellType::Hex), standard.count(CellType::Hex));
  QCOMPARE(r->patient_quality.summary.cells, standard.num_cells());
  QCOMPARE(r->patient_quality.summary.inverted, 0);
  QCOMPARE(summarize(r->patient_hex, element_quality(r->patient_hex)).inverted, 0);
  QVERIFY(r->patient_hex.cell_data.count("scaled_jacobian") && r->patient_hex.point_data.count("uvw"));
  for (Role role : kRoles) QVERIFY(session()->parameterization(role));
  QCOMPARE(session()->parameterization(Role::Patient)->V.rows(), session()->model(Role::Patient).mesh.V.rows());
  QVERIFY(r->registration);  // the registered skin, by default
  checkStates({"transfer", "quality", "messages"});
}

void GuiTest::registeredSkinIsAnOptionOfTheTransfer() {
  // On by default, as in the CLI; unchecked, the transfer uses the paper's feature lines
  // (--skin-correspondence features).
  QVERIFY2(openDemo(), qPrintable(error_));
  auto* registered = window_->findChild<QAction*>("Register_the_skins");
  QVERIFY(registered && registered->isCheckable() && registered->isChecked());
  QVERIFY(window_->controller()->options().skin_correspondence == SkinCorrespondence::registered);
  registered->trigger();
  QVERIFY(window_->controller()->options().skin_correspondence == SkinCorrespondence::features);
  QVERIFY2(runTransferAndWait(), qPrintable(error_));
  const TransferResult* r = session()->transfer();
  QVERIFY(r && !r->registration && r->registered_failure.empty());
  QCOMPARE(r->patient_quality.summary.inverted, 0);
  registered->trigger();
  QVERIFY(window_->controller()->options().skin_correspondence == SkinCorrespondence::registered);
}

void GuiTest::foundLandmarksCanPullTheRegistration() {
  // On by default, as in the CLI: the transfer pairs the found landmarks, keeps the standard's landmark vertices where
  // the mapping put them, and its message says where they landed; unchecked, the registration is not pulled.
  QVERIFY2(openDemo(), qPrintable(error_));
  auto* pull = window_->findChild<QAction*>("Pull_the_found_landmarks");
  QVERIFY(pull && pull->isCheckable() && pull->isChecked());
  QVERIFY(window_->controller()->options().pull_found_landmarks);
  QVERIFY2(runTransferAndWait(), qPrintable(error_));
  const TransferResult* r = session()->transfer();
  QVERIFY(r && r->registration && !r->landing.empty());
  QCOMPARE(r->patient_quality.summary.inverted, 0);
  const StandardFeatures features = standard_features(session()->model(Role::Standard).mesh);
  QVERIFY(features.landmark_vertices.size() >= 9);
  int kept = 0;
  for (const auto& [name, v] : features.landmark_vertices)
    kept += r->run.patient_hex.V.row(v) == r->run.mapped_hex.V.row(v);
  QVERIFY2(kept + r->run.untangle.released_feature_vertices >= static_cast<int>(features.landmark_vertices.size()),
           qPrintable(QString("%1 of %2 landmark vertices kept").arg(kept).arg(features.landmark_vertices.size())));
  double pulled_mean = 0;
  for (const FeatureLanding& l : r->landing) pulled_mean += l.distance / static_cast<double>(r->landing.size());
  MessageLog* log = window_->messageLog();
  QTreeWidgetItem* transfer = nullptr;
  for (int i = log->topLevelItemCount() - 1; i >= 0 && !transfer; --i)
    if (log->topLevelItem(i)->text(1).startsWith("Transfer done")) transfer = log->topLevelItem(i);
  QVERIFY(transfer);
  QStringList detail;
  for (int i = 0; i < transfer->childCount(); ++i) detail << transfer->child(i)->text(1);
  QVERIFY2(detail.filter("anatomy: the standard's").size() == 1, qPrintable(detail.join(" | ")));
  pull->trigger();
  QVERIFY(!window_->controller()->options().pull_found_landmarks);
  QVERIFY2(runTransferAndWait(), qPrintable(error_));
  double free_mean = 0;
  for (const FeatureLanding& l : session()->transfer()->landing)
    free_mean += l.distance / static_cast<double>(session()->transfer()->landing.size());
  QVERIFY2(pulled_mean < 0.5 * free_mean, qPrintable(QString("%1 against %2 mm").arg(pulled_mean).arg(free_mean)));
  pull->trigger();
  QVERIFY(window_->controller()->options().pull_found_landmarks);
  // Run > Landmarks that pull: one entry per landmark; unchecking the right mouth corner leaves it out of the pull,
  // and the standard's lands where the skins' shapes put it, the others still on the patient's.
  auto* pulling = window_->findChild<QMenu*>("Landmarks_that_pull");
  QVERIFY(pulling);
  QAction* corner = nullptr;
  for (QAction* a : pulling->actions())
    if (a->text() == "cheilion right") corner = a;
  QVERIFY(corner && corner->isCheckable() && corner->isChecked());
  QCOMPARE(pulling->actions().size(), static_cast<int>(landmark_names().size()));
  corner->trigger();
  QCOMPARE(window_->controller()->options().landmarks_not_pulled, std::vector<std::string>{"cheilion right"});
  QVERIFY2(runTransferAndWait(), qPrintable(error_));
  for (const FeatureLanding& l : session()->transfer()->landing) {
    QCOMPARE(l.pulled, l.name != "cheilion right");
    if (l.name == "cheilion right")
      QVERIFY2(l.distance > 1.0, qPrintable(QString("the unpulled corner lands %1 mm away").arg(l.distance)));
    else
      QVERIFY2(l.distance < 0.5,
               qPrintable(QString("%1 lands %2 mm away").arg(QString::fromStdString(l.name)).arg(l.distance)));
  }
  corner->trigger();
  QVERIFY(window_->controller()->options().landmarks_not_pulled.empty());
}

void GuiTest::cancelStopsTheSegmentation() {
  QVERIFY2(openDemo(), qPrintable(error_));
  QSignalSpy finished(window_->controller(), &TransferController::finished);
  const quint64 revision = session()->revision(Role::Patient);
  QVERIFY(window_->controller()->openPatient(QString::fromStdString(default_ct())));
  window_->findChild<QPushButton*>("cancelButton")->click();
  QVERIFY(window_->controller()->waitUntilIdle());
  QCOMPARE(finished.count(), 1);
  const QString status = finished.first().first().toString();
  QVERIFY2(status.startsWith("Segmenting headsq.mhd") && status.endsWith("cancelled"), qPrintable(status));
  QCOMPARE(session()->revision(Role::Patient), revision);  // the patient stays
  QVERIFY(error_.isEmpty());
}

void GuiTest::opensAndSegmentsTheBundledCt() {
  QVERIFY2(openDemo(), qPrintable(error_));  // the standard values the features
  const QString ct = QString::fromStdString(default_ct());
  QSignalSpy progress(window_->controller(), &TransferController::progress);
  const QString error = openPatient(ct);
  QVERIFY2(error.isEmpty(), qPrintable(error));
  QVERIFY(std::any_of(progress.begin(), progress.end(), [](const QList<QVariant>& args) {
    return args.first().toString().startsWith("segmentation: tetrahedralizing");
  }));
  const LoadedModel& patient = session()->model(Role::Patient);
  QCOMPARE(patient.path, ct);
  QVERIFY(patient.mesh.is_tet_mesh());
  QVERIFY(patient.mesh.num_cells() > 10000);
  // Six labelled sides, each selecting vertices, and the features at the landmarks.
  const Eigen::VectorXi mask = side_mask_of(patient.mesh);
  QCOMPARE(mask.size(), Eigen::Index(patient.mesh.num_vertices()));
  QCOMPARE(constraintCount(), 6 + int(feature_specs().size()));
  for (int s = 0; s < kNumSides; ++s) {
    const Constraint& c = session()->constraints(Role::Patient).set.constraints.at(s);
    QVERIFY(c.select.side && *c.select.side == static_cast<Side>(s));
    QVERIFY(!session()->constraintVertices(Role::Patient, s).empty());
  }
  for (const FeatureSpec& spec : feature_specs()) QVERIFY(patientConstraint(spec.name));
  for (int i = 6; i < constraintCount(); ++i) QVERIFY(!session()->constraintVertices(Role::Patient, i).empty());
  // Still ordinary, undoable constraints.
  session()->removeConstraint(Role::Patient, constraintCount() - 1);
  session()->undoStack()->undo();
  QCOMPARE(constraintCount(), 6 + int(feature_specs().size()));
  checkStates({"ct"});
}

void GuiTest::segmentationDialogRoundTripsItsOptions() {
  SegmentationDialog dialog;
  const SegmentOptions defaults;
  SegmentOptions o = dialog.options();  // opens with the CLI's defaults: everything automatic
  QCOMPARE(o.tets.target_edge_length, defaults.tets.target_edge_length);
  QCOMPARE(o.coarsen_above_tets, defaults.coarsen_above_tets);
  QVERIFY(o.follow_scan_spacing && defaults.follow_scan_spacing);
  QVERIFY(!o.skin_threshold && !o.bone_threshold && !o.cuts.top_z && !o.cuts.bottom_z && !o.cuts.posterior_y &&
          !o.cuts.centre_x && !o.cuts.head_turn && !o.cuts.head_pitch);
  QVERIFY(o.orientation.anterior.empty() && o.orientation.superior.empty());
  QCOMPARE(o.cuts.ear_clearance, defaults.cuts.ear_clearance);
  QCOMPARE(o.min_thickness, defaults.min_thickness);
  QCOMPARE(o.max_depth, defaults.max_depth);
  QCOMPARE(o.bone_gap_radius, defaults.bone_gap_radius);
  QCOMPARE(o.cavity_closing_radius, defaults.cavity_closing_radius);
  QCOMPARE(o.smoothing_sigma, defaults.smoothing_sigma);
  QVERIFY(o.denoising_blur < 0 && defaults.denoising_blur < 0);  // from the CT's noise
  QVERIFY(dialog.findChild<QCheckBox*>("segmentDenoiseAutomatic")->isChecked());

  SegmentOptions given;
  given.tets.target_edge_length = 3.5;
  given.coarsen_above_tets = 0;  // the edge length as given
  given.follow_scan_spacing = false;
  given.skin_threshold = 600;
  given.cuts.top_z = 120;
  given.cuts.centre_x = -4.5;
  given.cuts.head_turn = -12;
  given.cuts.head_pitch = 14;
  given.cuts.ear_clearance = 5;
  given.orientation.anterior = "-y";
  // The soft-tissue layer's settings, which a segmentation's error names when its surface has tunnels.
  given.min_thickness = 5;
  given.max_depth = 20;
  given.bone_gap_radius = 3.5;
  given.cavity_closing_radius = 6;
  given.smoothing_sigma = 2.2;
  given.find_skin_objects = false;
  given.denoising_blur = 0;  // none, whatever the noise
  dialog.setOptions(given);
  o = dialog.options();
  QCOMPARE(o.denoising_blur, 0.0);
  QVERIFY(!dialog.findChild<QCheckBox*>("segmentDenoiseAutomatic")->isChecked());
  dialog.findChild<QDoubleSpinBox*>("segmentDenoise")->setValue(1.5);
  QCOMPARE(dialog.options().denoising_blur, 1.5);
  QCOMPARE(o.min_thickness, 5.0);
  QCOMPARE(o.max_depth, 20.0);
  QCOMPARE(o.bone_gap_radius, 3.5);
  QCOMPARE(o.cavity_closing_radius, 6.0);
  QCOMPARE(o.smoothing_sigma, 2.2);
  QVERIFY(!o.find_skin_objects);
  QVERIFY(!dialog.findChild<QCheckBox*>("segmentSkinObjects")->isChecked());
  dialog.findChild<QCheckBox*>("segmentSkinObjects")->setChecked(true);
  QVERIFY(dialog.options().find_skin_objects);
  dialog.findChild<QDoubleSpinBox*>("segmentMinThickness")->setValue(4);
  QCOMPARE(dialog.options().min_thickness, 4.0);
  QCOMPARE(o.tets.target_edge_length, 3.5);
  QCOMPARE(o.coarsen_above_tets, 0.0);
  QVERIFY(!o.follow_scan_spacing);
  QVERIFY(!dialog.findChild<QCheckBox*>("segmentCoarsenLargeFaces")->isChecked());
  QCOMPARE(*o.skin_threshold, 600.0);
  QVERIFY(!o.bone_threshold);
  QCOMPARE(*o.cuts.top_z, 120.0);
  QCOMPARE(*o.cuts.centre_x, -4.5);
  QCOMPARE(*o.cuts.head_turn, -12.0);
  QCOMPARE(*o.cuts.head_pitch, 14.0);
  QVERIFY(!o.cuts.bottom_z && !o.cuts.posterior_y);
  QCOMPARE(o.cuts.ear_clearance, 5.0);
  QCOMPARE(o.orientation.anterior, std::string("-y"));
  QVERIFY(o.orientation.superior.empty());

  // Found values fill the automatic boxes only, and stay automatic until unticked.
  FaceCuts found;
  found.top_z = 130;
  found.bottom_z = 4;
  found.posterior_y = 101;
  found.centre_x = 98;
  found.turn.degrees = 7.5;
  found.turn.pitch = -6;
  dialog.findChild<QCheckBox*>("segmentHeadTurnAutomatic")->setChecked(true);
  CtSegmentation segmentation;
  segmentation.thresholds = {550, 1100};
  segmentation.cuts = found;
  segmentation.edge_length = 3.5;
  dialog.showFound(segmentation);
  o = dialog.options();
  QVERIFY(!o.cuts.head_turn);
  QCOMPARE(dialog.findChild<QDoubleSpinBox*>("segmentHeadTurn")->value(), 7.5);
  QCOMPARE(*o.cuts.head_pitch, 14.0);  // given, not replaced by the found -6
  QVERIFY(!o.bone_threshold && !o.cuts.posterior_y);
  QCOMPARE(*o.cuts.top_z, 120.0);  // given, not replaced by the found 130
  dialog.findChild<QCheckBox*>("segmentPosteriorCutAutomatic")->setChecked(false);
  QCOMPARE(*dialog.options().cuts.posterior_y, 101.0);
}

void GuiTest::segmentAgainStartsFromWhatWasFoundAndTakesACut() {
  // With the bundled CT as the patient, File > Segment again asks, starting from the thresholds and cuts the
  // segmentation found; nothing runs until Segment.
  QVERIFY2(segmentBundledCt(), qPrintable(error_));
  const LoadedModel& before = session()->model(Role::Patient);
  QVERIFY(before.segmentation);
  const FaceCuts found = before.segmentation->cuts;
  const double skin = before.segmentation->thresholds.skin;
  const QString ct = before.path;
  const int cells = before.mesh.num_cells();
  auto* again = window_->findChild<QAction*>("Segment_again");
  QVERIFY(again && again->isEnabled());
  again->trigger();
  SegmentationDialog* dialog = window_->segmentationDialog();
  QVERIFY(dialog->isVisible());
  QVERIFY(!window_->controller()->busy());
  QCOMPARE(dialog->findChild<QDoubleSpinBox*>("segmentSkin")->value(), std::round(skin * 10) / 10);
  QCOMPARE(dialog->findChild<QDoubleSpinBox*>("segmentPosteriorCut")->value(), found.posterior_y);
  // The edge length as the user left it, its rules on; the length the CT's 3.2 mm voxels made of it said beside.
  QCOMPARE(dialog->findChild<QDoubleSpinBox*>("segmentEdgeLength")->value(), SegmentOptions{}.tets.target_edge_length);
  QVERIFY(dialog->findChild<QCheckBox*>("segmentCoarsenLargeFaces")->isChecked());
  const QString madeAt = dialog->findChild<QLabel*>("segmentMadeAt")->text();
  QVERIFY2(madeAt.contains("3.2 mm") && madeAt.contains("voxel spacing"), qPrintable(madeAt));
  checkStates({"segmentation"});  // the window with the dialog, rendered

  // Cancel: nothing happens.
  const quint64 revision = session()->revision(Role::Patient);
  dialog->reject();
  QVERIFY(!window_->controller()->busy());
  QCOMPARE(session()->revision(Role::Patient), revision);

  // A posterior cut 8 mm further forward, on a coarser mesh, as a user sets it in the dialog.
  window_->openPatient(ct);
  QVERIFY(dialog->isVisible());
  dialog->findChild<QCheckBox*>("segmentPosteriorCutAutomatic")->setChecked(false);
  dialog->findChild<QDoubleSpinBox*>("segmentPosteriorCut")->setValue(found.posterior_y + 8);
  dialog->findChild<QDoubleSpinBox*>("segmentEdgeLength")->setValue(4);
  QSignalSpy finished(window_->controller(), &TransferController::finished);
  dialog->findChild<QPushButton*>("segmentButton")->click();
  QVERIFY(window_->controller()->busy());
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY2(error_.isEmpty(), qPrintable(takeError()));
  const LoadedModel& after = session()->model(Role::Patient);
  QCOMPARE(after.segmentation->cuts.posterior_y, found.posterior_y + 8);
  QCOMPARE(after.segmentation->cuts.top_z, found.top_z);                    // still automatic, found again
  QVERIFY(after.mesh.V.col(1).minCoeff() >= found.posterior_y + 8 - 1e-4);  // the surface is extracted in floats
  QVERIFY(after.mesh.num_cells() < cells);
  QCOMPARE(finished.count(), 1);
  const QString status = finished.first().first().toString();
  QVERIFY2(status.contains(QString("posterior y %1").arg(found.posterior_y + 8, 0, 'f', 1)), qPrintable(status));
  QCOMPARE(window_->statusBar()->toolTip(), status);  // the whole line, which the status bar cuts
}

void GuiTest::aFailedSegmentationAsksAgainNamingItsSettings() {
  // The bundled CT cropped across the cheeks: its segmentation stops (the scan holds too little of the face) naming
  // --posterior-cut. The dialog opens again as the user left it, says why, and names its own setting for it; with the
  // posterior cut given there, the CT is segmented.
  CtVolume cheeks = read_ct_volume(default_ct());
  cheeks.intensity = crop(cheeks.intensity, {13, 0, 0}, {51, 64, 93});
  const QString ct = dir_.filePath("cheeks.mha");
  write_ct_volume(ct.toStdString(), cheeks);
  window_->openPatient(ct);
  SegmentationDialog* dialog = window_->segmentationDialog();
  QVERIFY(dialog->isVisible());
  QVERIFY(!dialog->findChild<QLabel*>("segmentFailure")->isVisible());
  dialog->findChild<QDoubleSpinBox*>("segmentEarClearance")->setValue(7);
  dialog->findChild<QPushButton*>("segmentButton")->click();
  QVERIFY(window_->controller()->waitUntilIdle());
  const QString stopped = takeError();
  QVERIFY2(stopped.contains("the scan ends across the head"), qPrintable(stopped));
  QVERIFY(!session()->hasModel(Role::Patient));
  QVERIFY(dialog->isVisible());
  const QLabel* failure = dialog->findChild<QLabel*>("segmentFailure");
  QVERIFY(failure->isVisible());
  const QString text = failure->text();
  QVERIFY2(text.contains("In this dialog:") && text.mid(text.indexOf("In this dialog:")).contains("Posterior cut y"),
           qPrintable(text));
  QCOMPARE(failure->toolTip(), stopped);  // all of it, however much the label shows
  QCOMPARE(dialog->findChild<QDoubleSpinBox*>("segmentEarClearance")->value(), 7.0);  // as the user left it

  dialog->findChild<QCheckBox*>("segmentPosteriorCutAutomatic")->setChecked(false);
  dialog->findChild<QDoubleSpinBox*>("segmentPosteriorCut")->setValue(150);
  dialog->findChild<QPushButton*>("segmentButton")->click();
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY2(error_.isEmpty(), qPrintable(takeError()));
  QVERIFY(!dialog->isVisible());
  QVERIFY(session()->hasModel(Role::Patient));
  QCOMPARE(session()->model(Role::Patient).segmentation->cuts.posterior_y, 150.0);
  // Another CT starts without the message.
  window_->openPatient(QString::fromStdString(default_ct()));
  QVERIFY(!failure->isVisible());
  dialog->reject();
}

void GuiTest::aDicomFolderWithSeveralSeriesAsksWhichToSegment() {
  // The bundled CT as a DICOM series beside a one-slice localizer, as scanners export them: the segmentation dialog
  // lists the two, largest first, and segments the one chosen; a folder of one series shows no choice.
  const QDir folder(dir_.filePath("two-series"));
  QVERIFY(QDir().mkpath(folder.path()));
  facehex::testing::write_bundled_series(folder.path().toStdString(), [](int) { return 0; });
  facehex::testing::SliceSpec localizer;
  localizer.series_uid = "1.2.826.0.1.3680043.9.7777.9";
  localizer.description = "localizer";
  facehex::testing::write_slice(folder.filePath("scout.dcm").toStdString(), localizer, std::vector<std::int16_t>(6, 5));
  window_->openPatient(folder.path());
  SegmentationDialog* dialog = window_->segmentationDialog();
  QVERIFY(dialog->isVisible());
  auto* series = dialog->findChild<QComboBox*>("segmentSeries");
  QVERIFY(series->isVisible());
  QCOMPARE(series->count(), 2);
  QVERIFY2(series->itemText(1).contains("localizer"), qPrintable(series->itemText(1)));
  QCOMPARE(dialog->options().dicom_series, facehex::testing::SliceSpec{}.series_uid);
  dialog->findChild<QPushButton*>("segmentButton")->click();
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY2(error_.isEmpty(), qPrintable(takeError()));
  QVERIFY(session()->hasModel(Role::Patient));
  QCOMPARE(session()->model(Role::Patient).segmentation->options.dicom_series,
           facehex::testing::SliceSpec{}.series_uid);
  // One series: nothing to choose.
  QVERIFY(QFile::remove(folder.filePath("scout.dcm")));
  window_->openPatient(folder.path());
  QVERIFY(!series->isVisible());
  QVERIFY(dialog->options().dicom_series.empty());
  dialog->reject();
}

void GuiTest::aSmallerModelReplacingALargerOneKeepsThePlaneSelectionValid() {
  // The bundled demo's patient, then a box of a few hundred vertices, with the plane shown: the views rebuilt on the
  // new model must not be handed the old model's selected vertices.
  QVERIFY2(openDemo(), qPrintable(error_));
  QVERIFY(session()->display().showPlane);
  QVERIFY(!session()->planeSelection().empty());
  const VolumeMesh box = test::hex_box(4, 2, 3, 40, 12, 30);
  VolumeMesh tets = VolumeMesh::from_tets(box.V, split_into_tets(box).T);
  tets.point_data = box.point_data;
  const QString small = dir_.filePath("small.vtu");
  write_volume_mesh(small.toStdString(), tets);
  int stale = 0;
  const auto check = [this, &stale] {
    const Eigen::Index n = session()->model(Role::Patient).domain.V.rows();
    for (int v : session()->planeSelection()) stale += v >= n;
  };
  const QMetaObject::Connection changed = connect(session(), &SessionModel::modelChanged, this, check);
  const QString error = openPatient(small);
  disconnect(changed);
  QVERIFY2(error.isEmpty(), qPrintable(error));
  QCOMPARE(session()->model(Role::Patient).domain.V.rows(), Eigen::Index(tets.num_vertices()));
  QCOMPARE(stale, 0);
  check();
  QCOMPARE(stale, 0);
}

void GuiTest::opensModelsFromFiles() {
  QVERIFY2(openBoxes(), qPrintable(error_));
  QCOMPARE(session()->model(Role::Patient).path, dir_.filePath("bent.vtu"));
  QCOMPARE(session()->model(Role::Patient).mesh.num_cells(), 16 * 6 * 12 * 6);  // hexes split into six tets
  QCOMPARE(session()->model(Role::Standard).mesh.num_cells(), 8 * 3 * 6);
  QCOMPARE(int(session()->constraints(Role::Standard).set.constraints.size()), 6);  // box.json, found beside it
}

void GuiTest::computesTheFields() {
  QVERIFY2(openBoxes(), qPrintable(error_));
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

void GuiTest::scriptedFieldStatesShowTheModels() {
  QVERIFY2(openBoxes(), qPrintable(error_));
  checkStates({"loaded", "plane", "fields", "glyphs"});
}

void GuiTest::transfersExportsAndReloads() {
  QVERIFY2(openBoxes(), qPrintable(error_));
  session()->removeConstraint(Role::Patient, 0);  // an edit to undo, and put back
  session()->undoStack()->undo();
  auto* undo = window_->findChild<QAction*>("Undo");
  QVERIFY(undo && !undo->isEnabled() && window_->findChild<QAction*>("Redo")->isEnabled());
  QVERIFY(window_->controller()->runTransfer());
  QVERIFY(window_->controller()->busy());
  // While it runs, the constraints stay as the transfer read them: no panel, no undo or redo, no features.
  QVERIFY(!window_->findChild<QWidget*>("constraintPanel")->isEnabled());
  QVERIFY(!window_->findChild<QAction*>("Redo")->isEnabled());
  QVERIFY(!window_->findChild<QAction*>("Facial_features")->isEnabled());
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY2(error_.isEmpty(), qPrintable(error_));
  QVERIFY(window_->findChild<QWidget*>("constraintPanel")->isEnabled());
  QVERIFY(window_->findChild<QAction*>("Redo")->isEnabled());
  const TransferResult* r = session()->transfer();
  QVERIFY(r);
  QVERIFY(session()->display().showHex);  // the result is shown at once
  QCOMPARE(window_->view(Role::Patient)->drawnHexCells(), r->patient_hex.num_cells());
  QCOMPARE(r->patient_hex.num_cells(), session()->model(Role::Standard).mesh.num_cells());

  // Quitting before the export asks; No keeps the window (and the result).
  bool asked = false;
  QTimer::singleShot(200, [&] {
    if (auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget())) {
      asked = box->text().contains("has not been exported");
      box->button(QMessageBox::No)->click();
    }
  });
  QVERIFY(!window_->close());
  QVERIFY(asked);
  QVERIFY(window_->isVisible() && session()->transfer());

  const QString path = dir_.filePath("patient_hex.vtu");
  QVERIFY(window_->controller()->exportHex(path));
  QVERIFY(session()->transferExported());
  const VolumeMesh reloaded = read_volume_mesh(path.toStdString());
  QCOMPARE(reloaded.num_cells(), r->patient_hex.num_cells());
  QCOMPARE(reloaded.num_vertices(), r->patient_hex.num_vertices());
  QCOMPARE(summarize(reloaded, element_quality(reloaded)).inverted, 0);
  QVERIFY(reloaded.cell_data.count("scaled_jacobian"));
  QVERIFY((reloaded.V - r->patient_hex.V).cwiseAbs().maxCoeff() < 1e-9);
  QVERIFY(window_->close());  // exported: quits without asking
}

// The same case through both front ends: the bundled patient opened in the application (the demo) and given to
// `facehex run --export`, with the defaults of both. The exported files are the same, byte for byte.
void GuiTest::exportWritesWhatRunExportWrites() {
  QVERIFY2(openDemo(), qPrintable(error_));
  QVERIFY2(runTransferAndWait(), qPrintable(error_));
  QVERIFY(session()->transfer());
  for (const char* ext : {"inp", "vtu"})
    QVERIFY(window_->controller()->exportHex(dir_.filePath(QString("gui.") + ext)));

  const QString cli_out = dir_.filePath("cli");
  const std::string command = std::string(FACEHEX_CLI) + " run " + default_patient().mesh + " -o " +
                              cli_out.toStdString() + " --export inp > /dev/null 2>&1";
  QCOMPARE(std::system(command.c_str()), 0);
  const auto bytes = [](const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
  };
  const QByteArray gui_inp = bytes(dir_.filePath("gui.inp"));
  QVERIFY(!gui_inp.isEmpty());
  QVERIFY2(gui_inp == bytes(cli_out + "/patient_hex.inp"), "the .inp files differ");

  const VolumeMesh gui = read_volume_mesh(dir_.filePath("gui.vtu").toStdString());
  const VolumeMesh cli = read_volume_mesh((cli_out + "/patient_hex.vtu").toStdString());
  QCOMPARE(gui.C, cli.C);
  QCOMPARE(gui.V, cli.V);
  QCOMPARE(gui.point_data.size(), cli.point_data.size());
  for (const auto& [name, a] : cli.point_data) {
    QVERIFY2(gui.point_data.count(name), name.c_str());
    QVERIFY2(gui.point_data.at(name) == a, name.c_str());
  }
  QCOMPARE(gui.cell_data.size(), cli.cell_data.size());
  for (const auto& [name, a] : cli.cell_data) {
    QVERIFY2(gui.cell_data.count(name), name.c_str());
    QVERIFY2(gui.cell_data.at(name) == a, name.c_str());
  }
  for (const char* array : {"moved_from_mapping", "uvw", "side_mask"}) QVERIFY2(gui.point_data.count(array), array);
  QVERIFY(gui.cell_data.count("dihedral_change"));
}

void GuiTest::thresholdIsolatesBadCells() {
  QVERIFY2(openBoxes(), qPrintable(error_));
  QVERIFY2(runTransferAndWait(), qPrintable(error_));
  DisplaySettings d = session()->display();
  d.showHex = true;
  d.measure = QualityMeasure::ScaledJacobian;
  d.threshold = 1.0;
  session()->setDisplay(d);
  ModelView* view = window_->view(Role::Patient);
  QCOMPARE(view->drawnHexCells(), session()->transfer()->patient_hex.num_cells());
  // A threshold between the best and the worst cell of the bent box shows the cells at or below it, some but not all.
  const Eigen::VectorXd sj = session()->transfer()->patient_hex.cell_data.at("scaled_jacobian").col(0);
  d.threshold = 0.5 * (sj.minCoeff() + sj.maxCoeff());
  session()->setDisplay(d);
  const int below = int((sj.array() <= d.threshold).count());
  QVERIFY(below > 0 && below < sj.size());
  QCOMPARE(view->drawnHexCells(), below);
  QVERIFY(!view->planeWidgetEnabled());  // the hex display has no plane
  session()->setDisplay(DisplaySettings{});
  QVERIFY(view->planeWidgetEnabled());
}

void GuiTest::badFilesGiveTheCoreMessageAndTheAppKeepsRunning() {
  QVERIFY2(openDemo(), qPrintable(error_));
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

  // A tet model is a patient, not a standard: refused with the reason, the standard stays.
  const int standardCells = session()->model(Role::Standard).mesh.num_cells();
  QVERIFY(window_->controller()->openStandard(QString::fromStdString(default_patient().mesh)));
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY(takeError().contains("has no hexahedra: a standard is a hex-dominant mesh"));
  QCOMPARE(session()->model(Role::Standard).mesh.num_cells(), standardCells);

  QVERIFY(!window_->controller()->loadConstraints(Role::Patient, garbage, false));
  QVERIFY(takeError().startsWith(garbage));
  QVERIFY(window_->controller()->openPatient(dir_.filePath("missing.vtu")));
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY(takeError().contains("missing.vtu"));

  // A bad CT: the message `facehex segment` prints.
  const QString badCt = dir_.filePath("bad.mhd");
  QFile header(badCt);
  QVERIFY(header.open(QIODevice::WriteOnly));
  header.write("NDims = 3\nDimSize = 4 4 4\nElementType = MET_SHORT\nElementDataFile = missing.raw\n");
  header.close();
  try {
    load_patient_model(badCt.toStdString());
    cliMessage.clear();
  } catch (const Error& e) {
    cliMessage = e.what();
  }
  QVERIFY(!cliMessage.empty());
  QCOMPARE(openPatient(badCt), QString::fromStdString(cliMessage));
  QCOMPARE(session()->model(Role::Patient).mesh.num_vertices(), vertices);
  QVERIFY(window_->isVisible());
  QVERIFY(!window_->controller()->busy());
}

void GuiTest::undoBringsBackTheResultAnEditMadeStale() {
  QVERIFY2(openBoxes(), qPrintable(error_));
  QVERIFY2(runTransferAndWait(), qPrintable(error_));
  auto* exportAction = window_->findChild<QAction*>("Export_hex_mesh");
  const Eigen::MatrixXd first = session()->transfer()->patient_hex.V;
  QVERIFY(exportAction->isEnabled());

  // A rename changes the set: the result is stale, gone from view and from Export; the undo brings it back.
  Constraint renamed = session()->constraints(Role::Patient).set.constraints.at(0);
  renamed.name = "renamed";
  session()->updateConstraint(Role::Patient, 0, renamed);
  QVERIFY(!session()->transfer() && !session()->parameterization(Role::Patient));
  QVERIFY(!exportAction->isEnabled());
  QCOMPARE(window_->view(Role::Patient)->drawnHexCells(), -1);
  session()->undoStack()->undo();
  QVERIFY(session()->transfer() && session()->parameterization(Role::Patient));
  QVERIFY(session()->transfer()->patient_hex.V == first);
  QVERIFY(exportAction->isEnabled());
  QVERIFY(!session()->transferExported());
  QCOMPARE(window_->view(Role::Patient)->drawnHexCells(), session()->transfer()->patient_hex.num_cells());

  // A second transfer after an edit: undo and redo swap the two results, each with its constraints and its export.
  session()->undoStack()->redo();
  QVERIFY(!session()->transfer());
  const QString path = dir_.filePath("renamed.vtu");
  QVERIFY2(runTransferAndWait(), qPrintable(error_));
  QVERIFY(window_->controller()->exportHex(path));
  const Eigen::MatrixXd second = session()->transfer()->patient_hex.V;
  session()->undoStack()->undo();
  QVERIFY(session()->transfer() && session()->transfer()->patient_hex.V == first);
  QVERIFY(!session()->transferExported());
  session()->undoStack()->redo();
  QVERIFY(session()->transfer() && session()->transfer()->patient_hex.V == second);
  QVERIFY(session()->transferExported());

  // Showing or hiding a constraint makes nothing stale; opening another model drops what was set aside.
  session()->setConstraintVisible(Role::Patient, 1, false);
  QVERIFY(session()->transfer());
  QCOMPARE(openPatient(dir_.filePath("bent.vtu")), QString());
  QVERIFY(!session()->transfer());
  session()->addSideConstraints(Role::Patient);  // an edit to undo
  session()->undoStack()->undo();
  QVERIFY(!session()->transfer());
}

void GuiTest::replacingAnUnexportedResultAsksFirst() {
  QVERIFY2(openBoxes(), qPrintable(error_));
  QVERIFY2(runTransferAndWait(), qPrintable(error_));
  const QString standard = session()->model(Role::Standard).path;
  auto* choice = window_->findChild<QComboBox*>("standardChoice");
  const int bundled = choice->findData(QString::fromStdString(default_standard().name));
  QVERIFY(bundled >= 0);

  // Picking another standard: No keeps the standard, the result and the box's name in the choice.
  answerNextQuestion(QMessageBox::No);
  choice->setCurrentIndex(bundled);
  emit choice->activated(bundled);
  QVERIFY2(question_.contains("has not been exported"), qPrintable(question_));
  QVERIFY(!window_->controller()->busy());
  QCOMPARE(session()->model(Role::Standard).path, standard);
  QCOMPARE(choice->currentText(), session()->model(Role::Standard).name);
  QVERIFY(session()->transfer());

  // Open demo: No keeps everything; Yes opens it.
  auto* demo = window_->findChild<QAction*>("Open_demo");
  answerNextQuestion(QMessageBox::No);
  demo->trigger();
  QVERIFY2(question_.contains("has not been exported"), qPrintable(question_));
  QVERIFY(!window_->controller()->busy() && session()->transfer());
  answerNextQuestion(QMessageBox::Yes);
  demo->trigger();
  QVERIFY(!question_.isEmpty());
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY2(error_.isEmpty(), qPrintable(error_));
  QVERIFY(!session()->transfer());
  QCOMPARE(session()->model(Role::Standard).name, QString::fromStdString(default_standard().name));
}

void GuiTest::headerTextMovesNoWidget() {
  QVERIFY2(openDemo(), qPrintable(error_));
  fitToLaptopScreen();
  // Every widget but the rows of the lists (their cell editors), where it is in the window.
  auto layout = [this] {
    std::map<QString, QRect> where;
    int n = 0;
    for (QWidget* w : window_->findChildren<QWidget*>()) {
      if (!w->isVisible()) continue;
      bool inList = false;
      for (QWidget* p = w->parentWidget(); p && !inList; p = p->parentWidget())
        inList = qobject_cast<QAbstractItemView*>(p) != nullptr;
      if (!inList)
        where[QString("%1 %2 %3").arg(w->metaObject()->className(), w->objectName()).arg(n++)] =
            QRect(w->mapTo(window_.get(), QPoint(0, 0)), w->size());
    }
    return where;
  };
  auto* header = window_->findChild<QLabel*>("patientHeader");
  const std::map<QString, QRect> before = layout();
  DisplaySettings d = session()->display();
  for (const auto& [change, note] : std::vector<std::pair<std::function<void()>, QString>>{
           {[&] { d.showHex = true; }, "no hex mesh yet"}, {[&] { d = {}, d.field = 0; }, "fields not computed"}}) {
    change();
    session()->setDisplay(d);
    QTest::qWait(100);
    QVERIFY2(header->text().contains(note), qPrintable(header->text()));
    const std::map<QString, QRect> after = layout();
    QCOMPARE(after.size(), before.size());
    for (auto a = after.begin(), b = before.begin(); a != after.end(); ++a, ++b)
      QVERIFY2(a->first == b->first && a->second == b->second,
               qPrintable(QString("%1 moved with '%2'").arg(b->first, note)));
  }
}

void GuiTest::everythingIsReachableOnALaptopScreen() {
  QVERIFY2(openDemo(), qPrintable(error_));
  const QRect screen = fitToLaptopScreen();
  const QRect frame = window_->frameGeometry();
  QVERIFY2(screen.contains(frame), qPrintable(QString("the window (%1,%2 %3x%4, at least %5x%6) is off the screen")
                                                  .arg(frame.x())
                                                  .arg(frame.y())
                                                  .arg(frame.width())
                                                  .arg(frame.height())
                                                  .arg(window_->minimumSizeHint().width())
                                                  .arg(window_->minimumSizeHint().height())));
  // Every control of the right column is on the screen, or the panel it is in scrolls to bring it there.
  int controls = 0;
  for (const char* dock : {"constraintsDock", "displayDock"})
    for (QWidget* w : window_->findChild<QDockWidget*>(dock)->widget()->findChildren<QWidget*>()) {
      const bool control = qobject_cast<QAbstractButton*>(w) || qobject_cast<QComboBox*>(w) ||
                           qobject_cast<QAbstractSpinBox*>(w) || qobject_cast<QSlider*>(w) ||
                           qobject_cast<QLineEdit*>(w) || qobject_cast<QTableWidget*>(w);
      bool inList = false;
      for (QWidget* p = w->parentWidget(); p && !inList; p = p->parentWidget())
        inList = qobject_cast<QAbstractItemView*>(p) != nullptr;
      if (!control || inList || !w->isVisible()) continue;
      ++controls;
      QScrollArea* area = nullptr;
      for (QWidget* p = w->parentWidget(); p && !area; p = p->parentWidget()) area = qobject_cast<QScrollArea*>(p);
      if (area) {  // scrolled to show all of it (ensureWidgetVisible shows a spin box's text cursor only)
        const QPoint centre = w->mapTo(area->widget(), QPoint(w->width() / 2, w->height() / 2));
        area->ensureVisible(centre.x(), centre.y(), w->width() / 2 + 1, w->height() / 2 + 1);
      }
      QApplication::processEvents();
      const QRect global(w->mapToGlobal(QPoint(0, 0)), w->size());
      const QWidget* shown = area ? area->viewport() : w->window();
      const QRect viewport(shown->mapToGlobal(QPoint(0, 0)), shown->size());
      const QString name = QString("%1 '%2' at %3,%4 %5x%6")
                               .arg(w->metaObject()->className(), w->objectName())
                               .arg(global.x())
                               .arg(global.y())
                               .arg(global.width())
                               .arg(global.height());
      QVERIFY2(screen.contains(global), qPrintable(name + " is off the screen"));
      QVERIFY2(viewport.contains(global) || (w->height() > viewport.height() && viewport.intersects(global)),
               qPrintable(name + " cannot be scrolled into view"));
    }
  QVERIFY(controls > 20);
  // The progress bar and the cancel button of a running job.
  QVERIFY(window_->controller()->computeFields());
  QTest::qWait(200);
  for (QWidget* w : {static_cast<QWidget*>(window_->findChild<QProgressBar*>()),
                     static_cast<QWidget*>(window_->findChild<QPushButton*>("cancelButton"))}) {
    QVERIFY(w->isVisible());
    QVERIFY(screen.contains(QRect(w->mapToGlobal(QPoint(0, 0)), w->size())));
  }
  window_->controller()->cancel();
  QVERIFY(window_->controller()->waitUntilIdle());
}

void GuiTest::windowLayoutIsKeptBetweenSessions() {
  window_->resize(1300, 800);
  auto* dock = window_->findChild<QDockWidget*>("constraintsDock");
  window_->resizeDocks({dock}, {380}, Qt::Horizontal);
  QTest::qWait(200);
  const QSize size = window_->size();
  const int width = dock->width();
  QVERIFY(window_->close());
  MainWindow next;
  next.restoreWindowState();
  next.show();
  QVERIFY(QTest::qWaitForWindowExposed(&next));
  QTest::qWait(200);
  QCOMPARE(next.size(), size);
  QCOMPARE(next.findChild<QDockWidget*>("constraintsDock")->width(), width);
}

void GuiTest::constraintListShowsAllAutomaticConstraints() {
  QVERIFY2(openDemo(), qPrintable(error_));
  fitToLaptopScreen();
  auto* table = window_->findChild<QTableWidget*>("constraintTable");
  QCOMPARE(table->rowCount(), 6 + int(feature_specs().size()));
  QCOMPARE(table->verticalScrollBar()->maximum(), 0);  // nothing to scroll to: every row is in view
  for (int row = 0; row < table->rowCount(); ++row)
    QVERIFY2(table->viewport()->rect().contains(table->visualRect(table->model()->index(row, 1))),
             qPrintable(table->item(row, 1)->text()));
}

void GuiTest::messageLogKeepsOutcomesAndShowsWhatTheyName() {
  QVERIFY2(openBoxes(), qPrintable(error_));
  MessageLog* log = window_->messageLog();
  window_->findChild<QTabWidget*>("analysisTabs")->setCurrentWidget(log);
  auto find = [log](const QString& start) -> QTreeWidgetItem* {
    for (int i = log->topLevelItemCount() - 1; i >= 0; --i)
      if (log->topLevelItem(i)->text(1).startsWith(start)) return log->topLevelItem(i);
    return nullptr;
  };
  QVERIFY(find("Opened the standard") && find("Opened the patient"));
  QVERIFY2(runTransferAndWait(), qPrintable(error_));
  QTreeWidgetItem* transfer = find("Transfer done");
  QVERIFY(transfer);
  QStringList detail;
  for (int i = 0; i < transfer->childCount(); ++i) detail << transfer->child(i)->text(1);
  const QualitySummary& q = session()->transfer()->patient_quality.summary;
  for (const QString& fact : {QString("%L1 cells").arg(q.cells), QString("%1 inverted").arg(q.inverted),
                              QString("shape mean %1").arg(q.shape_mean, 0, 'f', 3), QString("time ")})
    QVERIFY2(detail.filter(fact).size() == 1, qPrintable(fact + " not in: " + detail.join(" | ")));
  const int outcomes = log->topLevelItemCount();

  auto click = [log](QTreeWidgetItem* item) {
    log->scrollToItem(item);
    QTest::mouseClick(log->viewport(), Qt::LeftButton, {}, log->visualItemRect(item).center());
  };
  // Two constraints that give one vertex two values of u: the error names the vertex, and a click shows it.
  const LoadedModel& patient = session()->model(Role::Patient);
  PlanePose pose = session()->plane();
  pose.origin = patient.domain.V.colwise().minCoeff().transpose();
  pose.normal = Eigen::Vector3d::UnitX();
  pose.band = 2.0;
  pose.region = "volume";
  session()->setPlane(pose);
  session()->addPlaneConstraint(Role::Patient, "clash", 0, 0.5);
  QVERIFY(window_->controller()->computeFields());
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY(takeError().contains("gets two values"));
  QTreeWidgetItem* clash = log->topLevelItem(log->topLevelItemCount() - 1);
  QVERIFY(clash->text(1).contains("gets two values"));
  QCOMPARE(log->topLevelItemCount(), outcomes + 1);  // the transfer's outcome is still there
  const std::optional<Highlight> named = namedInMessage(clash->text(1), *session());
  QVERIFY(named && named->role == Role::Patient && named->vertex >= 0);
  QVERIFY(std::abs(patient.domain.V(named->vertex, 0) - pose.origin.x()) <= 1.0);  // in the clashing slab
  session()->setActiveRole(Role::Standard);
  click(clash);
  QCOMPARE(session()->activeRole(), Role::Patient);
  QVERIFY(session()->highlight() && *session()->highlight() == *named);
  QCOMPARE(window_->view(Role::Patient)->highlightedPoints(), 1);
  QCOMPARE(window_->view(Role::Standard)->highlightedPoints(), 0);

  // A constraint that selects nothing: the error names it, and a click selects its row.
  session()->undoStack()->undo();
  pose.origin -= Eigen::Vector3d(100, 0, 0);
  session()->setPlane(pose);
  session()->addPlaneConstraint(Role::Patient, "nowhere", 0, 0.5);
  QVERIFY(window_->controller()->computeFields());
  QVERIFY(window_->controller()->waitUntilIdle());
  QVERIFY(takeError().contains("'nowhere' selects no vertex"));
  click(log->topLevelItem(log->topLevelItemCount() - 1));
  const int last = constraintCount() - 1;
  QVERIFY(session()->highlight() && session()->highlight()->constraint == last);
  QCOMPARE(window_->findChild<QTableWidget*>("constraintTable")->currentRow(), last);
  QCOMPARE(log->topLevelItemCount(), outcomes + 2);
}

void GuiTest::checkStates(const QStringList& states) {
  // The middle third of each 3D view must mostly show something other than the background (a vertical gradient:
  // the same row at the view's left edge is the reference). A grid of samples, not one pixel: the middle pixel may
  // look through an opening of the face (the mouth slit) at the background.
  for (const QString& name : states) {
    QVERIFY2(driveToState(*window_, *scriptedStateFromName(name)), qPrintable(error_));
    window_->snapshot();
    for (Role r : kRoles) {
      const QImage image = window_->view(r)->grab().toImage();
      int drawn = 0, samples = 0;
      for (int i = 0; i <= 8; ++i)
        for (int j = 0; j <= 8; ++j, ++samples) {
          const int row = image.height() / 3 + i * image.height() / 24,
                    col = image.width() / 3 + j * image.width() / 24;
          drawn += image.pixel(2, row) != image.pixel(col, row);
        }
      QVERIFY2(drawn * 2 > samples, qPrintable(name + " " + roleName(r) + ": nothing drawn in the middle"));
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

#include "ui/main_window.h"

#include <QAction>
#include <QCloseEvent>
#include <QComboBox>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QGuiApplication>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QPainter>
#include <QProgressBar>
#include <QPushButton>
#include <QScreen>
#include <QScrollArea>
#include <QSettings>
#include <QSplitter>
#include <QStatusBar>
#include <QTabWidget>
#include <QToolBar>
#include <QUndoGroup>
#include <QUndoStack>
#include <algorithm>
#include <utility>

#include "core/face/landmark_file.h"
#include "core/io/mesh_io.h"
#include "core/segment/ct_volume.h"
#include "core/util/resources.h"
#include "ui/angle_histogram.h"
#include "ui/autosave.h"
#include "ui/constraint_panel.h"
#include "ui/display_panel.h"
#include "ui/message_log.h"
#include "ui/model_view.h"
#include "ui/quality_panel.h"
#include "ui/segmentation_dialog.h"
#include "ui/transfer_controller.h"

namespace facehex::gui {
namespace {

constexpr int kMaxRecent = 8;
const char* kRecentKey = "recentPatients";
const char* kGeometryKey = "window/geometry";
const char* kStateKey = "window/state";
const char* kBusy = QT_TRANSLATE_NOOP("facehex::gui::MainWindow", "Busy: wait for the running job or cancel it");

// A panel in a scroll area: on a screen too small for it, it scrolls instead of pushing the window off the screen.
QScrollArea* scrolling(QWidget* panel) {
  auto* area = new QScrollArea;
  area->setWidget(panel);
  area->setWidgetResizable(true);
  area->setFrameShape(QFrame::NoFrame);
  return area;
}

QString filter(const QString& what, const std::vector<std::string>& extensions) {
  QStringList patterns;
  for (const auto& e : extensions) patterns << "*" + QString::fromStdString(e);
  return QString("%1 (%2)").arg(what, patterns.join(' '));
}

}  // namespace

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent),
      session_(new SessionModel(this)),
      controller_(new TransferController(session_, this)),
      autosave_(new ConstraintAutosave(session_, this)),
      reportError_([this](const QString& message) { QMessageBox::critical(this, tr("FaceHex"), message); }) {
  setObjectName("mainWindow");
  setWindowTitle(tr("FaceHex \u2014 patient-specific hex meshes of the face"));
  setAcceptDrops(true);
  views_[static_cast<int>(Role::Standard)] = new ModelView(session_, Role::Standard, this);
  views_[static_cast<int>(Role::Patient)] = new ModelView(session_, Role::Patient, this);
  auto* splitter = new QSplitter(Qt::Horizontal, this);
  splitter->addWidget(view(Role::Standard));
  splitter->addWidget(view(Role::Patient));
  splitter->setChildrenCollapsible(false);
  splitter->setSizes({1, 1});
  setCentralWidget(splitter);
  // Rotating one view turns the other the same way (each keeps its own centre and zoom).
  for (Role r : kRoles) {
    ModelView* other = view(r == Role::Standard ? Role::Patient : Role::Standard);
    connect(view(r), &ModelView::cameraOrientationChanged, other, &ModelView::setCameraOrientation);
    connect(view(r), &ModelView::landmarkMoved, this, &MainWindow::moveLandmark);
  }

  segmentationDialog_ = new SegmentationDialog(this);
  connect(segmentationDialog_, &QDialog::accepted, this, [this] {
    segmenting_ = controller_->openPatient(segmentationCt_, segmentationDialog_->options());
    if (!segmenting_) note(tr(kBusy));
  });
  createActions();
  createMenusAndToolbar();
  createDocks();
  createStatusBar();

  connect(controller_, &TransferController::failed, this, [this](const QString& m) {
    reportError(m);
    // A segmentation the dialog started: the dialog again, as the user left it, saying why and which of its settings
    // the error names, for the user to change one and segment again.
    if (std::exchange(segmenting_, false)) {
      segmentationDialog_->showFailure(m);
      segmentationDialog_->open();
    }
  });
  connect(controller_, &TransferController::finished, this, [this](const QString& m, const QStringList& detail) {
    segmenting_ = false;
    statusBar()->showMessage(m);
    statusBar()->setToolTip(m);  // the whole line, when the bar cuts it (a segmentation lists its thresholds and cuts)
    log_->add(MessageLog::Kind::Outcome, m, detail);
  });
  connect(controller_, &TransferController::busyChanged, this, &MainWindow::updateActions);
  connect(controller_, &TransferController::progress, this, [this](const QString& stage, double f) {
    progress_->setValue(static_cast<int>(1000 * f));
    progress_->setFormat(stage + "  %p%");
  });
  connect(autosave_, &ConstraintAutosave::failed, this,
          [this](const QString& m) { note(tr("Autosave failed: %1").arg(m)); });
  connect(session_, &SessionModel::modelChanged, this, [this](Role r) {
    updateSizes();
    updateActions();
    if (r == Role::Standard) updateStandardChoice();
    if (r == Role::Patient && !session_->model(r).path.isEmpty()) addRecent(session_->model(r).path);
  });
  connect(session_, &SessionModel::resultsChanged, this, &MainWindow::updateActions);
  connect(session_, &SessionModel::constraintsChanged, this, &MainWindow::updateActions);
  updateSizes();
  updateActions();
  if (const QScreen* screen = QGuiApplication::primaryScreen()) fitTo(screen->availableGeometry());
}

MainWindow::~MainWindow() = default;

void MainWindow::fitTo(const QRect& available) {
  // The screen's free area (a laptop's 1366 x 768 included) up to a size where the views stop gaining from it: every
  // dock and the progress bar stay on the screen, the constraints panel scrolling when it needs more. The display
  // panel gets its height, the constraints the rest of the column.
  const QSize size = QSize(1920, 1200).boundedTo(available.size());
  resize(size);
  move(available.topLeft() + QPoint(available.width() - size.width(), available.height() - size.height()) / 2);
  const int display = displayDock_->sizeHint().height();
  resizeDocks({constraintsDock_}, {std::min(470, size.width() * 35 / 100)}, Qt::Horizontal);
  resizeDocks({constraintsDock_, displayDock_}, {size.height() - display, display}, Qt::Vertical);
  resizeDocks({analysisDock_}, {size.height() / 5}, Qt::Vertical);
}

void MainWindow::restoreWindowState() {
  const QSettings settings;
  restoreGeometry(settings.value(kGeometryKey).toByteArray());
  restoreState(settings.value(kStateKey).toByteArray());
}

void MainWindow::reportError(const QString& message) {
  log_->add(MessageLog::Kind::Error, message);
  reportError_(message);
}

void MainWindow::note(const QString& text) {
  statusBar()->showMessage(text);
  log_->add(MessageLog::Kind::Note, text);
}

bool MainWindow::mayDiscardResult(const QString& action) {
  return !session_->transfer() || session_->transferExported() ||
         QMessageBox::question(
             this, action,
             tr("The transferred hex mesh has not been exported and will be lost. %1 anyway?").arg(action),
             QMessageBox::Yes | QMessageBox::No, QMessageBox::No) == QMessageBox::Yes;
}

void MainWindow::createActions() {
  auto action = [this](const QString& text, const QKeySequence& key, auto slot) {
    auto* a = new QAction(text, this);
    if (!key.isEmpty()) a->setShortcut(key);
    connect(a, &QAction::triggered, this, slot);
    return a;
  };
  openPatient_ = action(tr("Open &patient..."), QKeySequence::Open, &MainWindow::openPatientDialog);
  openPatient_->setToolTip(
      tr("Open a head CT (MetaImage, NIfTI, NRRD: segmented on opening), a patient tet model "
         "or a closed surface (VTU, VTK, Gmsh, TetGen, ANSYS, STL, OBJ, PLY, VTP)"));
  resegment_ = action(tr("Segment &again..."), QKeySequence(), [this] {
    if (session_->hasModel(Role::Patient) && mayDiscardResult(tr("Segment again")))
      askSegmentation(session_->model(Role::Patient).path);
  });
  resegment_->setToolTip(
      tr("Segment the patient's CT again with other thresholds or cuts (starting from the ones used)"));
  openDicom_ = action(tr("Open &DICOM folder..."), QKeySequence(), &MainWindow::openDicomDialog);
  openDicom_->setToolTip(tr("Open a head CT stored as a folder of DICOM slices (segmented on opening)"));
  openDemo_ = action(tr("Open &demo"), QKeySequence(), [this] {
    if (mayDiscardResult(tr("Open the demo"))) controller_->openDemo();
  });
  openStandardFile_ = action(tr("Open standard &file..."), QKeySequence(), [this] { onStandardChosen(-1); });
  loadConstraints_ = action(tr("&Load constraints..."), QKeySequence(), [this] { constraintsDialog(false); });
  mergeConstraints_ = action(tr("&Merge constraints..."), QKeySequence(), [this] { constraintsDialog(true); });
  saveConstraints_ = action(tr("&Save constraints..."), QKeySequence::Save, &MainWindow::saveConstraintsDialog);
  recover_ = action(tr("&Recover autosaved"), QKeySequence(), &MainWindow::recoverAutosave);
  features_ = action(tr("Facial &features"), QKeySequence(),
                     [this] { controller_->placeFeatureConstraints(session_->activeRole(), session_->plane().band); });
  features_->setToolTip(
      tr("Place the feature lines (mid-sagittal, eyebrow, below the nose, lips) at the model's "
         "landmarks again, valued as the standard's, selected with the band width above; they "
         "replace the ones of the same names"));
  loadLandmarks_ = action(tr("Landmarks from &file..."), QKeySequence(), &MainWindow::loadLandmarksDialog);
  loadLandmarks_->setToolTip(
      tr("Place the feature lines at the landmarks of a file (FaceHex .json or 3D Slicer .mrk.json), as the CLI's "
         "--landmarks does"));
  saveLandmarks_ = action(tr("Save l&andmarks..."), QKeySequence(), &MainWindow::saveLandmarksDialog);
  saveLandmarks_->setToolTip(tr("Save the landmarks the feature lines are placed at (found, loaded or moved)"));
  recover_->setToolTip(tr("Load the constraints autosaved after the last edit of this model (after a crash)"));
  export_ = action(tr("&Export hex mesh..."), QKeySequence(tr("Ctrl+E")), &MainWindow::exportDialog);
  screenshot_ = action(tr("Save screens&hot..."), QKeySequence(), &MainWindow::screenshotDialog);
  quit_ = action(tr("&Quit"), QKeySequence::Quit, &QWidget::close);
  // Undo and redo through a group whose stack is taken away while a job runs: an edit then would be thrown away
  // with the job's result (its inputs changed), so none can be made.
  undoGroup_ = new QUndoGroup(this);
  undoGroup_->addStack(session_->undoStack());
  undoGroup_->setActiveStack(session_->undoStack());
  undo_ = undoGroup_->createUndoAction(this, tr("&Undo"));
  undo_->setObjectName("Undo");
  undo_->setShortcut(QKeySequence::Undo);
  undo_->setIconText(tr("Undo"));  // the toolbar keeps it short; the menu and tooltip say what is undone
  redo_ = undoGroup_->createRedoAction(this, tr("&Redo"));
  redo_->setObjectName("Redo");
  redo_->setShortcut(QKeySequence::Redo);
  redo_->setIconText(tr("Redo"));
  computeFields_ = action(tr("Compute &fields"), QKeySequence(tr("F5")), [this] { controller_->computeFields(); });
  computeFields_->setToolTip(tr("Compute u, v, w on both models with their constraints (paper 3.2-3.3)"));
  transfer_ = action(tr("&Transfer"), QKeySequence(tr("F6")), [this] { controller_->runTransfer(); });
  transfer_->setToolTip(tr("Map the standard hex mesh onto the patient (paper 3.4)"));
  cancel_ = action(tr("&Cancel"), QKeySequence(Qt::Key_Escape), [this] { controller_->cancel(); });
  // A checkable option of the transfer: `set` writes it into the controller's TransferOptions, `get` reads it.
  auto option = [this, &action](const QString& text, const QString& tip, auto set, auto get) {
    QAction* a = action(text, QKeySequence(), [this, set](bool on) {
      TransferOptions o = controller_->options();
      set(o, on);
      controller_->setOptions(o);
    });
    a->setCheckable(true);
    a->setChecked(get(controller_->options()));
    a->setToolTip(tip);
    return a;
  };
  allowInverted_ = option(
      tr("Continue despite &inverted tets"),
      tr("Map even when the patient parameterization folds (the CLI's --allow-inverted)"),
      [](TransferOptions& o, bool on) { o.allow_inverted_parameterization = on; },
      [](const TransferOptions& o) { return o.allow_inverted_parameterization; });
  shapeRelaxation_ = option(
      tr("Keep the standard's cell &shapes"),
      tr("After the mapping, slide vertices along the patient towards the standard's cell "
         "shapes (the CLI's --shape-relaxation; off: the paper's plain mapping)"),
      [](TransferOptions& o, bool on) { o.shape_relaxation = on; },
      [](const TransferOptions& o) { return o.shape_relaxation; });
  registeredSkin_ = option(
      tr("&Register the skins"),
      tr("Register the standard's skin onto the patient's and give the patient's skin the standard's parameters "
         "there, in place of the feature lines found at the landmarks (the CLI's --skin-correspondence registered)"),
      [](TransferOptions& o, bool on) {
        o.skin_correspondence = on ? SkinCorrespondence::registered : SkinCorrespondence::features;
      },
      [](const TransferOptions& o) { return o.skin_correspondence == SkinCorrespondence::registered; });
  pullLandmarks_ = option(
      tr("&Pull the found landmarks"),
      tr("With the skins registered: the landmarks found (or estimated) on the patient pull the registration towards "
         "the standard's and the standard's landmarks are kept where the mapping put them, so that its eyes, nose and "
         "mouth land on the patient's (the CLI's --pull-found-landmarks on|off; the transfer's message says where "
         "they landed)"),
      [](TransferOptions& o, bool on) { o.pull_found_landmarks = on; },
      [](const TransferOptions& o) { return o.pull_found_landmarks; });
  about_ = action(tr("&About FaceHex"), QKeySequence(), &MainWindow::about);
  for (QAction* a : {openPatient_, resegment_, openDicom_, openDemo_, loadConstraints_, mergeConstraints_,
                     saveConstraints_, export_, computeFields_, transfer_, cancel_, recover_, features_, loadLandmarks_,
                     saveLandmarks_, registeredSkin_, pullLandmarks_})
    a->setObjectName(a->text().remove('&').remove("...").replace(' ', '_'));
}

void MainWindow::createMenusAndToolbar() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(openPatient_);
  file->addAction(openDicom_);
  file->addAction(resegment_);
  recentMenu_ = file->addMenu(tr("Open &recent"));
  file->addAction(openDemo_);
  QMenu* standards = file->addMenu(tr("Open &standard"));
  for (const BundledModel& s : bundled_standards()) {
    const QString name = QString::fromStdString(s.name);
    standards->addAction(name, this, [this, name] { onStandardChosen(standardChoice_->findData(name)); });
  }
  standards->addSeparator();
  standards->addAction(openStandardFile_);
  file->addSeparator();
  for (QAction* a : {loadConstraints_, mergeConstraints_, saveConstraints_, recover_}) file->addAction(a);
  file->addSeparator();
  for (QAction* a : {loadLandmarks_, saveLandmarks_}) file->addAction(a);
  file->addSeparator();
  file->addAction(export_);
  file->addAction(screenshot_);
  file->addSeparator();
  file->addAction(quit_);
  QMenu* edit = menuBar()->addMenu(tr("&Edit"));
  edit->addAction(undo_);
  edit->addAction(redo_);
  QMenu* run = menuBar()->addMenu(tr("&Run"));
  for (QAction* a : {computeFields_, transfer_, cancel_}) run->addAction(a);
  run->addSeparator();
  run->addAction(allowInverted_);
  run->addAction(shapeRelaxation_);
  run->addAction(registeredSkin_);
  run->addAction(pullLandmarks_);
  // One checkable entry per landmark, checked while it may pull (the CLI's --landmarks-not-pulled lists the others).
  QMenu* pulling = run->addMenu(tr("&Landmarks that pull"));
  pulling->setObjectName("Landmarks_that_pull");
  for (const std::string& name : landmark_names()) {
    QAction* a = pulling->addAction(QString::fromStdString(name));
    a->setCheckable(true);
    const std::vector<std::string>& out = controller_->options().landmarks_not_pulled;
    a->setChecked(std::find(out.begin(), out.end(), name) == out.end());
    a->setToolTip(
        tr("Unchecked: this landmark, found or given, does not pull the registration and lands where the "
           "skins' shapes put it (the CLI's --landmarks-not-pulled)"));
    connect(a, &QAction::toggled, this, [this, name](bool on) {
      TransferOptions o = controller_->options();
      std::vector<std::string>& left_out = o.landmarks_not_pulled;
      left_out.erase(std::remove(left_out.begin(), left_out.end(), name), left_out.end());
      if (!on) left_out.push_back(name);
      controller_->setOptions(o);
    });
  }
  menuBar()->addMenu(tr("&Help"))->addAction(about_);
  rebuildRecentMenu();

  QToolBar* tools = addToolBar(tr("Main"));
  tools->setObjectName("mainToolbar");
  tools->setToolButtonStyle(Qt::ToolButtonTextOnly);
  tools->addAction(openPatient_);
  tools->addWidget(new QLabel(tr("  Standard: "), this));
  standardChoice_ = new QComboBox(this);
  standardChoice_->setObjectName("standardChoice");
  standardChoice_->setMinimumContentsLength(18);
  for (const BundledModel& s : bundled_standards())  // the bundled ones first, then any file
    standardChoice_->addItem(QString::fromStdString(s.name), QString::fromStdString(s.name));
  standardChoice_->insertSeparator(standardChoice_->count());
  standardChoice_->addItem(tr("Other file..."));
  standardChoice_->setCurrentIndex(-1);
  connect(standardChoice_, qOverload<int>(&QComboBox::activated), this, &MainWindow::onStandardChosen);
  tools->addWidget(standardChoice_);
  tools->addSeparator();
  for (QAction* a : {undo_, redo_}) tools->addAction(a);
  tools->addSeparator();
  for (QAction* a : {computeFields_, transfer_, export_, screenshot_}) tools->addAction(a);
}

void MainWindow::createDocks() {
  constraintPanel_ = new ConstraintPanel(
      session_,
      {features_, loadLandmarks_, saveLandmarks_, loadConstraints_, mergeConstraints_, saveConstraints_, recover_},
      this);
  // The panels on the right run the full height; the analysis tabs sit under the views only.
  setCorner(Qt::BottomRightCorner, Qt::RightDockWidgetArea);
  auto dock = [this](const QString& title, const char* name, QWidget* content, Qt::DockWidgetArea area) {
    auto* d = new QDockWidget(title, this);
    d->setObjectName(name);
    d->setWidget(content);
    addDockWidget(area, d);
    return d;
  };
  constraintsDock_ = dock(tr("Constraints"), "constraintsDock", scrolling(constraintPanel_), Qt::RightDockWidgetArea);
  displayDock_ = dock(tr("Display"), "displayDock", new DisplayPanel(session_, this), Qt::RightDockWidgetArea);

  auto* tabs = new QTabWidget(this);
  tabs->setObjectName("analysisTabs");
  tabs->addTab(new AngleHistogram(session_, this), tr("Gradient angles"));
  tabs->addTab(scrolling(new QualityPanel(session_, this)), tr("Quality"));
  log_ = new MessageLog(session_, this);
  tabs->addTab(log_, tr("Messages"));
  analysisDock_ = dock(tr("Analysis"), "analysisDock", tabs, Qt::BottomDockWidgetArea);
}

void MainWindow::createStatusBar() {
  sizes_ = new QLabel(this);
  progress_ = new QProgressBar(this);
  progress_->setRange(0, 1000);
  progress_->setMinimumWidth(320);
  cancelButton_ = new QPushButton(tr("Cancel"), this);
  cancelButton_->setObjectName("cancelButton");
  connect(cancelButton_, &QPushButton::clicked, controller_, &TransferController::cancel);
  statusBar()->addPermanentWidget(progress_);
  statusBar()->addPermanentWidget(cancelButton_);
  statusBar()->addPermanentWidget(sizes_);
}

void MainWindow::updateActions() {
  const bool busy = controller_->busy();
  const bool active = session_->hasModel(session_->activeRole());
  const bool both = session_->hasModel(Role::Standard) && session_->hasModel(Role::Patient);
  for (QAction* a : {openPatient_, openDicom_, openDemo_, openStandardFile_}) a->setEnabled(!busy);
  resegment_->setEnabled(!busy && session_->hasModel(Role::Patient) && session_->model(Role::Patient).segmentation);
  standardChoice_->setEnabled(!busy);
  // While a job runs the constraints stay as the job read them (see undoGroup_).
  constraintPanel_->setEnabled(!busy);
  undoGroup_->setActiveStack(busy ? nullptr : session_->undoStack());
  for (QAction* a : {loadConstraints_, mergeConstraints_}) a->setEnabled(active && !busy);
  saveConstraints_->setEnabled(active);
  features_->setEnabled(!busy && active && session_->model(session_->activeRole()).domain.side_mask.size() > 0);
  loadLandmarks_->setEnabled(features_->isEnabled());
  saveLandmarks_->setEnabled(active && session_->landmarks(session_->activeRole()).has_value());
  recover_->setEnabled(!busy && active && ConstraintAutosave::exists(session_->activeRole()));
  computeFields_->setEnabled(!busy && (session_->hasModel(Role::Standard) || session_->hasModel(Role::Patient)));
  transfer_->setEnabled(!busy && both);
  export_->setEnabled(!busy && session_->transfer());
  cancel_->setEnabled(busy);
  progress_->setVisible(busy);
  cancelButton_->setVisible(busy);
  if (!busy) progress_->setValue(0);
}

void MainWindow::updateSizes() {
  QStringList parts;
  for (Role r : kRoles)
    if (session_->hasModel(r)) {
      const VolumeMesh& m = session_->model(r).mesh;
      parts << tr("%1: %L2 vertices, %L3 cells").arg(roleName(r)).arg(m.num_vertices()).arg(m.num_cells());
    }
  sizes_->setText(parts.isEmpty() ? tr("no model loaded") : parts.join("  \u00b7  "));
}

void MainWindow::updateStandardChoice() {
  const int i = standardChoice_->findData(session_->model(Role::Standard).name);
  if (i >= 0) {
    standardChoice_->setCurrentIndex(i);
    return;
  }
  // A standard from a file: list it above the separator so the choice shows what is loaded.
  const QString name = session_->model(Role::Standard).name;
  standardChoice_->insertItem(0, name, session_->model(Role::Standard).path);
  standardChoice_->setCurrentIndex(0);
}

void MainWindow::onStandardChosen(int index) {
  const QVariant data = index >= 0 ? standardChoice_->itemData(index) : QVariant();
  QString choice = data.toString();
  if (mayDiscardResult(tr("Open another standard")) &&
      (data.isValid() ||
       !(choice = QFileDialog::getOpenFileName(this, tr("Open a standard hex mesh"), QString(),
                                               filter(tr("Hex-dominant meshes"), {".vtu", ".vtk", ".msh"})))
            .isEmpty()))
    controller_->openStandard(choice);
  else if (session_->hasModel(Role::Standard))
    updateStandardChoice();  // the choice shows what is loaded
}

void MainWindow::openPatientDialog() {
  std::vector<std::string> all = ct_volume_extensions();
  const std::vector<std::string> meshes = readable_volume_extensions();
  all.insert(all.end(), meshes.begin(), meshes.end());
  const QString path = QFileDialog::getOpenFileName(
      this, tr("Open a patient"), QSettings().value(kRecentKey).toStringList().value(0),
      QStringList{filter(tr("CT volumes and patient models"), all), filter(tr("CT volumes"), ct_volume_extensions()),
                  filter(tr("Tet models and closed surfaces"), meshes), tr("All files (*)")}
          .join(";;"));
  if (!path.isEmpty()) openPatient(path);
}

void MainWindow::openDicomDialog() {
  const QString folder = QFileDialog::getExistingDirectory(this, tr("Open a folder of DICOM slices"),
                                                           QSettings().value(kRecentKey).toStringList().value(0));
  if (!folder.isEmpty()) openPatient(folder);
}

void MainWindow::openPatient(const QString& path) {
  if (!mayDiscardResult(tr("Open another patient"))) return;
  if (is_ct_input(path.toStdString()))
    askSegmentation(path);
  else if (!controller_->openPatient(path))
    note(tr(kBusy));
}

void MainWindow::askSegmentation(const QString& ct) {
  segmentationCt_ = ct;
  segmentationDialog_->setCt(ct);
  // Segmenting the loaded patient's CT again: start from what was used. Another CT keeps the dialog's last options.
  if (session_->hasModel(Role::Patient)) {
    const LoadedModel& patient = session_->model(Role::Patient);
    if (patient.path == ct && patient.segmentation) {
      segmentationDialog_->setOptions(patient.segmentation->options);
      segmentationDialog_->showFound(*patient.segmentation);
    }
  }
  segmentationDialog_->open();
}

void MainWindow::constraintsDialog(bool merge) {
  const QString path =
      QFileDialog::getOpenFileName(this, merge ? tr("Merge a constraint set") : tr("Load a constraint set"), QString(),
                                   tr("Constraint sets (*.json)"));
  if (!path.isEmpty() && controller_->loadConstraints(session_->activeRole(), path, merge))
    note((merge ? tr("Merged %1 into the %2's constraints") : tr("Loaded %1 as the %2's constraints"))
             .arg(path, roleName(session_->activeRole())));
}

void MainWindow::saveConstraintsDialog() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Save the constraint set"),
                                                    session_->model(session_->activeRole()).constraintsPath,
                                                    tr("Constraint sets (*.json)"));
  if (!path.isEmpty() && controller_->saveConstraints(session_->activeRole(), path)) note(tr("Saved %1").arg(path));
}

void MainWindow::loadLandmarksDialog() {
  const QString path = QFileDialog::getOpenFileName(this, tr("Landmarks from a file"), QString(),
                                                    tr("Landmark files (*.json *.mrk.json)"));
  if (!path.isEmpty() && controller_->loadLandmarks(session_->activeRole(), path, session_->plane().band))
    note(tr("Placed the %1's features at the landmarks of %2").arg(roleName(session_->activeRole()), path));
}

void MainWindow::saveLandmarksDialog() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Save the landmarks"), QString(),
                                                    tr("FaceHex landmarks (*.json);;3D Slicer markups (*.mrk.json)"));
  if (!path.isEmpty() && controller_->saveLandmarks(session_->activeRole(), path)) note(tr("Saved %1").arg(path));
}

void MainWindow::moveLandmark(Role role, const std::string& name, const Eigen::Vector3d& point) {
  // A job reads the constraints as they were when it started: no edit meanwhile (see undoGroup_).
  if (controller_->busy()) {
    note(tr(kBusy));
  } else if (controller_->moveLandmark(role, name, point, session_->plane().band)) {
    note(tr("Moved the %1's %2 and placed its features again").arg(roleName(role), QString::fromStdString(name)));
    return;
  }
  view(role)->showSessionLandmarks();  // the handle goes back to where the landmark still is
}

void MainWindow::recoverAutosave() {
  if (controller_->loadConstraints(session_->activeRole(), ConstraintAutosave::path(session_->activeRole()), false))
    note(tr("Recovered the %1's constraints autosaved after its last edit").arg(roleName(session_->activeRole())));
}

void MainWindow::exportDialog() {
  const QString path = QFileDialog::getSaveFileName(this, tr("Export the patient hex mesh"), "patient_hex.vtu",
                                                    filter(tr("Volume meshes"), writable_volume_extensions()));
  if (!path.isEmpty() && controller_->exportHex(path)) note(tr("Exported %1").arg(path));
}

QImage MainWindow::snapshot() {
  for (ModelView* v : views_) v->render();
  QImage image = grab().toImage();
  if (segmentationDialog_->isVisible()) {
    QPainter painter(&image);
    painter.drawPixmap(mapFromGlobal(segmentationDialog_->geometry().topLeft()), segmentationDialog_->grab());
  }
  return image;
}

bool MainWindow::saveScreenshot(const QString& path) {
  if (snapshot().save(path, "PNG")) return true;
  reportError(tr("%1: cannot write the screenshot").arg(path));
  return false;
}

void MainWindow::screenshotDialog() {
  const QString path =
      QFileDialog::getSaveFileName(this, tr("Save a screenshot"), "facehex.png", tr("PNG images (*.png)"));
  if (!path.isEmpty() && saveScreenshot(path)) note(tr("Saved %1").arg(path));
}

void MainWindow::about() {
  QMessageBox::about(
      this, tr("About FaceHex"),
      tr("<h3>FaceHex %1</h3>"
         "<p>Patient-specific hexahedral finite-element meshes of the facial soft tissue, by mapping a standard hex "
         "mesh onto a patient model through three harmonic fields.</p>"
         "<p><b>Data credits</b></p><ul>"
         "<li>Reference face standard mesh: the ArtiSynth face model (ArtiSynth Models license); "
         "Nazari, Perrier, Chabanas, Payan, <i>Simulation of dynamic orofacial movements using a constitutive "
         "law varying with muscle activation</i>, CMBBE 2010; Lloyd, Stavness, Fels, <i>ArtiSynth: a fast "
         "interactive biomechanical modeling toolkit combining multibody and finite element simulation</i>, 2012."
         "</li><li>CT sample data: the VTK headsq data set, Kitware; the sample patient and the headsq-template "
         "standard are derived from it.</li>"
         "<li>DICOM reading: GDCM (Grassroots DICOM), BSD license.</li></ul>"
         "<p>Built with Qt %2 and VTK.</p>")
          .arg(FACEHEX_VERSION, qVersion()));
}

void MainWindow::addRecent(const QString& path) {
  QSettings settings;
  QStringList recent = settings.value(kRecentKey).toStringList();
  recent.removeAll(path);
  recent.prepend(path);
  while (recent.size() > kMaxRecent) recent.removeLast();
  settings.setValue(kRecentKey, recent);
  rebuildRecentMenu();
}

void MainWindow::rebuildRecentMenu() {
  recentMenu_->clear();
  for (const QString& path : QSettings().value(kRecentKey).toStringList())
    recentMenu_->addAction(QFileInfo(path).fileName(), this, [this, path] { openPatient(path); })->setToolTip(path);
  recentMenu_->setEnabled(!recentMenu_->isEmpty());
}

void MainWindow::closeEvent(QCloseEvent* event) {
  if (!mayDiscardResult(tr("Quit"))) {
    event->ignore();
    return;
  }
  QSettings settings;
  settings.setValue(kGeometryKey, saveGeometry());
  settings.setValue(kStateKey, saveState());
  event->accept();
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  if (event->mimeData()->hasUrls()) event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
  // A constraint set goes to the active model; anything else (a CT volume or DICOM folder, a tet model, a surface) is
  // opened as the patient (errors say what is wrong).
  for (const QUrl& url : event->mimeData()->urls()) {
    const QString path = url.toLocalFile();
    if (path.isEmpty()) continue;
    if (path.endsWith(".json", Qt::CaseInsensitive))
      controller_->loadConstraints(session_->activeRole(), path, false);
    else
      openPatient(path);
  }
  event->acceptProposedAction();
}

}  // namespace facehex::gui

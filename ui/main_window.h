#pragma once
// The FaceHex main window: the standard and patient views side by side, the constraint and display panels, the
// analysis tabs (angle histogram, quality tables, the message log), menus and toolbar, and a status bar with the mesh
// sizes, the progress of the running job and its cancel button. It owns the session, the controller and the
// autosave, logs every outcome, note and error, and routes every error to one replaceable reporter (a message box by
// default) with the core's message unchanged. Its panels scroll, so all of it is reachable on a small screen.
#include <QMainWindow>
#include <functional>

#include "ui/session_model.h"

class QComboBox;
class QDockWidget;
class QLabel;
class QMenu;
class QProgressBar;
class QPushButton;

class QUndoGroup;

namespace facehex::gui {

class ConstraintAutosave;
class ConstraintPanel;
class MessageLog;
class ModelView;
class SegmentationDialog;
class TransferController;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  SessionModel* session() const { return session_; }
  TransferController* controller() const { return controller_; }
  ModelView* view(Role role) const { return views_[static_cast<int>(role)]; }
  ConstraintAutosave* autosave() const { return autosave_; }
  MessageLog* messageLog() const { return log_; }

  using ErrorReporter = std::function<void(const QString& message)>;
  void setErrorReporter(ErrorReporter reporter) { reportError_ = std::move(reporter); }
  void reportError(const QString& message);  // logged, then reported

  // Sizes the window and its panels for a screen's free area (the primary screen's on construction): as large as
  // the design's layout where there is room, the panels in proportion.
  void fitTo(const QRect& available);
  // The window's size, place and panel layout as the last session left them (saved when the window closes).
  void restoreWindowState();

  // Opens a patient as File > Open does: a CT first asks for its segmentation options (segmentationDialog(), not
  // blocking; Segment starts the job), anything else is opened at once.
  void openPatient(const QString& path);
  SegmentationDialog* segmentationDialog() const { return segmentationDialog_; }

  // The window as an image, 3D views included (rendered first), with an open dialog drawn where it is.
  QImage snapshot();
  bool saveScreenshot(const QString& path);

 protected:
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;
  // Quitting with a hex mesh that was never exported asks first: minutes of work are not lost to a stray Ctrl+Q.
  void closeEvent(QCloseEvent* event) override;

 private:
  // Whether `action` (which replaces the transfer's result) may go ahead: true when the result was exported or
  // there is none, else the user is asked.
  bool mayDiscardResult(const QString& action);
  void note(const QString& text);  // the status bar and the log
  void createActions();
  void createMenusAndToolbar();
  void createDocks();
  void createStatusBar();
  void updateActions();
  void updateSizes();
  void updateStandardChoice();
  void openPatientDialog();
  void openDicomDialog();
  void askSegmentation(const QString& ct);
  void onStandardChosen(int index);
  void constraintsDialog(bool merge);
  void saveConstraintsDialog();
  void loadLandmarksDialog();
  void saveLandmarksDialog();
  void moveLandmark(Role role, const std::string& name, const Eigen::Vector3d& point);
  void recoverAutosave();
  void exportDialog();
  void screenshotDialog();
  void about();
  void addRecent(const QString& path);
  void rebuildRecentMenu();

  SessionModel* session_;
  TransferController* controller_;
  ConstraintAutosave* autosave_;
  std::array<ModelView*, 2> views_{};
  ConstraintPanel* constraintPanel_ = nullptr;
  MessageLog* log_ = nullptr;
  QDockWidget *constraintsDock_ = nullptr, *displayDock_ = nullptr, *analysisDock_ = nullptr;
  SegmentationDialog* segmentationDialog_ = nullptr;
  QString segmentationCt_;   // the CT the dialog is asking about
  bool segmenting_ = false;  // the controller is segmenting segmentationCt_ as the dialog asked
  ErrorReporter reportError_;

  QAction *openPatient_, *resegment_, *openDicom_, *openDemo_, *openStandardFile_, *loadConstraints_,
      *mergeConstraints_, *saveConstraints_, *recover_, *export_, *screenshot_, *quit_, *undo_, *redo_, *computeFields_,
      *transfer_, *cancel_, *allowInverted_, *shapeRelaxation_, *registeredSkin_, *pullLandmarks_, *features_,
      *loadLandmarks_, *saveLandmarks_, *about_;
  QUndoGroup* undoGroup_ = nullptr;
  QMenu* recentMenu_ = nullptr;
  QComboBox* standardChoice_ = nullptr;
  QLabel* sizes_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QPushButton* cancelButton_ = nullptr;
};

}  // namespace facehex::gui

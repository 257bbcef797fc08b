#pragma once
// Runs the core (loading or segmenting, parameterization, transfer, quality) for the session, long work on a worker
// thread so the window stays responsive. Progress comes through the core's ProgressCallback, which also carries the
// cancel request; results are installed in the SessionModel on the GUI thread, unless the model changed meanwhile.
// Failures are reported as the facehex::Error text, the same line the CLI prints.
#include <QFutureWatcher>
#include <QObject>
#include <atomic>
#include <functional>

#include "core/util/progress.h"
#include "ui/session_model.h"

namespace facehex::gui {

class TransferController : public QObject {
  Q_OBJECT

 public:
  explicit TransferController(SessionModel* session, QObject* parent = nullptr);
  ~TransferController() override;  // cancels and waits for a running job

  // From start() until the result is delivered on the GUI thread (the worker itself may have finished earlier).
  bool busy() const { return !job_.isEmpty(); }
  // The options of the next runs (the CLI's --iterations, --order, --allow-inverted).
  const TransferOptions& options() const { return options_; }
  void setOptions(const TransferOptions& options) { options_ = options; }

  // Jobs on the worker thread; each returns false (and does nothing) while another job runs.
  // A patient from a head CT (segmented with `segmentOptions`), a tet model or a closed surface; without a
  // constraint file of its own it gets the automatic constraints, its features valued as the loaded standard's
  // (model_loading.h).
  bool openPatient(const QString& path, const SegmentOptions& segmentOptions = {});
  bool openStandard(const QString& nameOrPath);  // empty: the bundled default
  // A standard (default: the bundled default) and the bundled sample patient.
  bool openDemo(const QString& standard = {});
  bool computeFields();  // parameterizes every loaded model with its constraint set
  bool runTransfer();    // maps the standard onto the patient, then measures the quality
  void cancel();
  // Spins an event loop until no job runs (the scripted states of --screenshot and the tests); false on timeout.
  bool waitUntilIdle(int timeoutMs = 600000);

  // Quick operations on the GUI thread; false (and failed()) on error.
  // The feature constraints at the model's facial landmarks (core/face_landmarks.h), valued as the standard's
  // features of the same names and selected by slabs `band` mm wide: they replace the model's features (re-computed
  // after a change of standard, band or model) or are added, as one undoable edit.
  bool placeFeatureConstraints(Role role, double band);
  // The same at the landmarks of a landmark file (core/face/landmark_file.h), as the CLI's --landmarks places them.
  bool loadLandmarks(Role role, const QString& path, double band);
  bool saveLandmarks(Role role, const QString& path);
  // The named landmark moved to the skin point closest to `point` (a drag's release), its features placed again.
  bool moveLandmark(Role role, const std::string& name, const Eigen::Vector3d& point, double band);
  bool loadConstraints(Role role, const QString& path, bool merge);
  bool saveConstraints(Role role, const QString& path);
  bool exportHex(const QString& path);

 signals:
  void busyChanged(bool busy);
  void progress(const QString& stage, double fraction);
  void failed(const QString& message);
  // summary: one line for the status bar; detail: what the job made, a line per fact, for the message log.
  void finished(const QString& summary, const QStringList& detail);

 private:
  struct Report {
    QString summary;
    QStringList detail;
  };
  // Work returns what to do with its result on the GUI thread (that returns the report).
  using Apply = std::function<Report(SessionModel&)>;
  using Work = std::function<Apply(const ProgressCallback&)>;
  struct Outcome {
    Apply apply;
    QString error;
    bool cancelled = false;
  };
  bool start(const QString& what, Work work);
  void deliver();
  bool reportErrors(const std::function<void()>& f);
  // The role's model; throws facehex::Error(subject, "open the ... model first") when there is none.
  const LoadedModel& openedModel(Role role, const std::string& subject) const;
  // The model's feature constraints placed at `given` landmarks, else at those found (one undoable edit).
  void placeFeatures(Role role, double band, const FaceLandmarks* given, const QString& what);

  SessionModel* session_;
  TransferOptions options_;
  QFutureWatcher<Outcome> watcher_;
  QString job_;  // what is running, or empty
  std::atomic<bool> cancelRequested_{false};
  std::atomic<int> lastReport_{-1};  // per-mille of the last progress signal, to send one per step
};

}  // namespace facehex::gui

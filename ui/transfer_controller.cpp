#include "ui/transfer_controller.h"

#include <QEventLoop>
#include <QFileInfo>
#include <QTimer>
#include <QtConcurrent/QtConcurrentRun>
#include <algorithm>
#include <memory>
#include <optional>

#include "core/face/automatic_constraints.h"
#include "core/io/mesh_io.h"
#include "core/segment/ct_volume.h"
#include "core/segment/patient_input.h"
#include "core/util/error.h"
#include "core/util/resources.h"
#include "ui/model_loading.h"

namespace facehex::gui {
namespace {

// The progress of one of several consecutive stages, mapped into [lo, hi] of the job and named after its model.
ProgressCallback part(const ProgressCallback& progress, const QString& prefix, double lo, double hi) {
  const std::string p = prefix.toStdString();
  const ProgressCallback named = [=](const std::string& stage, double f) { return progress(p + ": " + stage, f); };
  return sub_progress(named, lo, hi);
}

QString count(long n) { return QString("%L1").arg(n); }

QString sizeText(const LoadedModel& m) {
  return QObject::tr("%1 vertices, %2 cells").arg(count(m.mesh.num_vertices()), count(m.mesh.num_cells()));
}

// What a transfer gave, a line per fact: the cells, their validity before and after the repair, their quality
// against the standard's, how far the side vertices lie from the patient's surface, the time of each stage, and the
// openings of the patient model closed as the standard's (core/workflow/transfer.h).
QStringList transferDetail(const TransferResult& r) {
  const QualitySummary &q = r.patient_quality.summary, &sq = r.standard_quality.summary;
  QStringList stages;
  double total = 0;
  for (const auto& [stage, seconds] : r.run.seconds) {
    stages << QString("%1 %2 s").arg(QString::fromStdString(stage).replace('_', ' ')).arg(seconds, 0, 'f', 1);
    total += seconds;
  }
  QStringList lines = {
      QObject::tr("%1 cells (%2 hexes, %3 wedges)").arg(count(q.cells), count(q.hexes), count(q.wedges)),
      QObject::tr("%1 inverted, %2 flat (%3 inverted after the plain mapping)")
          .arg(q.inverted)
          .arg(q.degenerate)
          .arg(r.plain_mapping_quality.summary.inverted),
      QObject::tr("shape mean %1, min %2 (standard: mean %3, min %4)")
          .arg(q.shape_mean, 0, 'f', 3)
          .arg(q.shape_min, 0, 'f', 3)
          .arg(sq.shape_mean, 0, 'f', 3)
          .arg(sq.shape_min, 0, 'f', 3),
      QObject::tr("scaled Jacobian min %1, %2% of the cells below 0.3")
          .arg(q.scaled_jacobian_min, 0, 'f', 3)
          .arg(100 * q.fraction_scaled_jacobian_below_0_3, 0, 'f', 1),
      QObject::tr("dihedral angles changed by %1\u00b0 on average, %2\u00b0 at most")
          .arg(r.patient_quality.distortion.mean_deg, 0, 'f', 1)
          .arg(r.patient_quality.distortion.max_deg, 0, 'f', 1),
      QObject::tr("side vertices off the patient's surface: mean %1 mm, max %2 mm")
          .arg(r.distance.mean, 0, 'f', 2)
          .arg(r.distance.max, 0, 'f', 2),
      QObject::tr("time %1 s: %2").arg(total, 0, 'f', 1).arg(stages.join(", "))};
  if (!r.patient_openings.empty())
    lines
        << QObject::tr("the patient model's %1 as the standard's are").arg(QString::fromStdString(r.patient_openings));
  if (const std::string landing = feature_landing_text(r.landing); !landing.empty())
    lines << QString::fromStdString(landing).trimmed();
  return lines;
}

const char* kStale = QT_TRANSLATE_NOOP("TransferController", " (not applied: the models changed meanwhile)");

}  // namespace

TransferController::TransferController(SessionModel* session, QObject* parent) : QObject(parent), session_(session) {
  connect(&watcher_, &QFutureWatcher<Outcome>::finished, this, &TransferController::deliver);
}

TransferController::~TransferController() {
  cancel();
  watcher_.waitForFinished();
}

bool TransferController::start(const QString& what, Work work) {
  if (busy()) return false;
  job_ = what;
  cancelRequested_ = false;
  lastReport_ = -1;
  // Called on the worker thread: forward at most one signal per percent to the GUI thread.
  ProgressCallback progressCallback = [this](const std::string& stage, double fraction) {
    const int percent = static_cast<int>(100 * fraction);
    if (lastReport_.exchange(percent) != percent) {
      const QString s = QString::fromStdString(stage);
      QMetaObject::invokeMethod(
          this,
          [this, s, fraction] {
            if (busy()) emit progress(s, fraction);
          },
          Qt::QueuedConnection);
    }
    return !cancelRequested_;
  };
  watcher_.setFuture(QtConcurrent::run([work, progressCallback]() {
    Outcome o;
    try {
      o.apply = work(progressCallback);
    } catch (const Cancelled&) {
      o.cancelled = true;
    } catch (const std::exception& e) {  // facehex::Error, and anything else (bad_alloc) rather than a crash
      o.error = QString::fromStdString(e.what());
    }
    return o;
  }));
  emit busyChanged(true);
  emit progress(what, 0.0);
  return true;
}

void TransferController::deliver() {
  const Outcome o = watcher_.result();
  Report report;
  if (o.apply) report = o.apply(*session_);
  const QString job = std::exchange(job_, QString());
  emit busyChanged(false);
  if (o.cancelled)
    emit finished(tr("%1: cancelled").arg(job), {});
  else if (!o.error.isEmpty())
    emit failed(o.error);
  else
    emit finished(report.summary, report.detail);
}

void TransferController::cancel() { cancelRequested_ = true; }

bool TransferController::waitUntilIdle(int timeoutMs) {
  if (!busy()) return true;
  QEventLoop loop;
  connect(this, &TransferController::busyChanged, &loop, [&loop](bool b) {
    if (!b) loop.quit();
  });
  QTimer::singleShot(timeoutMs, &loop, &QEventLoop::quit);
  loop.exec();
  return !busy();
}

bool TransferController::openPatient(const QString& path, const SegmentOptions& segmentOptions) {
  const std::string p = path.toStdString();
  const bool ct = is_ct_input(p);
  // Without a standard there is nothing to value the features with: the patient opens with its six sides.
  std::optional<std::map<std::string, double>> values;
  if (session_->hasModel(Role::Standard)) values = feature_values(session_->constraints(Role::Standard).set);
  const QString file = QFileInfo(path).fileName();
  return start(ct ? tr("Segmenting %1").arg(file) : tr("Opening %1").arg(file),
               [p, ct, values, segmentOptions](const ProgressCallback& progress) -> Apply {
                 auto note = std::make_shared<QString>();
                 auto m = std::make_shared<LoadedModel>(
                     load_patient(p, segmentOptions, values ? &*values : nullptr, progress, *note));
                 return [m, note, ct](SessionModel& s) {
                   Report r{(ct ? tr("Segmented the CT %1: %2; %3") : tr("Opened the patient %1: %2; %3"))
                                .arg(m->name, sizeText(*m), *note),
                            {m->path, sizeText(*m), *note}};
                   if (m->segmentation) {
                     const QString used = QString::fromStdString(segmentation_summary(*m->segmentation));
                     r.summary += "; " + used;
                     r.detail << used;
                   }
                   s.setModel(Role::Patient, std::move(*m));
                   return r;
                 };
               });
}

bool TransferController::openStandard(const QString& nameOrPath) {
  const std::string n = nameOrPath.toStdString();
  return start(tr("Opening the standard %1").arg(nameOrPath), [n](const ProgressCallback&) -> Apply {
    auto m = std::make_shared<LoadedModel>(load_standard(n.empty() ? default_standard().name : n));
    return [m](SessionModel& s) {
      Report r{tr("Opened the standard %1: %2").arg(m->name, sizeText(*m)), {m->path, sizeText(*m)}};
      s.setModel(Role::Standard, std::move(*m));
      return r;
    };
  });
}

bool TransferController::openDemo(const QString& standardName) {
  const std::string name = standardName.toStdString();
  return start(tr("Opening the demo"), [name](const ProgressCallback&) -> Apply {
    auto standard = std::make_shared<LoadedModel>(load_standard(name.empty() ? default_standard().name : name));
    auto note = std::make_shared<QString>();
    const std::map<std::string, double> values = feature_values(standard->constraints.set);
    auto patient = std::make_shared<LoadedModel>(demo_patient(&values, *note));
    return [standard, patient, note](SessionModel& s) {
      Report r{tr("Opened the demo: standard %1, patient %2; %3").arg(standard->name, patient->name, *note),
               {tr("standard %1: %2").arg(standard->name, sizeText(*standard)),
                tr("patient %1: %2").arg(patient->name, sizeText(*patient)), *note}};
      s.setModel(Role::Standard, std::move(*standard));
      s.setModel(Role::Patient, std::move(*patient));
      return r;
    };
  });
}

bool TransferController::computeFields() {
  struct Input {
    Role role;
    std::string path;  // the mesh file, or empty for a model made in memory
    TetDomain domain;
    ConstraintSet set;
    std::string source;
    quint64 revision;
  };
  std::vector<Input> inputs;
  for (Role r : kRoles)
    if (session_->hasModel(r)) {
      const LoadedModel& m = session_->model(r);
      inputs.push_back({r, m.path.toStdString(), m.domain, m.constraints.set, m.source(), session_->revision(r)});
    }
  if (inputs.empty()) {
    emit failed(tr("fields: open a model first"));
    return false;
  }
  const HarmonicFieldsOptions options = options_.fields;
  return start(tr("Computing the fields"), [inputs, options](const ProgressCallback& progress) -> Apply {
    auto results = std::make_shared<std::vector<ModelParameterization>>();
    auto fromCache = std::make_shared<std::vector<bool>>();
    for (size_t i = 0; i < inputs.size(); ++i) {
      const Input& in = inputs[i];
      const double lo = double(i) / inputs.size(), hi = double(i + 1) / inputs.size();
      std::optional<ModelParameterization> cached;
      if (!in.path.empty()) cached = cached_parameterization(in.path, in.domain, in.set, options);
      fromCache->push_back(cached.has_value());
      results->push_back(cached ? std::move(*cached)
                                : parameterize_model(in.domain.V, in.domain.T, in.domain.side_mask, in.set, in.source,
                                                     options, part(progress, roleName(in.role), lo, hi)));
    }
    return [inputs, results, fromCache](SessionModel& s) {
      QStringList parts, detail;
      for (size_t i = 0; i < inputs.size(); ++i) {
        const ModelParameterization& p = (*results)[i];
        // The angles are in the histogram tab; the status line says what decides whether the transfer can go on.
        QString text = tr("%1 %L2 tets folded (%3%)")
                           .arg(roleName(inputs[i].role))
                           .arg(p.health.inverted)
                           .arg(100.0 * p.health.inverted / std::max(1, p.health.tets), 0, 'f', 2);
        if ((*fromCache)[i]) text += tr(" (from its cache)");
        detail << tr("%1: %L2 of %L3 tets folded, gradient angles %4\u00b0 from 90\u00b0 on average (%5\u00b0 before "
                     "the orthogonality improvement)%6")
                      .arg(roleName(inputs[i].role))
                      .arg(p.health.inverted)
                      .arg(p.health.tets)
                      .arg(p.fields.angles.mean_deviation_from_90, 0, 'f', 1)
                      .arg(p.fields.angles_initial.mean_deviation_from_90, 0, 'f', 1)
                      .arg((*fromCache)[i] ? tr(", read from its cache") : QString());
        if (s.revision(inputs[i].role) == inputs[i].revision)
          s.setParameterization(inputs[i].role, std::move((*results)[i]));
        else
          text += tr(kStale);
        parts << text;
      }
      return Report{tr("Fields computed: ") + parts.join(", "), detail};
    };
  });
}

bool TransferController::runTransfer() {
  if (!session_->hasModel(Role::Standard) || !session_->hasModel(Role::Patient)) {
    emit failed(tr("transfer: open a standard and a patient first"));
    return false;
  }
  auto standard = std::make_shared<const StandardSetup>(standard_setup(session_->model(Role::Standard)));
  auto patient = std::make_shared<const PatientSetup>(patient_setup(session_->model(Role::Patient)));
  const std::array<quint64, 2> revisions = {session_->revision(Role::Standard), session_->revision(Role::Patient)};
  const TransferOptions options = options_;
  return start(tr("Transfer"), [standard, patient, revisions, options](const ProgressCallback& progress) -> Apply {
    auto result = std::make_shared<TransferResult>(transfer(*standard, *patient, options, progress));
    return [result, revisions](SessionModel& s) {
      const QualitySummary& q = result->patient_quality.summary;
      Report r{tr("Transfer done: %1 cells, %2 inverted, mean shape %3 (standard %4)")
                   .arg(count(q.cells))
                   .arg(q.inverted)
                   .arg(q.shape_mean, 0, 'f', 3)
                   .arg(result->standard_quality.summary.shape_mean, 0, 'f', 3),
               transferDetail(*result)};
      if (s.revision(Role::Standard) != revisions[0] || s.revision(Role::Patient) != revisions[1]) {
        r.summary += tr(kStale);
        return r;
      }
      s.setParameterization(Role::Standard, std::move(result->run.standard));
      s.setParameterization(Role::Patient, std::move(result->run.patient));
      s.setTransfer(std::move(*result));
      DisplaySettings d = s.display();  // the result is what the user waited for: shown at once
      d.showHex = true;
      s.setDisplay(d);
      return r;
    };
  });
}

bool TransferController::reportErrors(const std::function<void()>& f) {
  try {
    f();
    return true;
  } catch (const std::exception& e) {
    emit failed(QString::fromStdString(e.what()));
    return false;
  }
}

const LoadedModel& TransferController::openedModel(Role role, const std::string& subject) const {
  if (!session_->hasModel(role)) throw Error(subject, "open the " + roleName(role).toStdString() + " model first");
  return session_->model(role);
}

void TransferController::placeFeatures(Role role, double band, const FaceLandmarks* given, const QString& what) {
  const LoadedModel& model = openedModel(role, "features");
  if (!session_->hasModel(Role::Standard))
    throw Error("features", "open a standard first: the features take the values of its constraint set");
  const VolumeMesh& mesh = model.mesh;
  FaceLandmarks landmarks;
  const ConstraintSet features =
      landmark_feature_constraints(mesh.V, side_mask_of(mesh), landmark_options_for(mesh, model.path.toStdString()),
                                   feature_values(session_->constraints(Role::Standard).set), band, &landmarks, given);
  session_->setFeatureConstraints(role, features, landmarks, what);
}

bool TransferController::placeFeatureConstraints(Role role, double band) {
  return reportErrors([&] { placeFeatures(role, band, nullptr, tr("place the facial features")); });
}

bool TransferController::loadLandmarks(Role role, const QString& path, double band) {
  return reportErrors([&] {
    const std::string p = path.toStdString();
    const FaceLandmarks given =
        landmarks_from(read_landmark_file(p, scan_frame(openedModel(role, "features").mesh, p)), p);
    placeFeatures(role, band, &given, tr("landmarks from %1").arg(QFileInfo(path).fileName()));
  });
}

bool TransferController::saveLandmarks(Role role, const QString& path) {
  return reportErrors([&] {
    const std::string p = path.toStdString();
    if (!session_->hasModel(role) || !session_->landmarks(role))
      throw Error(p, "the " + roleName(role).toStdString() + " model has no landmarks");
    write_landmark_file(p, named_landmarks(*session_->landmarks(role)), session_->landmarks(role)->scan_frame);
  });
}

bool TransferController::moveLandmark(Role role, const std::string& name, const Eigen::Vector3d& point, double band) {
  return reportErrors([&] {
    if (!session_->hasModel(role) || !session_->landmarks(role))
      throw Error("landmarks", "the " + roleName(role).toStdString() + " model has no landmarks");
    std::vector<NamedLandmark> named = named_landmarks(*session_->landmarks(role));
    const auto moved = std::find_if(named.begin(), named.end(), [&](const NamedLandmark& n) { return n.name == name; });
    if (moved == named.end()) throw Error("landmarks", "no landmark '" + name + "'");
    const VolumeMesh& mesh = session_->model(role).mesh;
    moved->position = closest_skin_point(mesh.V, side_mask_of(mesh), point);
    moved->status = LandmarkStatus::given;
    const FaceLandmarks given = landmarks_from(named, "the moved " + name);
    placeFeatures(role, band, &given,
                  tr("move the %1").arg(QString::fromStdString(patient_side_name(name, scan_frame(mesh, "")))));
  });
}

bool TransferController::loadConstraints(Role role, const QString& path, bool merge) {
  return reportErrors([&] {
    const std::string p = path.toStdString();
    openedModel(role, p);
    const ConstraintSet set = read_constraint_set(p);
    const QString name = QFileInfo(path).fileName();
    if (merge)
      session_->mergeConstraints(role, set, tr("merge %1").arg(name));
    else
      session_->replaceConstraints(role, set, tr("load %1").arg(name));
  });
}

bool TransferController::saveConstraints(Role role, const QString& path) {
  return reportErrors([&] {
    if (!session_->hasModel(role)) throw Error(path.toStdString(), "no " + roleName(role).toStdString() + " model");
    write_constraint_set(path.toStdString(), session_->constraints(role).set);
  });
}

bool TransferController::exportHex(const QString& path) {
  return reportErrors([&] {
    if (!session_->transfer()) throw Error(path.toStdString(), "no hex mesh to export yet: run the transfer first");
    write_volume_mesh(path.toStdString(), session_->transfer()->patient_hex);
    session_->markTransferExported();
  });
}

}  // namespace facehex::gui

#include "ui/session_model.h"

#include <QUndoCommand>
#include <QUndoStack>
#include <algorithm>
#include <stdexcept>
#include <utility>

namespace facehex::gui {
namespace {

// One constraint edit: the whole list before and after. Lists are small (selections are rules, not vertex sets), so
// snapshots keep every edit (add, rename, delete, load, merge, show/hide) one simple, exactly reversible command.
class ConstraintEditCommand : public QUndoCommand {
 public:
  ConstraintEditCommand(SessionModel* session, Role role, ConstraintList before, ConstraintList after,
                        const QString& what)
      : QUndoCommand(what), session_(session), role_(role), before_(std::move(before)), after_(std::move(after)) {}
  void redo() override { session_->applyConstraints(role_, after_); }
  void undo() override { session_->applyConstraints(role_, before_); }

 private:
  SessionModel* session_;
  Role role_;
  ConstraintList before_, after_;
};

bool sameVector(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).cwiseAbs().maxCoeff() == 0; }

constexpr size_t kResultsSetAside = 2;

}  // namespace

QString roleName(Role role) { return role == Role::Standard ? "standard" : "patient"; }

std::string LoadedModel::source() const {
  if (!constraintsPath.isEmpty()) return constraintsPath.toStdString();
  return (path.isEmpty() ? name : path).toStdString();
}

bool DisplaySettings::operator==(const DisplaySettings& o) const {
  return field == o.field && isoLines == o.isoLines && clipAtPlane == o.clipAtPlane && glyphs == o.glyphs &&
         showHex == o.showHex && measure == o.measure && threshold == o.threshold &&
         showConstraints == o.showConstraints && showPlane == o.showPlane && showLandmarks == o.showLandmarks;
}

SessionModel::SessionModel(QObject* parent) : QObject(parent), undo_(new QUndoStack(this)) {}

SessionModel::~SessionModel() = default;

const LoadedModel& SessionModel::model(Role role) const {
  if (!hasModel(role)) throw std::logic_error("no " + roleName(role).toStdString() + " model loaded");
  return *models_[index(role)];
}

LoadedModel& SessionModel::mutableModel(Role role) {
  if (!hasModel(role)) throw std::logic_error("no " + roleName(role).toStdString() + " model loaded");
  return *models_[index(role)];
}

void SessionModel::setModel(Role role, LoadedModel model) {
  model.constraints.visible.resize(model.constraints.set.constraints.size(), true);
  models_[index(role)] = std::move(model);
  undo_->clear();
  updateConstraintVertices(role);
  // Results of the old model go before anyone hears of the new one; views rebuild their pipelines on modelChanged
  // before the other signals refer to them.
  ++revisions_[index(role)];
  results_.parameterizations[index(role)].reset();
  results_.transfer.reset();
  setAside_.clear();
  const bool highlighted = std::exchange(highlight_, std::nullopt).has_value();  // it named the old model
  if (role == activeRole_) planeSelection_.clear();  // so did the plane's selection, until it is made again below
  emit modelChanged(role);
  emit resultsChanged();
  emit constraintsChanged(role);
  if (highlighted) emit highlightChanged();
  if (role == activeRole_) {
    centrePlaneOn(role);
    updatePlaneSelection();
  }
}

void SessionModel::setActiveRole(Role role) {
  if (role == activeRole_) return;
  activeRole_ = role;
  emit activeRoleChanged(role);
  // Keep the plane where it is if it still cuts the newly active model (the two frames usually agree).
  if (hasModel(role)) {
    const Eigen::MatrixXd& V = model(role).domain.V;
    const Eigen::Vector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
    if ((plane_.origin.array() < lo.array()).any() || (plane_.origin.array() > hi.array()).any()) centrePlaneOn(role);
  }
  updatePlaneSelection();
}

const std::vector<int>& SessionModel::constraintVertices(Role role, int i) const {
  return constraintVertices_[index(role)].at(i);
}

const QString& SessionModel::constraintProblem(Role role, int i) const {
  return constraintProblems_[index(role)].at(i);
}

void SessionModel::edit(Role role, ConstraintList after, const QString& what) {
  undo_->push(new ConstraintEditCommand(this, role, constraints(role), std::move(after), what));
}

void SessionModel::addPlaneConstraint(Role role, const QString& name, int field, double value) {
  ConstraintList list = constraints(role);
  list.set.constraints.push_back({name.toStdString(), field, value, planeAsSelection(), ""});
  list.visible.push_back(true);
  edit(role, std::move(list), tr("add constraint '%1'").arg(name));
}

void SessionModel::updateConstraint(Role role, int i, const Constraint& constraint) {
  ConstraintList list = constraints(role);
  list.set.constraints.at(i) = constraint;
  edit(role, std::move(list), tr("edit constraint '%1'").arg(QString::fromStdString(constraint.name)));
}

void SessionModel::removeConstraint(Role role, int i) {
  ConstraintList list = constraints(role);
  const QString name = QString::fromStdString(list.set.constraints.at(i).name);
  list.set.constraints.erase(list.set.constraints.begin() + i);
  list.visible.erase(list.visible.begin() + i);
  edit(role, std::move(list), tr("delete constraint '%1'").arg(name));
}

void SessionModel::setConstraintVisible(Role role, int i, bool visible) {
  ConstraintList list = constraints(role);
  if (list.visible.at(i) == visible) return;
  list.visible[i] = visible;
  const QString name = QString::fromStdString(list.set.constraints[i].name);
  edit(role, std::move(list), visible ? tr("show '%1'").arg(name) : tr("hide '%1'").arg(name));
}

void SessionModel::replaceConstraints(Role role, const ConstraintSet& set, const QString& what) {
  edit(role, {set, std::vector<bool>(set.constraints.size(), true), std::nullopt}, what);  // placed at no landmarks
}

void SessionModel::mergeConstraints(Role role, const ConstraintSet& set, const QString& what) {
  ConstraintList list = constraints(role);
  list.set.constraints.insert(list.set.constraints.end(), set.constraints.begin(), set.constraints.end());
  list.visible.resize(list.set.constraints.size(), true);
  edit(role, std::move(list), what);
}

void SessionModel::setNamedConstraints(Role role, const ConstraintSet& set, const QString& what) {
  edit(role, withNamed(role, set), what);
}

void SessionModel::setFeatureConstraints(Role role, const ConstraintSet& features, const FaceLandmarks& landmarks,
                                         const QString& what) {
  ConstraintList list = withNamed(role, features);
  list.landmarks = landmarks;
  edit(role, std::move(list), what);
}

ConstraintList SessionModel::withNamed(Role role, const ConstraintSet& set) const {
  ConstraintList list = constraints(role);
  auto& cs = list.set.constraints;
  for (const Constraint& c : set.constraints) {
    const auto same = std::find_if(cs.begin(), cs.end(), [&c](const Constraint& o) { return o.name == c.name; });
    if (same != cs.end()) {
      *same = c;
    } else {
      cs.push_back(c);
      list.visible.push_back(true);
    }
  }
  return list;
}

void SessionModel::addSideConstraints(Role role) {
  setNamedConstraints(role, side_constraints(), tr("add the six sides"));
}

void SessionModel::applyConstraints(Role role, const ConstraintList& list) {
  // Showing or hiding a constraint changes no result; anything else makes the fields and the transfer stale.
  const ConstraintState before = constraintState();
  mutableModel(role).constraints = list;
  if (constraintState() != before) {
    updateConstraintVertices(role);
    ++revisions_[index(role)];
    if (highlight_ && highlight_->role == role && highlight_->constraint >= 0) setHighlight(std::nullopt);
    exchangeResults(role, before);
  }
  emit constraintsChanged(role);
  emit constraintsEdited(role);
}

SessionModel::ConstraintState SessionModel::constraintState() const {
  ConstraintState state;
  for (Role r : kRoles)
    if (hasModel(r)) state[index(r)] = to_json(constraints(r).set);
  return state;
}

void SessionModel::exchangeResults(Role role, const ConstraintState& before) {
  Results stale;
  stale.parameterizations[index(role)] = std::exchange(results_.parameterizations[index(role)], std::nullopt);
  stale.transfer = std::exchange(results_.transfer, std::nullopt);
  stale.transferExported = results_.transferExported;
  bool changed = !stale.empty();
  const ConstraintState now = constraintState();
  const auto back = std::find_if(setAside_.begin(), setAside_.end(), [&now](const auto& s) { return s.first == now; });
  if (back != setAside_.end()) {
    Results& r = back->second;
    for (Role k : kRoles)
      if (r.parameterizations[index(k)])
        results_.parameterizations[index(k)] = std::move(r.parameterizations[index(k)]);
    if (r.transfer) {
      results_.transfer = std::move(r.transfer);
      results_.transferExported = r.transferExported;
    }
    setAside_.erase(back);
    changed = true;
  }
  if (!stale.empty()) {
    setAside_.emplace_front(before, std::move(stale));
    if (setAside_.size() > kResultsSetAside) setAside_.pop_back();
  }
  if (changed) emit resultsChanged();
}

void SessionModel::updateConstraintVertices(Role role) {
  const LoadedModel& m = model(role);
  auto& vertices = constraintVertices_[index(role)];
  auto& problems = constraintProblems_[index(role)];
  vertices.assign(m.constraints.set.constraints.size(), {});
  problems.assign(m.constraints.set.constraints.size(), {});
  for (size_t i = 0; i < vertices.size(); ++i) {
    try {
      vertices[i] =
          select_vertices(m.constraints.set.constraints[i].select, m.domain.V, m.boundary, m.domain.side_mask);
      if (vertices[i].empty()) problems[i] = tr("selects no vertex");
    } catch (const std::exception& e) {
      problems[i] = QString::fromStdString(e.what());
    }
  }
}

void SessionModel::setPlane(const PlanePose& pose) {
  if (sameVector(pose.origin, plane_.origin) && sameVector(pose.normal, plane_.normal) && pose.band == plane_.band &&
      pose.region == plane_.region)
    return;
  plane_ = pose;
  plane_.normal.normalize();
  emit planeChanged();
  updatePlaneSelection();
}

void SessionModel::centrePlaneOn(Role role) {
  const Eigen::MatrixXd& V = model(role).domain.V;
  PlanePose pose = plane_;
  pose.origin = 0.5 * (V.colwise().minCoeff() + V.colwise().maxCoeff()).transpose();
  setPlane(pose);
}

Selection SessionModel::planeAsSelection() const {
  Selection s;
  s.plane = PlaneSelection{plane_.origin, plane_.normal, plane_.band, plane_.region, std::nullopt, 0.0};
  return s;
}

void SessionModel::updatePlaneSelection() {
  planeSelection_.clear();
  if (hasModel(activeRole_)) {
    const LoadedModel& m = model(activeRole_);
    try {
      planeSelection_ = select_vertices(planeAsSelection(), m.domain.V, m.boundary, m.domain.side_mask);
    } catch (const std::exception&) {
      // A side region on a model without "side_mask" selects nothing; the panel offers no such region then.
    }
  }
  emit planeSelectionChanged();
}

void SessionModel::setDisplay(const DisplaySettings& display) {
  if (display == display_) return;
  display_ = display;
  emit displayChanged();
}

const ModelParameterization* SessionModel::parameterization(Role role) const {
  const auto& p = results_.parameterizations[index(role)];
  return p ? &*p : nullptr;
}

void SessionModel::setParameterization(Role role, ModelParameterization p) {
  results_.parameterizations[index(role)] = std::move(p);
  emit resultsChanged();
}

void SessionModel::setTransfer(TransferResult result) {
  results_.transfer = std::move(result);
  results_.transferExported = false;
  emit resultsChanged();
}

void SessionModel::setHighlight(const std::optional<Highlight>& highlight) {
  if (highlight == highlight_) return;
  highlight_ = highlight;
  emit highlightChanged();
}

}  // namespace facehex::gui

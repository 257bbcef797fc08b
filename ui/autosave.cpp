#include "ui/autosave.h"

#include <QDir>
#include <QFileInfo>
#include <QStandardPaths>

namespace facehex::gui {

ConstraintAutosave::ConstraintAutosave(SessionModel* session, QObject* parent) : QObject(parent), session_(session) {
  // Edits only: loading a model must not overwrite what a crashed session left behind.
  connect(session_, &SessionModel::constraintsEdited, this, &ConstraintAutosave::save);
}

QString ConstraintAutosave::path(Role role) {
  return QDir(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation))
      .filePath(QString("autosave-%1-constraints.json").arg(roleName(role)));
}

bool ConstraintAutosave::exists(Role role) { return QFileInfo::exists(path(role)); }

void ConstraintAutosave::save(Role role) {
  if (!enabled_ || !session_->hasModel(role)) return;
  const QString file = path(role);
  try {
    QDir().mkpath(QFileInfo(file).absolutePath());
    write_constraint_set(file.toStdString(), session_->constraints(role).set);
    emit saved(file);
  } catch (const std::exception& e) {
    emit failed(QString::fromStdString(e.what()));
  }
}

}  // namespace facehex::gui

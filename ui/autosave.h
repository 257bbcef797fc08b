#pragma once
// Writes a model's constraint set to a file under QStandardPaths::AppDataLocation after every edit (and undo), so a
// crash loses no placed constraint; File > Recover loads it back as an ordinary, undoable load.
#include <QObject>

#include "ui/session_model.h"

namespace facehex::gui {

class ConstraintAutosave : public QObject {
  Q_OBJECT

 public:
  explicit ConstraintAutosave(SessionModel* session, QObject* parent = nullptr);

  static QString path(Role role);
  static bool exists(Role role);
  void setEnabled(bool enabled) { enabled_ = enabled; }

 signals:
  void saved(const QString& path);
  void failed(const QString& message);

 private:
  void save(Role role);

  SessionModel* session_;
  bool enabled_ = true;
};

}  // namespace facehex::gui

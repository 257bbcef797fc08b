#pragma once
// The session's messages, kept for the whole session: every job's outcome (what was opened or segmented, the fields,
// what the transfer gave) with its detail under it, every error with the core's message unchanged, and the notes of
// quick operations (saved, exported). A message that names a vertex or a constraint of a model ("vertex 436 gets
// two values", "constraint 'eyebrow' selects no vertex") shows it when clicked, through the session's highlight.
#include <QTreeWidget>
#include <optional>

#include "ui/session_model.h"

namespace facehex::gui {

// The vertex or constraint `message` names, on the model whose source (SessionModel's LoadedModel::source) starts
// it, else on the patient; none when the model has no such vertex or constraint.
std::optional<Highlight> namedInMessage(const QString& message, const SessionModel& session);

class MessageLog : public QTreeWidget {
  Q_OBJECT

 public:
  enum class Kind { Outcome, Error, Note };
  explicit MessageLog(SessionModel* session, QWidget* parent = nullptr);
  // Appends a message, its detail lines as its children, and scrolls to it.
  void add(Kind kind, const QString& text, const QStringList& detail = {});

 private:
  void show(QTreeWidgetItem* item);

  SessionModel* session_;
};

}  // namespace facehex::gui

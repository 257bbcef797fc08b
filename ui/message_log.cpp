#include "ui/message_log.h"

#include <QHeaderView>
#include <QRegularExpression>
#include <QStyle>
#include <QTime>
#include <algorithm>
#include <map>

namespace facehex::gui {
namespace {

enum Column { kTime, kText };

QString describe(const Highlight& h, const SessionModel& session) {
  if (h.vertex >= 0) return QObject::tr("vertex %1 of the %2").arg(h.vertex).arg(roleName(h.role));
  return QObject::tr("constraint '%1' of the %2")
      .arg(QString::fromStdString(session.constraints(h.role).set.constraints.at(h.constraint).name), roleName(h.role));
}

}  // namespace

std::optional<Highlight> namedInMessage(const QString& message, const SessionModel& session) {
  Highlight h;
  for (Role r : kRoles)
    if (session.hasModel(r) && message.startsWith(QString::fromStdString(session.model(r).source()) + ":")) h.role = r;
  if (!session.hasModel(h.role)) return std::nullopt;
  const LoadedModel& m = session.model(h.role);
  static const QRegularExpression vertex(R"(\bvertex (\d+)\b)"), constraint(R"((?:constraint|feature) '([^']*)')");
  if (const QRegularExpressionMatch v = vertex.match(message); v.hasMatch()) {
    const long id = v.captured(1).toLong();
    if (id >= m.domain.V.rows()) return std::nullopt;
    h.vertex = static_cast<int>(id);
    return h;
  }
  if (const QRegularExpressionMatch c = constraint.match(message); c.hasMatch()) {
    const std::string name = c.captured(1).toStdString();
    const auto& cs = m.constraints.set.constraints;
    const auto it = std::find_if(cs.begin(), cs.end(), [&name](const Constraint& k) { return k.name == name; });
    if (it == cs.end()) return std::nullopt;
    h.constraint = static_cast<int>(it - cs.begin());
    return h;
  }
  return std::nullopt;
}

MessageLog::MessageLog(SessionModel* session, QWidget* parent) : QTreeWidget(parent), session_(session) {
  setObjectName("messageLog");
  setColumnCount(2);
  setHeaderLabels({tr("Time"), tr("Message")});
  header()->setSectionResizeMode(kTime, QHeaderView::ResizeToContents);
  header()->setStretchLastSection(true);
  setWordWrap(true);
  setUniformRowHeights(false);
  setSelectionMode(QAbstractItemView::SingleSelection);
  connect(this, &QTreeWidget::itemClicked, this, [this](QTreeWidgetItem* item) { show(item); });
  connect(this, &QTreeWidget::itemActivated, this, [this](QTreeWidgetItem* item) { show(item); });
}

void MessageLog::add(Kind kind, const QString& text, const QStringList& detail) {
  static const std::map<Kind, QStyle::StandardPixmap> kIcons = {{Kind::Outcome, QStyle::SP_DialogApplyButton},
                                                                {Kind::Error, QStyle::SP_MessageBoxCritical},
                                                                {Kind::Note, QStyle::SP_MessageBoxInformation}};
  auto* item = new QTreeWidgetItem(this, {QTime::currentTime().toString("HH:mm:ss"), text});
  item->setIcon(kTime, style()->standardIcon(kIcons.at(kind)));
  item->setToolTip(kText, text);
  QList<QTreeWidgetItem*> lines{item};
  for (const QString& line : detail) {
    if (line.isEmpty()) continue;
    auto* child = new QTreeWidgetItem(item, {QString(), line});
    child->setToolTip(kText, line);
    lines << child;
  }
  // Each line that names a vertex or a constraint links to it (looked up again when clicked: a constraint by its name).
  for (QTreeWidgetItem* line : lines)
    if (const std::optional<Highlight> h = namedInMessage(line->text(kText), *session_)) {
      line->setForeground(kText, palette().color(QPalette::Link));
      line->setToolTip(kText, tr("%1\n\nClick to show %2").arg(line->text(kText), describe(*h, *session_)));
    }
  item->setExpanded(kind != Kind::Note);
  scrollToItem(lines.back());
}

void MessageLog::show(QTreeWidgetItem* item) {
  const std::optional<Highlight> h = namedInMessage(item->text(kText), *session_);
  if (!h) return;
  // The list beside the views shows the model the message is about.
  session_->setActiveRole(h->role);
  session_->setHighlight(h);
}

}  // namespace facehex::gui

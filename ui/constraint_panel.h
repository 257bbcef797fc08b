#pragma once
// Placing and editing constraints: which model the plane acts on, the editable list (rename, change field or value,
// show/hide, delete; as tall as the automatic set), the plane's band and region and the number of vertices it
// selects, and a form that turns the selection into a constraint (name, field, value). File operations and undo/redo
// are the main window's actions, shown here as buttons. Everything goes through the SessionModel.
#include <QWidget>

#include "ui/session_model.h"

class QAction;
class QComboBox;
class QDoubleSpinBox;
class QGridLayout;
class QGroupBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QTableWidget;

namespace facehex::gui {

class ConstraintPanel : public QWidget {
  Q_OBJECT

 public:
  // actions: the main window's (facial features, load, merge, save, ...), shown as buttons under the list.
  ConstraintPanel(SessionModel* session, const QList<QAction*>& actions, QWidget* parent = nullptr);

 private:
  QGroupBox* buildPlaneBox();
  QGroupBox* buildNewConstraintBox();
  void buildTable();
  QGridLayout* buildListButtons(const QList<QAction*>& actions);
  void refreshModelChoice();
  void refreshPlane();
  void refreshList();
  void onCellChanged(int row, int column);
  void addFromPlane();
  void snapNormal(int axis);
  void editPlane(const std::function<void(PlanePose&)>& change);

  SessionModel* session_;
  QComboBox* modelChoice_;
  QDoubleSpinBox* band_;
  QComboBox* region_;
  QLabel* selectionCount_;
  QLineEdit* name_;
  QComboBox* field_;
  QDoubleSpinBox* value_;
  QPushButton* add_;
  QTableWidget* table_;
  QPushButton* remove_;
  QPushButton* sides_;
};

}  // namespace facehex::gui

#pragma once
// The quality tables of the paper for the last transfer: Table 1, the distortion of the dihedral angles of the
// mapped mesh against the standard in the paper's bins; Table 2, the element quality (mean shape and the rest) of
// the standard and of the patient hex mesh.
#include <QWidget>

#include "ui/session_model.h"

class QLabel;
class QTableWidget;

namespace facehex::gui {

class QualityPanel : public QWidget {
  Q_OBJECT

 public:
  explicit QualityPanel(SessionModel* session, QWidget* parent = nullptr);

 private:
  void refresh();

  SessionModel* session_;
  QLabel* status_;
  QTableWidget* distortion_;
  QTableWidget* quality_;
};

}  // namespace facehex::gui

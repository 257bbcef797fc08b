#pragma once
// What the views show: the field colouring and iso-lines, the cut at the plane, the gradient glyphs before or after
// the orthogonality improvement, and the hex meshes by quality with the threshold that isolates bad elements.
// Edits the session's DisplaySettings only.
#include <QWidget>

#include "ui/session_model.h"

class QCheckBox;
class QComboBox;
class QLabel;
class QSlider;

namespace facehex::gui {

class DisplayPanel : public QWidget {
  Q_OBJECT

 public:
  explicit DisplayPanel(SessionModel* session, QWidget* parent = nullptr);

 private:
  void refresh();
  void edit(const std::function<void(DisplaySettings&)>& change);

  SessionModel* session_;
  QComboBox* field_;
  QCheckBox* isoLines_;
  QCheckBox* clip_;
  QComboBox* glyphs_;
  QCheckBox* showHex_;
  QComboBox* measure_;
  QSlider* threshold_;
  QLabel* thresholdLabel_;
  QCheckBox* constraints_;
  QCheckBox* plane_;
  QCheckBox* landmarks_;
};

}  // namespace facehex::gui

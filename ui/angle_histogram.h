#pragma once
// The paper's Fig. 6 for the active model: the histogram of the angles between the three pairs of field gradients
// in every tet, before and after the orthogonality improvement (a good parameterization piles up at 90 degrees).
#include <QWidget>

#include "ui/session_model.h"

namespace facehex::gui {

class AngleHistogram : public QWidget {
  Q_OBJECT

 public:
  explicit AngleHistogram(SessionModel* session, QWidget* parent = nullptr);
  QSize sizeHint() const override { return {520, 240}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  SessionModel* session_;
};

}  // namespace facehex::gui

#include "ui/display_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QSignalBlocker>
#include <QSlider>

namespace facehex::gui {
namespace {

QWidget* row(std::initializer_list<QWidget*> widgets) {
  auto* w = new QWidget;
  auto* layout = new QHBoxLayout(w);
  layout->setContentsMargins(0, 0, 0, 0);
  for (QWidget* child : widgets) layout->addWidget(child, child->inherits("QSlider") ? 1 : 0);
  layout->addStretch();
  return w;
}

}  // namespace

DisplayPanel::DisplayPanel(SessionModel* session, QWidget* parent) : QWidget(parent), session_(session) {
  setObjectName("displayPanel");
  field_ = new QComboBox(this);
  field_->setObjectName("colourBy");
  field_->addItems({tr("nothing (plain surface)"), tr("u: lateral -x \u2192 +x"), tr("v: bottom \u2192 top"),
                    tr("w: bone \u2192 skin")});
  isoLines_ = new QCheckBox(tr("iso-lines every 0.1"), this);
  clip_ = new QCheckBox(tr("cut open at the plane"), this);
  clip_->setToolTip(tr("Show the fields inside the model, on the cut"));
  glyphs_ = new QComboBox(this);
  glyphs_->setObjectName("glyphs");
  glyphs_->addItems({tr("off"), tr("before orthogonalization"), tr("after orthogonalization")});
  glyphs_->setToolTip(tr("Gradient arrows of u (red), v (green) and w (blue) on a subset of the tets"));
  showHex_ = new QCheckBox(tr("Hex meshes by quality:"), this);
  showHex_->setObjectName("showHex");
  measure_ = new QComboBox(this);
  measure_->setObjectName("qualityMeasure");
  measure_->addItems({tr("shape"), tr("scaled Jacobian")});
  threshold_ = new QSlider(Qt::Horizontal, this);
  threshold_->setObjectName("qualityThreshold");
  threshold_->setRange(0, 100);
  thresholdLabel_ = new QLabel(this);
  thresholdLabel_->setMinimumWidth(thresholdLabel_->fontMetrics().horizontalAdvance("\u2264 0.00 only  "));
  constraints_ = new QCheckBox(tr("constraint vertices"), this);
  plane_ = new QCheckBox(tr("cutting plane and selection"), this);
  landmarks_ = new QCheckBox(tr("landmarks"), this);
  landmarks_->setObjectName("showLandmarks");
  landmarks_->setToolTip(
      tr("The facial landmarks the feature lines are placed at; drag one along the skin to move it"));

  auto* form = new QFormLayout(this);
  form->addRow(tr("Colour by:"), field_);
  form->addRow("", row({isoLines_, clip_}));
  form->addRow(tr("Gradients:"), glyphs_);
  form->addRow("", row({showHex_, measure_}));
  form->addRow(tr("Threshold:"), row({threshold_, thresholdLabel_}));
  form->addRow(tr("Show:"), row({constraints_, plane_}));
  form->addRow("", row({landmarks_}));

  connect(field_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int i) { edit([i](DisplaySettings& d) { d.field = i - 1; }); });
  connect(isoLines_, &QCheckBox::toggled, this, [this](bool b) { edit([b](DisplaySettings& d) { d.isoLines = b; }); });
  connect(clip_, &QCheckBox::toggled, this, [this](bool b) { edit([b](DisplaySettings& d) { d.clipAtPlane = b; }); });
  connect(glyphs_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int i) { edit([i](DisplaySettings& d) { d.glyphs = static_cast<GlyphMode>(i); }); });
  connect(showHex_, &QCheckBox::toggled, this, [this](bool b) { edit([b](DisplaySettings& d) { d.showHex = b; }); });
  connect(measure_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int i) { edit([i](DisplaySettings& d) { d.measure = static_cast<QualityMeasure>(i); }); });
  connect(threshold_, &QSlider::valueChanged, this,
          [this](int v) { edit([v](DisplaySettings& d) { d.threshold = v / 100.0; }); });
  connect(constraints_, &QCheckBox::toggled, this,
          [this](bool b) { edit([b](DisplaySettings& d) { d.showConstraints = b; }); });
  connect(plane_, &QCheckBox::toggled, this, [this](bool b) { edit([b](DisplaySettings& d) { d.showPlane = b; }); });
  connect(landmarks_, &QCheckBox::toggled, this,
          [this](bool b) { edit([b](DisplaySettings& d) { d.showLandmarks = b; }); });
  connect(session_, &SessionModel::displayChanged, this, &DisplayPanel::refresh);
  refresh();
}

void DisplayPanel::edit(const std::function<void(DisplaySettings&)>& change) {
  DisplaySettings d = session_->display();
  change(d);
  session_->setDisplay(d);
}

void DisplayPanel::refresh() {
  const DisplaySettings& d = session_->display();
  const QSignalBlocker b1(field_), b2(isoLines_), b3(clip_), b4(glyphs_), b5(showHex_), b6(measure_), b7(threshold_),
      b8(constraints_), b9(plane_), b10(landmarks_);
  field_->setCurrentIndex(d.field + 1);
  isoLines_->setChecked(d.isoLines);
  clip_->setChecked(d.clipAtPlane);
  glyphs_->setCurrentIndex(static_cast<int>(d.glyphs));
  showHex_->setChecked(d.showHex);
  measure_->setCurrentIndex(static_cast<int>(d.measure));
  threshold_->setValue(static_cast<int>(std::lround(d.threshold * 100)));
  constraints_->setChecked(d.showConstraints);
  plane_->setChecked(d.showPlane);
  landmarks_->setChecked(d.showLandmarks);
  isoLines_->setEnabled(d.field >= 0);
  measure_->setEnabled(d.showHex);
  threshold_->setEnabled(d.showHex);
  thresholdLabel_->setText(d.threshold >= 1.0 ? tr("all cells") : tr("\u2264 %1 only").arg(d.threshold, 0, 'f', 2));
}

}  // namespace facehex::gui

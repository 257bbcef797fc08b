#include "ui/segmentation_dialog.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QRegularExpression>
#include <QVBoxLayout>
#include <utility>
#include <vector>

#include "core/segment/dicom_series.h"
#include "core/util/error.h"

namespace facehex::gui {
namespace {

const QStringList kAxes = {"+x", "-x", "+y", "-y", "+z", "-z"};

QDoubleSpinBox* spinBox(double lo, double hi, const QString& suffix, const QString& name, QWidget* parent) {
  auto* box = new QDoubleSpinBox(parent);
  box->setObjectName(name);
  box->setRange(lo, hi);
  box->setDecimals(1);
  box->setSuffix(suffix);
  return box;
}

QComboBox* axisChoice(const QString& name, const QString& fallback, QWidget* parent) {
  auto* box = new QComboBox(parent);
  box->setObjectName(name);
  box->addItem(QObject::tr("a DICOM series' own, else voxel axis %1").arg(fallback), QString());
  for (const QString& axis : kAxes) box->addItem(QObject::tr("voxel axis %1").arg(axis), axis);
  return box;
}

void selectAxis(QComboBox* box, const std::string& axis) {
  box->setCurrentIndex(std::max(0, box->findData(QString::fromStdString(axis))));
}

}  // namespace

void SegmentationDialog::OptionalNumber::set(const std::optional<double>& given) {
  automatic->setChecked(!given);
  if (given) value->setValue(*given);
}

std::optional<double> SegmentationDialog::OptionalNumber::get() const {
  if (automatic->isChecked()) return std::nullopt;
  return value->value();
}

SegmentationDialog::SegmentationDialog(QWidget* parent) : QDialog(parent) {
  setObjectName("segmentationDialog");
  setWindowTitle(tr("Segment the CT"));
  auto* layout = new QVBoxLayout(this);
  heading_ = new QLabel(this);
  heading_->setWordWrap(true);
  layout->addWidget(heading_);
  failure_ = new QLabel(this);
  failure_->setObjectName("segmentFailure");
  failure_->setWordWrap(true);
  failure_->setStyleSheet("color: #b00020;");
  failure_->hide();
  layout->addWidget(failure_);

  auto* form = new QFormLayout;
  form_ = form;
  // A row of a form, and the command line's option it sets.
  const auto addRow = [&](QFormLayout* into, const QString& label, auto* field, const QString& option) {
    into->addRow(label, field);
    rowOfOption_.emplace_back(option, label);
  };
  series_ = new QComboBox(this);
  series_->setObjectName("segmentSeries");
  series_->setToolTip(
      tr("The DICOM folder holds several series (a localizer, other reconstructions): the one to "
         "segment. Largest first."));
  addRow(form, tr("DICOM series"), series_, "--series");
  edgeLength_ = spinBox(0.5, 20, tr(" mm"), "segmentEdgeLength", this);
  edgeLength_->setToolTip(tr("Target mean edge length of the tets (the paper: about 2 mm). Coarser is faster."));
  addRow(form, tr("Tet edge length"), edgeLength_, "--edge-length");
  coarsenLargeFaces_ = new QCheckBox(tr("coarser for a coarse scan or a large face"), this);
  coarsenLargeFaces_->setObjectName("segmentCoarsenLargeFaces");
  coarsenLargeFaces_->setToolTip(
      tr("The edges are at least the CT's coarsest voxel spacing (up to %1 mm), and a face whose model would have "
         "more tets than the transfer gains from (a fine CT showing the face and neck) is meshed with longer edges "
         "(docs/segmentation.md). Untick to keep the edge length as given.")
          .arg(kMostScanEdgeLength));
  form->addRow(QString(), coarsenLargeFaces_);
  madeAt_ = new QLabel(this);
  madeAt_->setObjectName("segmentMadeAt");
  madeAt_->setWordWrap(false);
  form->addRow(QString(), madeAt_);
  anterior_ = axisChoice("segmentAnterior", "+y", this);
  superior_ = axisChoice("segmentSuperior", "+z", this);
  addRow(form, tr("Face looks along"), anterior_, "--anterior");
  addRow(form, tr("Top of the head along"), superior_, "--superior");

  const auto addNumber = [&](Number n, const QString& label, double lo, double hi, const QString& suffix,
                             const QString& name, const QString& option, const QString& tip) {
    OptionalNumber& number = numbers_[n];
    number.automatic = new QCheckBox(tr("automatic"), this);
    number.automatic->setObjectName(name + "Automatic");
    number.value = spinBox(lo, hi, suffix, name, this);
    number.value->setToolTip(tip);
    number.automatic->setToolTip(tip);
    connect(number.automatic, &QCheckBox::toggled, number.value, &QWidget::setDisabled);
    number.set(std::nullopt);
    number.value->setDisabled(true);
    auto* row = new QHBoxLayout;
    row->addWidget(number.automatic);
    row->addWidget(number.value, 1);
    addRow(form, label, row, option);
  };
  const QString units = tr("in the file's intensity units (Hounsfield units when the file says so)");
  addNumber(Skin, tr("Skin threshold"), -1e5, 1e5, QString(), "segmentSkin", "--skin",
            tr("Body above this intensity; automatic: from the histogram. ") + units);
  addNumber(Bone, tr("Bone threshold"), -1e5, 1e5, QString(), "segmentBone", "--bone",
            tr("Bone above this intensity; automatic: from the histogram. ") + units);
  addNumber(DenoisingBlur, tr("Denoising blur"), 0, kMostDenoisingBlur * 4, tr(" mm"), "segmentDenoise", "--denoise",
            tr("Gaussian blur of the CT before it is segmented; automatic: the blur that brings a noisy CT's voxel "
               "noise (a low-dose or cone-beam CT's) down to a diagnostic CT's, none for a CT that quiet; 0: none."));
  addNumber(HeadTurnAngle, tr("Head turn"), -45, 45, tr(" deg"), "segmentHeadTurn", "--head-turn",
            tr("Degrees the head is turned about the vertical axis in the scanner, towards +x from +y; the cuts are "
               "placed in the head frame turned back by it, and the model stays in the CT's frame. Automatic: from "
               "the head's mirror symmetry, none under 2 degrees; 0: the CT's own frame."));
  addNumber(
      HeadPitchAngle, tr("Head pitch"), -45, 45, tr(" deg"), "segmentHeadPitch", "--head-pitch",
      tr("Degrees the head is pitched (nodding) about the lateral axis in the scanner, positive with the chin "
         "raised; the cuts are placed in the head frame pitched back by it, and the model stays in the CT's "
         "frame. Automatic: the CT's own frame, or the hard palate's slope when the face or its landmarks are not "
         "found there and it slopes 5 degrees or more; 0: the CT's own frame only."));
  const QString frame =
      tr("Millimetres in the head frame: the file's coordinates, axes swapped or negated so the face looks to +y "
         "and the top of the head is +z, turned and pitched back by the head's turn and pitch.");
  addNumber(TopCut, tr("Top cut z"), -1e4, 1e4, tr(" mm"), "segmentTopCut", "--top-cut",
            tr("Automatic: the brow clearance above the glabella, within the CT. ") + frame);
  addNumber(BottomCut, tr("Bottom cut z"), -1e4, 1e4, tr(" mm"), "segmentBottomCut", "--bottom-cut",
            tr("Automatic: the chin clearance below the chin's bone. ") + frame);
  addNumber(PosteriorCut, tr("Posterior cut y"), -1e4, 1e4, tr(" mm"), "segmentPosteriorCut", "--posterior-cut",
            tr("Automatic: a vertical plane the ear clearance in front of both tragi, its y at the mid-plane "
               "shown; a value given is a coronal plane. ") +
                frame);
  addNumber(
      MidPlane, tr("Mid-plane x"), -1e4, 1e4, tr(" mm"), "segmentMidPlane", "--mid-plane",
      tr("Divides the posterior cut into the u0 and u1 ends; automatic: the face's mirror-symmetry plane. ") + frame);
  browClearance_ = spinBox(0, 100, tr(" mm"), "segmentBrowClearance", this);
  chinClearance_ = spinBox(0, 100, tr(" mm"), "segmentChinClearance", this);
  earClearance_ = spinBox(0, 100, tr(" mm"), "segmentEarClearance", this);
  addRow(form, tr("Brow clearance (automatic top cut)"), browClearance_, "--brow-clearance");
  addRow(form, tr("Chin clearance (automatic bottom cut)"), chinClearance_, "--chin-clearance");
  addRow(form, tr("Ear clearance (automatic posterior cut)"), earClearance_, "--ear-clearance");
  // The soft-tissue layer's settings, beside the rest (the dialog stays short enough for a laptop's screen): the ones
  // a segmentation's error names when its surface has tunnels (docs/segmentation.md).
  auto* tissue = new QGroupBox(tr("Soft-tissue layer"), this);
  auto* tissueForm = new QFormLayout(tissue);
  const auto addLength = [&](QDoubleSpinBox*& box, const QString& label, double lo, const QString& name,
                             const QString& option, const QString& tip) {
    box = spinBox(lo, 100, tr(" mm"), name, this);
    box->setToolTip(tip + tr(" (the command line's %1)").arg(option));
    addRow(tissueForm, label, box, option);
  };
  addLength(minThickness_, tr("Min thickness"), 0, "segmentMinThickness", "--min-thickness",
            tr("Tissue this close below the skin is always in the model, bone or not (thin skin over bone)."));
  addLength(maxDepth_, tr("Max depth"), 0.5, "segmentMaxDepth", "--max-depth",
            tr("Nothing deeper than this below the skin is in the model, where no bone is nearer."));
  addLength(boneGap_, tr("Bone gap"), 0, "segmentBoneGap", "--bone-gap",
            tr("Gaps in the bone narrower than twice this (between the teeth, thin orbital walls) still hide the "
               "tissue behind them."));
  addLength(cavityClosing_, tr("Cavity closing"), 0, "segmentCavityClosing", "--cavity-closing",
            tr("Openings narrower than twice this (nostrils, lips, eyelids) are closed."));
  addLength(smoothing_, tr("Smoothing"), 0, "segmentSmoothing", "--smoothing",
            tr("Gaussian blur of the model before its surface is taken."));
  skinObjects_ = new QCheckBox(tr("landmarks under straps, tape"), this);
  skinObjects_->setObjectName("segmentSkinObjects");
  skinObjects_->setToolTip(
      tr("An object lying on the skin's front above the nose tip (a head strap, thick tape) is found by its edges in "
         "the CT, and the landmarks there are read on the skin under it. Untick to read them on the skin as "
         "segmented (the command line's --skin-objects off)."));
  tissueForm->addRow(QString(), skinObjects_);
  auto* columns = new QHBoxLayout;
  columns->addLayout(form, 1);
  columns->addWidget(tissue, 0, Qt::AlignTop);
  layout->addLayout(columns);

  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
  buttons->button(QDialogButtonBox::Ok)->setText(tr("Segment"));
  buttons->button(QDialogButtonBox::Ok)->setObjectName("segmentButton");
  connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
  layout->addWidget(buttons);
  setOptions(SegmentOptions{});
  setCt(QString());
}

void SegmentationDialog::setCt(const QString& path) {
  heading_->setText(path.isEmpty() ? tr("Segment a head CT into the facial soft-tissue model.")
                                   : tr("Segment <b>%1</b> into the facial soft-tissue model (docs/segmentation.md).")
                                         .arg(QFileInfo(path).fileName().toHtmlEscaped()));
  heading_->setToolTip(path);
  madeAt_->hide();  // until showFound says how this CT's model was made
  failure_->hide();
  // A DICOM folder's series, when there is a choice to make.
  series_->clear();
  folderSeries_.clear();
  if (QFileInfo(path).isDir()) {
    try {
      folderSeries_ = dicom_series_in(path.toStdString());
    } catch (const Error&) {
      // not readable as a folder: the segmentation says why
    }
  }
  if (folderSeries_.size() > 1)
    for (size_t i = 0; i < folderSeries_.size(); ++i)
      series_->addItem(QString("%1: %2").arg(i + 1).arg(QString::fromStdString(series_text(folderSeries_[i]))),
                       QString::fromStdString(folderSeries_[i].uid));
  series_->setVisible(folderSeries_.size() > 1);
  form_->labelForField(series_)->setVisible(folderSeries_.size() > 1);
}

void SegmentationDialog::showFailure(const QString& message) {
  QStringList named;
  for (const auto& [option, label] : rowOfOption_)
    if (message.contains(QRegularExpression(QRegularExpression::escape(option) + "(?![\\w-])"))) named << label;
  // The first lines of a long message (a second attempt's reasons follow the first's): the dialog stays short enough
  // for a laptop's screen; the tooltip and the Messages tab have all of it.
  constexpr int kShownCharacters = 320;
  const QString shown = message.size() > kShownCharacters ? message.left(kShownCharacters) + "\u2026" : message;
  QString text = tr("The last segmentation stopped: %1").arg(shown.toHtmlEscaped());
  if (!named.isEmpty()) text += tr("<br><b>In this dialog: %1.</b>").arg(named.join(", "));
  failure_->setText(text);
  failure_->setToolTip(message);
  failure_->show();
}

void SegmentationDialog::setOptions(const SegmentOptions& o) {
  edgeLength_->setValue(o.tets.target_edge_length);
  coarsenLargeFaces_->setChecked(o.coarsen_above_tets > 0 || o.follow_scan_spacing);
  if (const DicomSeries* named = series_->count() > 0 ? named_series(folderSeries_, o.dicom_series) : nullptr)
    series_->setCurrentIndex(static_cast<int>(named - folderSeries_.data()));
  selectAxis(anterior_, o.orientation.anterior);
  selectAxis(superior_, o.orientation.superior);
  numbers_[Skin].set(o.skin_threshold);
  numbers_[Bone].set(o.bone_threshold);
  numbers_[HeadTurnAngle].set(o.cuts.head_turn);
  numbers_[HeadPitchAngle].set(o.cuts.head_pitch);
  numbers_[TopCut].set(o.cuts.top_z);
  numbers_[BottomCut].set(o.cuts.bottom_z);
  numbers_[PosteriorCut].set(o.cuts.posterior_y);
  numbers_[MidPlane].set(o.cuts.centre_x);
  numbers_[DenoisingBlur].set(o.denoising_blur < 0 ? std::nullopt : std::optional<double>(o.denoising_blur));
  browClearance_->setValue(o.cuts.brow_clearance);
  chinClearance_->setValue(o.cuts.chin_clearance);
  earClearance_->setValue(o.cuts.ear_clearance);
  minThickness_->setValue(o.min_thickness);
  maxDepth_->setValue(o.max_depth);
  boneGap_->setValue(o.bone_gap_radius);
  cavityClosing_->setValue(o.cavity_closing_radius);
  smoothing_->setValue(o.smoothing_sigma);
  skinObjects_->setChecked(o.find_skin_objects);
}

SegmentOptions SegmentationDialog::options() const {
  SegmentOptions o;
  o.tets.target_edge_length = edgeLength_->value();
  if (!coarsenLargeFaces_->isChecked()) {
    o.coarsen_above_tets = 0;
    o.follow_scan_spacing = false;
  }
  if (series_->count() > 0) o.dicom_series = series_->currentData().toString().toStdString();
  o.orientation.anterior = anterior_->currentData().toString().toStdString();
  o.orientation.superior = superior_->currentData().toString().toStdString();
  o.skin_threshold = numbers_[Skin].get();
  o.bone_threshold = numbers_[Bone].get();
  o.cuts.head_turn = numbers_[HeadTurnAngle].get();
  o.cuts.head_pitch = numbers_[HeadPitchAngle].get();
  o.cuts.top_z = numbers_[TopCut].get();
  o.cuts.bottom_z = numbers_[BottomCut].get();
  o.cuts.posterior_y = numbers_[PosteriorCut].get();
  o.cuts.centre_x = numbers_[MidPlane].get();
  o.denoising_blur = numbers_[DenoisingBlur].get().value_or(-1);
  o.cuts.brow_clearance = browClearance_->value();
  o.cuts.chin_clearance = chinClearance_->value();
  o.cuts.ear_clearance = earClearance_->value();
  o.min_thickness = minThickness_->value();
  o.max_depth = maxDepth_->value();
  o.bone_gap_radius = boneGap_->value();
  o.cavity_closing_radius = cavityClosing_->value();
  o.smoothing_sigma = smoothing_->value();
  o.find_skin_objects = skinObjects_->isChecked();
  return o;
}

void SegmentationDialog::showFound(const CtSegmentation& segmentation) {
  const TissueThresholds& thresholds = segmentation.thresholds;
  const FaceCuts& cuts = segmentation.cuts;
  const std::array<double, kNumbers> found = {thresholds.skin,  thresholds.bone, cuts.turn.degrees,
                                              cuts.turn.pitch,  cuts.top_z,      cuts.bottom_z,
                                              cuts.posterior_y, cuts.centre_x,   segmentation.noise.blur};
  for (int n = 0; n < kNumbers; ++n)
    if (numbers_[n].automatic->isChecked()) numbers_[n].value->setValue(found[n]);
  madeAt_->setText(segmentation.edge_length_rule.empty()
                       ? tr("The model's tets were made at %1 mm.").arg(segmentation.edge_length, 0, 'f', 1)
                       : tr("The model's tets were made at %1 mm (%2).")
                             .arg(segmentation.edge_length, 0, 'f', 1)
                             .arg(QString::fromStdString(segmentation.edge_length_rule)));
  madeAt_->show();
}

}  // namespace facehex::gui

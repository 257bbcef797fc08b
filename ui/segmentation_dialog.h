#pragma once
// The options of a CT's segmentation (core/segment/soft_tissue.h), asked before a CT is segmented: tet edge length,
// the voxel axes the face and the top of the head point along, the skin and bone thresholds, the head's turn about
// the vertical axis and the four cut planes (in the head frame that turn gives). Thresholds and cuts are "automatic"
// (found in the CT) unless unticked; after a segmentation the dialog can show the values that were found, so unticking
// one starts from it (the loop: segment, look, move a cut, segment again). The same options as `facehex segment`, with
// the same defaults.
#include <QDialog>
#include <QString>
#include <array>
#include <utility>
#include <vector>

#include "core/segment/dicom_series.h"
#include "core/segment/patient_input.h"
#include "core/segment/soft_tissue.h"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QFormLayout;
class QLabel;

namespace facehex::gui {

class SegmentationDialog : public QDialog {
  Q_OBJECT

 public:
  explicit SegmentationDialog(QWidget* parent = nullptr);

  // Names the CT in the dialog's heading; a DICOM folder holding several series shows them to choose from.
  void setCt(const QString& path);
  void setOptions(const SegmentOptions& options);
  SegmentOptions options() const;
  // What a segmentation of this CT found: its thresholds and cuts in the boxes that are still automatic, and the
  // edge length its tets were made at under the edge length's box.
  void showFound(const CtSegmentation& segmentation);
  // Why the last segmentation of this CT stopped, above the settings, with the settings of this dialog its message
  // names (it names the command line's options); until setCt.
  void showFailure(const QString& message);

 private:
  // A number that is either automatic (box disabled, showing the found value if any) or given.
  struct OptionalNumber {
    QCheckBox* automatic = nullptr;
    QDoubleSpinBox* value = nullptr;
    void set(const std::optional<double>& given);
    std::optional<double> get() const;
  };
  enum Number {
    Skin,
    Bone,
    HeadTurnAngle,
    HeadPitchAngle,
    TopCut,
    BottomCut,
    PosteriorCut,
    MidPlane,
    DenoisingBlur,
    kNumbers
  };

  QLabel *heading_, *failure_, *madeAt_;
  QDoubleSpinBox *edgeLength_, *browClearance_, *chinClearance_, *earClearance_;
  QDoubleSpinBox *minThickness_, *maxDepth_, *boneGap_, *cavityClosing_, *smoothing_;  // the soft-tissue layer
  QCheckBox *coarsenLargeFaces_, *skinObjects_;
  QComboBox *anterior_, *superior_;
  QComboBox* series_;                      // a DICOM folder's series, shown when it holds several
  std::vector<DicomSeries> folderSeries_;  // the CT's series when it is a DICOM folder (dicom_series_in)
  QFormLayout* form_;
  std::array<OptionalNumber, kNumbers> numbers_;
  // Each row's label and the command line's option it sets, in the dialog's order (showFailure names the rows).
  std::vector<std::pair<QString, QString>> rowOfOption_;
};

}  // namespace facehex::gui

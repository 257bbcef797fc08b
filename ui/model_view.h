#pragma once
// One 3D view of a model (the standard or the patient), rendered from the session: the surface, plain or coloured by
// a field with iso-lines and optionally cut open at the plane; the vertices of the visible constraints; on the active
// model, the cutting-plane widget and the vertices it selects; gradient glyphs; and the hex mesh coloured by quality
// with a threshold; the model's facial landmarks as labelled handles on its surface (the tragi, which lie behind the
// model, as labelled markers only). Dragging the plane widget moves
// the session's plane; releasing a dragged landmark is reported (landmarkMoved) for the controller to place its
// features again: the view never edits anything else.
#include <Eigen/Core>
#include <QRectF>
#include <QWidget>
#include <array>
#include <memory>
#include <vector>

#include "ui/session_model.h"

class QLabel;
class vtkObject;
class QStackedWidget;

namespace facehex::gui {

class ModelView : public QWidget {
  Q_OBJECT

 public:
  ModelView(SessionModel* session, Role role, QWidget* parent = nullptr);
  ~ModelView() override;

  Role role() const { return role_; }
  // Moves the plane widget as a drag by the user would; the session's plane follows (scripted states, tests).
  void movePlaneWidget(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal);
  // Moves a landmark's handle to `point` and releases it, as a drag by the user would (tests).
  void dragLandmark(const std::string& name, const Eigen::Vector3d& point);
  // The landmark handles where the session's landmarks are (after a move the session refused).
  void showSessionLandmarks();
  // Where a point of the model appears in the 3D widget (widget pixels; tests drive the mouse there).
  QPoint widgetPosition(const Eigen::Vector3d& x) const;
  QWidget* renderWidget() const;
  // Landmarks shown in this view.
  int shownLandmarks() const;
  // The boxes of the landmarks' names as last drawn (display pixels, origin at the lower left), in the order of the
  // session's landmarks.
  std::vector<QRectF> landmarkLabelBoxes() const;
  // Frames the model in a three-quarter view, and keeps it framed as the view resizes until the user turns it.
  void resetCamera();
  // Turns the camera to look along `direction` with `viewUp`, keeping its focal point and distance (linked views).
  void setCameraOrientation(const Eigen::Vector3d& direction, const Eigen::Vector3d& viewUp);
  void render();
  // Cells the hex-quality display draws (after the threshold), or -1 when it is not shown.
  int drawnHexCells() const;
  bool planeWidgetEnabled() const;
  // Points drawn for the session's highlight (a vertex, a constraint's vertices) in this view.
  int highlightedPoints() const;

 signals:
  void cameraOrientationChanged(const Eigen::Vector3d& direction, const Eigen::Vector3d& viewUp);
  // A landmark's handle was released at `point` (on the model's surface).
  void landmarkMoved(facehex::gui::Role role, const std::string& name, const Eigen::Vector3d& point);

 private:
  struct Pipeline;
  void connectSession();
  void onModelChanged();
  void onResultsChanged();
  void refresh();
  void updateHeader();
  void updateSurface();
  void updateHex();
  void updateConstraints();
  bool cutHere() const;
  void extractSurface();
  void colourSurface();
  void updateSelection();
  void updateHighlight();
  void updateGlyphs();
  void updatePlaneWidget();
  void updateLandmarks();
  void layOutLandmarkLabels();
  void onLandmarkDragged(vtkObject* handle, unsigned long event, void*);
  void onPlaneInteraction();
  void onCameraInteraction();
  void onRenderStart();
  void frameModel();

  SessionModel* session_;
  Role role_;
  QLabel* header_;
  QStackedWidget* stack_;  // a hint while no model is loaded, then the 3D view
  bool autoFrame_ = true;
  std::array<int, 2> framedSize_{};  // the window size the camera was last framed for
  std::unique_ptr<Pipeline> p_;
};

}  // namespace facehex::gui

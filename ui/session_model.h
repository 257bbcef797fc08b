#pragma once
// The state of one FaceHex session, shared by every widget and view (the "scene" of 3D Slicer / ITK-SNAP): the two
// models (standard and patient) with their constraint sets, the cutting plane and the vertices it selects, what to
// display, and the results of the last parameterization and transfer. Widgets edit it, views render from its
// signals, the TransferController fills in the results. Every constraint edit goes through the undo stack.
#include <QObject>
#include <QString>
#include <array>
#include <deque>
#include <optional>
#include <vector>

#include "core/face/automatic_constraints.h"
#include "core/fields/constraint_set.h"
#include "core/fields/tet_domain.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/mesh/mesh.h"
#include "core/quality/hex_quality.h"
#include "core/segment/patient_input.h"
#include "core/workflow/transfer.h"

class QUndoStack;

namespace facehex::gui {

enum class Role { Standard = 0, Patient = 1 };
constexpr std::array<Role, 2> kRoles = {Role::Standard, Role::Patient};
QString roleName(Role role);  // "standard", "patient"

// A constraint set as the user edits it: the set, per constraint whether its vertices are drawn, and the facial
// landmarks its feature constraints were placed at (found, loaded or moved; undone with the constraints they placed).
struct ConstraintList {
  ConstraintSet set;
  std::vector<bool> visible;  // parallel to set.constraints
  std::optional<FaceLandmarks> landmarks;
};

// A model ready for constraint placement and parameterization (built from a file by the controller).
struct LoadedModel {
  VolumeMesh mesh;  // standard: hex-dominant mesh; patient: checked, positively oriented tet model
  // The tets the fields live on and the constraints select from: the patient's own tets, or the standard's
  // parameterization domain (its first rows are the hex vertices). For the patient hex_vertices is 0.
  TetDomain domain;
  std::vector<char> boundary;  // per domain vertex: on the domain's boundary
  ElementQuality quality;      // per cell of a hex-dominant mesh (the standard's reference quality), else empty
  QString path;                // the mesh file, or empty for a model made in memory
  QString name;                // short display name
  QString constraintsPath;     // the file its constraints came from, or empty
  ConstraintList constraints;
  // A patient segmented from a CT: the options it was segmented with, and the thresholds and cuts it used (found or
  // given); empty for a mesh file.
  std::optional<CtSegmentation> segmentation;

  // What error messages about this model name: its constraint file, else its mesh file, else its name.
  std::string source() const;
};

// The cutting plane and the slab of vertices it selects (see PlaneSelection in constraint_set.h).
struct PlanePose {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double band = kFeatureBand;     // mm, full width of the slab (as wide as the automatic features' slabs)
  std::string region = "volume";  // "volume", "boundary" or a side name
};

enum class GlyphMode { Off, Before, After };  // gradients before / after the orthogonality improvement
enum class QualityMeasure { Shape, ScaledJacobian };

struct DisplaySettings {
  int field = -1;  // -1: plain surface; 0, 1, 2: coloured by u, v, w
  bool isoLines = true;
  bool clipAtPlane = false;  // cut the model open at the plane to show the fields inside
  GlyphMode glyphs = GlyphMode::Off;
  bool showHex = false;  // hex meshes coloured by quality instead of the models
  QualityMeasure measure = QualityMeasure::Shape;
  double threshold = 1.0;  // draw only the cells whose quality is at most this
  bool showConstraints = true;
  bool showPlane = true;
  bool showLandmarks = true;
  bool operator==(const DisplaySettings& o) const;
};

// What a message names and the user asked to see: a vertex of a model (its domain's row, as the core's messages
// count them), or one of its constraints.
struct Highlight {
  Role role = Role::Patient;
  int vertex = -1;
  int constraint = -1;
  bool operator==(const Highlight& o) const {
    return role == o.role && vertex == o.vertex && constraint == o.constraint;
  }
};

class SessionModel : public QObject {
  Q_OBJECT

 public:
  explicit SessionModel(QObject* parent = nullptr);
  ~SessionModel() override;

  // Models. Loading one clears its results, the transfer, the results set aside and the undo history (old edits
  // refer to old vertices).
  bool hasModel(Role role) const { return models_[index(role)].has_value(); }
  const LoadedModel& model(Role role) const;  // requires hasModel(role)
  void setModel(Role role, LoadedModel model);
  // Incremented whenever a model or its constraints change: results computed from an older revision are stale.
  quint64 revision(Role role) const { return revisions_[index(role)]; }

  Role activeRole() const { return activeRole_; }
  void setActiveRole(Role role);

  // Constraint edits on a model (each one undoable).
  const ConstraintList& constraints(Role role) const { return model(role).constraints; }
  const std::vector<int>& constraintVertices(Role role, int i) const;
  const QString& constraintProblem(Role role, int i) const;  // why a constraint selects nothing, or empty
  void addPlaneConstraint(Role role, const QString& name, int field, double value);
  void updateConstraint(Role role, int i, const Constraint& constraint);
  void removeConstraint(Role role, int i);
  void setConstraintVisible(Role role, int i, bool visible);
  void replaceConstraints(Role role, const ConstraintSet& set, const QString& what);
  void mergeConstraints(Role role, const ConstraintSet& set, const QString& what);
  // Each constraint of `set` replaces the model's constraint of the same name, in its place, or is appended.
  void setNamedConstraints(Role role, const ConstraintSet& set, const QString& what);
  // setNamedConstraints with the feature constraints placed at `landmarks`, which become the model's landmarks.
  void setFeatureConstraints(Role role, const ConstraintSet& features, const FaceLandmarks& landmarks,
                             const QString& what);
  const std::optional<FaceLandmarks>& landmarks(Role role) const { return constraints(role).landmarks; }
  void addSideConstraints(Role role);  // the six shape ends by "side_mask" (setNamedConstraints)
  QUndoStack* undoStack() const { return undo_; }
  // Installs a constraint list without recording it (the undo command's own entry point). A change of the set makes
  // the model's fields and the transfer stale: they are set aside, and come back when an undo or a redo brings back
  // the constraints they were computed with.
  void applyConstraints(Role role, const ConstraintList& list);

  // The cutting plane acts on the active model.
  const PlanePose& plane() const { return plane_; }
  void setPlane(const PlanePose& pose);
  void centrePlane() { centrePlaneOn(activeRole_); }  // through the centre of the active model's bounding box
  const std::vector<int>& planeSelection() const { return planeSelection_; }  // vertices of the active model
  Selection planeAsSelection() const;

  const DisplaySettings& display() const { return display_; }
  void setDisplay(const DisplaySettings& display);

  // Results (set by the controller on the GUI thread). The transfer's parameterizations live in parameterization():
  // its run holds none.
  const ModelParameterization* parameterization(Role role) const;
  void setParameterization(Role role, ModelParameterization p);
  const TransferResult* transfer() const { return results_.transfer ? &*results_.transfer : nullptr; }
  void setTransfer(TransferResult result);
  // Whether the present transfer's hex mesh was written to a file (quitting without it asks first).
  bool transferExported() const { return results_.transferExported; }
  void markTransferExported() { results_.transferExported = true; }

  // The vertex or constraint a message named, shown by the views and the constraint list until another is asked
  // for or the model changes.
  const std::optional<Highlight>& highlight() const { return highlight_; }
  void setHighlight(const std::optional<Highlight>& highlight);

 signals:
  void modelChanged(facehex::gui::Role role);        // a model was loaded: everything about it changed
  void constraintsChanged(facehex::gui::Role role);  // its constraint list (or their visibility) changed
  void constraintsEdited(facehex::gui::Role role);   // ... by an edit or its undo (not by loading a model)
  void activeRoleChanged(facehex::gui::Role role);
  void planeChanged();
  void planeSelectionChanged();
  void displayChanged();
  void resultsChanged();  // a parameterization or the transfer was set, cleared, set aside or restored
  void highlightChanged();

 private:
  static int index(Role role) { return static_cast<int>(role); }
  LoadedModel& mutableModel(Role role);
  void edit(Role role, ConstraintList after, const QString& what);
  ConstraintList withNamed(Role role, const ConstraintSet& set) const;
  void updateConstraintVertices(Role role);
  void updatePlaneSelection();
  void centrePlaneOn(Role role);

  // The results of one state of the constraints.
  struct Results {
    std::array<std::optional<ModelParameterization>, 2> parameterizations;
    std::optional<TransferResult> transfer;
    bool transferExported = false;
    bool empty() const { return !parameterizations[0] && !parameterizations[1] && !transfer; }
  };
  // Both models' constraint sets as JSON: the state results belong to.
  using ConstraintState = std::array<std::string, 2>;
  ConstraintState constraintState() const;
  // After `role`'s constraints changed from `before`: its stale results are set aside under `before`, and those set
  // aside under the present constraints come back.
  void exchangeResults(Role role, const ConstraintState& before);

  std::array<std::optional<LoadedModel>, 2> models_;
  std::array<quint64, 2> revisions_{};
  std::array<std::vector<std::vector<int>>, 2> constraintVertices_;
  std::array<std::vector<QString>, 2> constraintProblems_;
  Results results_;
  // Most recent first. Bounded: each holds whole parameterizations, and an undo rarely goes further back.
  std::deque<std::pair<ConstraintState, Results>> setAside_;
  std::optional<Highlight> highlight_;
  Role activeRole_ = Role::Patient;
  PlanePose plane_;
  std::vector<int> planeSelection_;
  DisplaySettings display_;
  QUndoStack* undo_;
};

}  // namespace facehex::gui

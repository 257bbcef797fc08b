#include "ui/model_view.h"

#include <QVTKOpenGLNativeWidget.h>
#include <vtkActor.h>
#include <vtkActor2D.h>
#include <vtkArrowSource.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkColorTransferFunction.h>
#include <vtkContourFilter.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkDoubleArray.h>
#include <vtkExtractGeometry.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGlyph3D.h>
#include <vtkHandleWidget.h>
#include <vtkIdTypeArray.h>
#include <vtkImplicitPlaneRepresentation.h>
#include <vtkImplicitPlaneWidget2.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkPlane.h>
#include <vtkPointData.h>
#include <vtkPointHandleRepresentation3D.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkPolyDataNormals.h>
#include <vtkPolygonalSurfacePointPlacer.h>
#include <vtkProperty.h>
#include <vtkProperty2D.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkThreshold.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <QLabel>
#include <QStackedWidget>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "core/face/landmark_file.h"
#include "core/quality/vtk_grid.h"
#include "ui/label_layout.h"
#include "ui/palette.h"

namespace facehex::gui {
namespace {

template <class T>
using Ptr = vtkSmartPointer<T>;
template <class T>
Ptr<T> make() {
  return Ptr<T>::New();
}

const char* const kConstraintColours = "constraint_colour";
const char* const kVertexIds = "vertex";
constexpr double kGlyphGridCells = 22;  // glyph grid spacing: the model's diagonal over this

void setColour(vtkProperty* p, const QColor& c) { p->SetColor(c.redF(), c.greenF(), c.blueF()); }

// A constraint's colour mixed into the tissue colour: large painted sides (the whole skin) stay easy on the eye.
QColor tint(const QColor& c) {
  constexpr double kShare = 0.5;
  const QColor t = tissueColour();
  auto mix = [](int a, int b) { return static_cast<int>(kShare * a + (1 - kShare) * b); };
  return QColor(mix(c.red(), t.red()), mix(c.green(), t.green()), mix(c.blue(), t.blue()));
}

std::array<unsigned char, 3> rgb(const QColor& c) {
  return {static_cast<unsigned char>(c.red()), static_cast<unsigned char>(c.green()),
          static_cast<unsigned char>(c.blue())};
}

// Diverging blue-white-red for the fields on [0, 1]: the middle value (0.5, where a feature constraint typically
// sits) is neutral and both ends are equally salient.
Ptr<vtkColorTransferFunction> fieldColours() {
  auto f = make<vtkColorTransferFunction>();
  f->SetColorSpaceToDiverging();
  f->AddRGBPoint(0.0, 0.230, 0.299, 0.754);
  f->AddRGBPoint(0.5, 0.865, 0.865, 0.865);
  f->AddRGBPoint(1.0, 0.706, 0.016, 0.150);
  return f;
}

// Red (bad) - yellow - green (good) for element quality on [0, 1]; negative scaled Jacobians clamp to red.
Ptr<vtkColorTransferFunction> qualityColours() {
  auto f = make<vtkColorTransferFunction>();
  f->AddRGBPoint(0.0, 0.80, 0.08, 0.08);
  f->AddRGBPoint(0.5, 0.98, 0.82, 0.20);
  f->AddRGBPoint(1.0, 0.10, 0.60, 0.25);
  return f;
}

const char* measureArray(QualityMeasure m) { return m == QualityMeasure::Shape ? "shape" : "scaled_jacobian"; }
QString measureTitle(QualityMeasure m) { return m == QualityMeasure::Shape ? "shape" : "scaled Jacobian"; }

Ptr<vtkDoubleArray> doubleArray(const char* name, const Eigen::VectorXd& values) {
  auto a = make<vtkDoubleArray>();
  a->SetName(name);
  a->SetNumberOfValues(values.size());
  for (Eigen::Index i = 0; i < values.size(); ++i) a->SetValue(i, values[i]);
  return a;
}

// A point cloud with one RGB colour per point, drawn as vertices.
struct PointCloud {
  Ptr<vtkPoints> points = make<vtkPoints>();
  Ptr<vtkCellArray> vertices = make<vtkCellArray>();
  Ptr<vtkUnsignedCharArray> colours = make<vtkUnsignedCharArray>();
  PointCloud() { colours->SetNumberOfComponents(3); }
  void add(const Eigen::Vector3d& x, const QColor& c) {
    const vtkIdType id = points->InsertNextPoint(x.data());
    vertices->InsertNextCell(1, &id);
    colours->InsertNextTypedTuple(rgb(c).data());
  }
  void install(vtkPolyData* pd) const {
    pd->Initialize();
    pd->SetPoints(points);
    pd->SetVerts(vertices);
    pd->GetPointData()->SetScalars(colours);
    pd->Modified();
  }
};

Ptr<vtkActor> pointActor(vtkPolyData* data, double size) {
  auto mapper = make<vtkPolyDataMapper>();
  mapper->SetInputData(data);
  mapper->SetColorModeToDirectScalars();
  auto actor = make<vtkActor>();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetPointSize(size);
  actor->GetProperty()->SetRenderPointsAsSpheres(true);
  return actor;
}

// px: how far a landmark's handle reaches from its centre (its 24 px cursor), kept clear of the names.
constexpr double kLandmarkHandleRadius = 12;

Ptr<vtkTextActor> landmarkLabel(const std::string& name) {
  auto label = make<vtkTextActor>();
  label->SetInput(name.c_str());
  vtkTextProperty* text = label->GetTextProperty();
  text->SetFontSize(14);
  text->SetBold(true);
  text->ItalicOff();
  text->SetShadow(true);
  text->SetColor(1, 1, 1);
  text->SetJustificationToLeft();
  text->SetVerticalJustificationToBottom();
  return label;
}

}  // namespace

struct ModelView::Pipeline {
  QVTKOpenGLNativeWidget* widget = nullptr;
  Ptr<vtkGenericOpenGLRenderWindow> window = make<vtkGenericOpenGLRenderWindow>();
  Ptr<vtkRenderer> renderer = make<vtkRenderer>();
  Ptr<vtkRenderer> overlay = make<vtkRenderer>();  // layer 1: the selection preview, never hidden by the surface

  // The model's surface, optionally cut open at the plane, extracted only when the geometry or the cut changes; its
  // colours (a field, or the constraints' paint) are arrays set per model vertex through the "vertex" id array.
  Ptr<vtkUnstructuredGrid> grid;  // the model, with only the "vertex" id array as point data
  Ptr<vtkPlane> plane = make<vtkPlane>();
  Ptr<vtkExtractGeometry> cut = make<vtkExtractGeometry>();
  Ptr<vtkDataSetSurfaceFilter> surface = make<vtkDataSetSurfaceFilter>();
  Ptr<vtkPolyDataNormals> normals = make<vtkPolyDataNormals>();
  Ptr<vtkPolyData> surfacePoly = make<vtkPolyData>();
  std::optional<PlanePose> extractedCut;  // the plane the surface was cut at, if it was
  bool extracted = false;
  std::vector<std::array<unsigned char, 3>> paint;  // per model vertex
  Ptr<vtkPolyDataMapper> surfaceMapper = make<vtkPolyDataMapper>();
  Ptr<vtkActor> surfaceActor = make<vtkActor>();
  Ptr<vtkContourFilter> iso = make<vtkContourFilter>();
  Ptr<vtkActor> isoActor = make<vtkActor>();
  Ptr<vtkColorTransferFunction> fieldLut = fieldColours();

  // The hex mesh by quality: the cells under the threshold, and the whole mesh as a faint context.
  Ptr<vtkUnstructuredGrid> hexGrid;
  Ptr<vtkThreshold> threshold = make<vtkThreshold>();
  Ptr<vtkDataSetSurfaceFilter> hexSurface = make<vtkDataSetSurfaceFilter>();
  Ptr<vtkPolyDataMapper> hexMapper = make<vtkPolyDataMapper>();
  Ptr<vtkActor> hexActor = make<vtkActor>();
  Ptr<vtkDataSetSurfaceFilter> contextSurface = make<vtkDataSetSurfaceFilter>();
  Ptr<vtkActor> contextActor = make<vtkActor>();
  Ptr<vtkColorTransferFunction> qualityLut = qualityColours();

  Ptr<vtkScalarBarActor> scalarBar = make<vtkScalarBarActor>();
  Ptr<vtkPolyData> constraintPoints = make<vtkPolyData>();
  Ptr<vtkActor> constraintActor = pointActor(constraintPoints, 5);
  Ptr<vtkPolyData> selectionPoints = make<vtkPolyData>();
  Ptr<vtkActor> selectionActor = pointActor(selectionPoints, 9);
  Ptr<vtkPolyData> highlightPoints = make<vtkPolyData>();  // what a message named (a vertex, a constraint's)
  Ptr<vtkActor> highlightActor = pointActor(highlightPoints, 9);

  Ptr<vtkPolyData> glyphSeeds = make<vtkPolyData>();
  Ptr<vtkGlyph3D> glyphs = make<vtkGlyph3D>();
  Ptr<vtkActor> glyphActor = make<vtkActor>();

  // The landmarks: a marker and a name each, and a handle each that slides on the model's surface (the placer picks
  // the surface actor). Handles are kept by name, so a release that re-places the features keeps its own handle.
  // The names are laid out on the screen before each frame (label_layout.h), with a leader line to the marker from a
  // name that had to move away from it.
  Ptr<vtkPolyData> landmarkPoints = make<vtkPolyData>();
  Ptr<vtkActor> landmarkActor = pointActor(landmarkPoints, 12);
  std::vector<Ptr<vtkTextActor>> labels;
  Ptr<vtkPolyData> leaderLines = make<vtkPolyData>();
  Ptr<vtkActor2D> leaderActor = make<vtkActor2D>();
  std::vector<QRectF> labelBoxes;  // display pixels, as last laid out
  Ptr<vtkPolygonalSurfacePointPlacer> placer = make<vtkPolygonalSurfacePointPlacer>();
  std::map<std::string, Ptr<vtkHandleWidget>> handles;

  Ptr<vtkImplicitPlaneRepresentation> planeRep = make<vtkImplicitPlaneRepresentation>();
  Ptr<vtkImplicitPlaneWidget2> planeWidget = make<vtkImplicitPlaneWidget2>();

  bool hexShown = false;

  void setUpSurface();     // the model's surface, cut at the plane, coloured by a field, with iso-lines
  void setUpHexDisplay();  // the hex cells under the quality threshold, the rest as a faint context
  void setUpScalarBar();
  void setUpGlyphs();  // gradient arrows
  void setUpLandmarks();
};

void ModelView::Pipeline::setUpSurface() {
  // Whole cells behind the plane: no new points on the cut, so every surface point is a model vertex.
  cut->SetImplicitFunction(plane);
  cut->ExtractInsideOn();
  cut->ExtractBoundaryCellsOn();
  normals->SetInputConnection(surface->GetOutputPort());
  normals->SplittingOff();  // smooth shading across the tets' facets
  surfaceMapper->SetInputData(surfacePoly);
  surfaceMapper->SetLookupTable(fieldLut);
  surfaceMapper->SetScalarModeToUsePointFieldData();
  surfaceActor->SetMapper(surfaceMapper);
  surfaceActor->GetProperty()->SetEdgeColor(0.55, 0.42, 0.35);
  iso->SetInputData(surfacePoly);
  iso->GenerateValues(9, 0.1, 0.9);
  auto isoMapper = make<vtkPolyDataMapper>();
  isoMapper->SetInputConnection(iso->GetOutputPort());
  isoMapper->ScalarVisibilityOff();
  isoActor->SetMapper(isoMapper);
  isoActor->GetProperty()->SetColor(0.08, 0.08, 0.08);
  isoActor->GetProperty()->SetLineWidth(3);
  isoActor->GetProperty()->SetRenderLinesAsTubes(true);
}

void ModelView::Pipeline::setUpHexDisplay() {
  threshold->SetThresholdFunction(vtkThreshold::THRESHOLD_BETWEEN);
  threshold->SetLowerThreshold(-2.0);  // quality is at least -1: only the upper end moves
  hexSurface->SetInputConnection(threshold->GetOutputPort());
  hexMapper->SetInputConnection(hexSurface->GetOutputPort());
  hexMapper->SetLookupTable(qualityLut);
  hexMapper->SetScalarModeToUseCellData();
  hexMapper->UseLookupTableScalarRangeOn();
  hexActor->SetMapper(hexMapper);
  hexActor->GetProperty()->EdgeVisibilityOn();
  hexActor->GetProperty()->SetEdgeColor(0.15, 0.15, 0.15);
  auto contextMapper = make<vtkPolyDataMapper>();
  contextMapper->SetInputConnection(contextSurface->GetOutputPort());
  contextMapper->ScalarVisibilityOff();
  contextActor->SetMapper(contextMapper);
  contextActor->GetProperty()->SetColor(0.85, 0.85, 0.85);
  contextActor->GetProperty()->SetOpacity(0.15);
}

void ModelView::Pipeline::setUpScalarBar() {
  // Horizontal, under the model: long titles ("scaled Jacobian") fit, and the model keeps the view's width.
  scalarBar->SetOrientationToHorizontal();
  scalarBar->SetTextPositionToPrecedeScalarBar();  // labels under the bar, the title over it
  scalarBar->SetNumberOfLabels(6);
  scalarBar->SetLabelFormat("%.1f");
  scalarBar->SetPosition(0.25, 0.02);
  scalarBar->SetWidth(0.5);
  scalarBar->SetHeight(0.1);
  scalarBar->UnconstrainedFontSizeOn();
  scalarBar->GetTitleTextProperty()->SetFontSize(16);
  scalarBar->GetLabelTextProperty()->SetFontSize(13);
  scalarBar->GetTitleTextProperty()->ShadowOff();
  scalarBar->GetLabelTextProperty()->ShadowOff();
  scalarBar->GetLabelTextProperty()->ItalicOff();
  scalarBar->GetTitleTextProperty()->ItalicOff();
}

void ModelView::Pipeline::setUpGlyphs() {
  auto arrow = make<vtkArrowSource>();
  arrow->SetTipResolution(8);
  arrow->SetShaftResolution(8);
  glyphs->SetSourceConnection(arrow->GetOutputPort());
  glyphs->SetInputData(glyphSeeds);
  glyphs->SetVectorModeToUseVector();
  glyphs->SetScaleModeToScaleByVector();
  glyphs->SetColorModeToColorByScalar();
  glyphs->OrientOn();
  auto glyphMapper = make<vtkPolyDataMapper>();
  glyphMapper->SetInputConnection(glyphs->GetOutputPort());
  glyphMapper->SetColorModeToDirectScalars();
  glyphActor->SetMapper(glyphMapper);
}

void ModelView::Pipeline::setUpLandmarks() {
  auto mapper = make<vtkPolyDataMapper2D>();
  mapper->SetInputData(leaderLines);
  leaderActor->SetMapper(mapper);
  leaderActor->GetProperty()->SetColor(1, 1, 1);
  leaderActor->GetProperty()->SetLineWidth(1.5);
  placer->AddProp(surfaceActor);
}

ModelView::ModelView(SessionModel* session, Role role, QWidget* parent)
    : QWidget(parent), session_(session), role_(role), p_(std::make_unique<Pipeline>()) {
  setObjectName(roleName(role) + "View");
  header_ = new QLabel(this);
  header_->setObjectName(roleName(role) + "Header");
  header_->setTextFormat(Qt::RichText);
  header_->setContentsMargins(6, 3, 6, 3);
  // What the header says must not resize the view: a longer note would widen the centre and push the panels (and
  // the control under the user's pointer) sideways. It is cut at the view's edge; the tooltip has all of it.
  header_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
  auto* hint = new QLabel(role == Role::Patient
                              ? tr("<p>No patient model yet.</p><p>Open a head CT, a tet model or a closed surface "
                                   "with <b>File \u25b8 Open patient</b> (a folder of DICOM slices: <b>File \u25b8 "
                                   "Open DICOM folder</b>), drop a file here, or try <b>File \u25b8 Open "
                                   "demo</b>.</p>")
                              : tr("<p>No standard yet: pick one in the toolbar.</p>"),
                          this);
  hint->setAlignment(Qt::AlignCenter);
  hint->setWordWrap(true);
  p_->widget = new QVTKOpenGLNativeWidget(this);
  stack_ = new QStackedWidget(this);
  stack_->addWidget(hint);
  stack_->addWidget(p_->widget);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(0);
  layout->addWidget(header_);
  layout->addWidget(stack_, 1);

  Pipeline& p = *p_;
  p.widget->setRenderWindow(p.window);
  p.window->SetNumberOfLayers(2);
  p.window->AddRenderer(p.renderer);
  p.window->AddRenderer(p.overlay);
  p.overlay->SetLayer(1);
  p.overlay->SetActiveCamera(p.renderer->GetActiveCamera());
  p.overlay->InteractiveOff();
  p.renderer->GradientBackgroundOn();
  p.renderer->SetBackground(0.20, 0.22, 0.27);
  p.renderer->SetBackground2(0.42, 0.45, 0.52);
  auto style = make<vtkInteractorStyleTrackballCamera>();
  p.widget->interactor()->SetInteractorStyle(style);
  style->AddObserver(vtkCommand::InteractionEvent, this, &ModelView::onCameraInteraction);
  p.renderer->AddObserver(vtkCommand::StartEvent, this, &ModelView::onRenderStart);

  p.setUpSurface();
  p.setUpHexDisplay();
  p.setUpScalarBar();
  p.setUpGlyphs();
  p.setUpLandmarks();
  for (vtkProp* prop :
       {static_cast<vtkProp*>(p.surfaceActor), static_cast<vtkProp*>(p.isoActor), static_cast<vtkProp*>(p.hexActor),
        static_cast<vtkProp*>(p.contextActor), static_cast<vtkProp*>(p.constraintActor),
        static_cast<vtkProp*>(p.glyphActor), static_cast<vtkProp*>(p.scalarBar)})
    p.renderer->AddViewProp(prop);
  p.overlay->AddActor(p.selectionActor);
  p.overlay->AddActor(p.highlightActor);
  p.overlay->AddActor(p.landmarkActor);
  p.overlay->AddActor(p.leaderActor);

  p.planeRep->SetPlaceFactor(1.05);
  p.planeRep->OutlineTranslationOff();
  p.planeRep->ScaleEnabledOff();
  p.planeRep->OutsideBoundsOff();
  p.planeRep->GetPlaneProperty()->SetOpacity(0.25);
  p.planeRep->GetSelectedPlaneProperty()->SetOpacity(0.35);
  p.planeWidget->SetRepresentation(p.planeRep);
  p.planeWidget->SetInteractor(p.widget->interactor());
  p.planeWidget->SetCurrentRenderer(p.renderer);
  p.planeWidget->AddObserver(vtkCommand::InteractionEvent, this, &ModelView::onPlaneInteraction);

  connectSession();
  refresh();
}

void ModelView::connectSession() {
  connect(session_, &SessionModel::modelChanged, this, [this](Role r) {
    if (r == role_) onModelChanged();
  });
  connect(session_, &SessionModel::resultsChanged, this, &ModelView::onResultsChanged);
  connect(session_, &SessionModel::constraintsChanged, this, [this](Role r) {
    if (r != role_) return;
    updateConstraints();
    updateLandmarks();
    render();
  });
  connect(session_, &SessionModel::activeRoleChanged, this, &ModelView::refresh);
  connect(session_, &SessionModel::highlightChanged, this, [this] {
    if (!session_->hasModel(role_)) return;
    updateHighlight();
    render();
  });
  connect(session_, &SessionModel::displayChanged, this, &ModelView::refresh);
  // Dragging the plane must stay fluid: only what depends on the plane is updated.
  connect(session_, &SessionModel::planeSelectionChanged, this, [this] {
    if (!session_->hasModel(role_)) return;
    updateSurface();
    updateSelection();
    updatePlaneWidget();
    render();
  });
}

ModelView::~ModelView() {
  // The observers point at this widget: stop them before it goes.
  p_->planeWidget->Off();
  p_->planeWidget->RemoveAllObservers();
  for (auto& [name, handle] : p_->handles) {
    handle->Off();
    handle->RemoveAllObservers();
  }
  if (auto* style = p_->widget->interactor()->GetInteractorStyle()) style->RemoveAllObservers();
  p_->renderer->RemoveAllObservers();
}

void ModelView::onModelChanged() {
  Pipeline& p = *p_;
  const LoadedModel& m = session_->model(role_);
  p.grid = to_vtk_grid(m.mesh);
  auto ids = make<vtkIdTypeArray>();
  ids->SetName(kVertexIds);
  ids->SetNumberOfValues(m.mesh.num_vertices());
  for (vtkIdType v = 0; v < m.mesh.num_vertices(); ++v) ids->SetValue(v, v);
  p.grid->GetPointData()->AddArray(ids);
  p.extracted = false;
  if (m.quality.shape.size() == m.mesh.num_cells()) {  // a hex-dominant model: it is its own "hex mesh"
    p.grid->GetCellData()->AddArray(doubleArray("shape", m.quality.shape));
    p.grid->GetCellData()->AddArray(doubleArray("scaled_jacobian", m.quality.scaled_jacobian));
  }
  double bounds[6];
  p.grid->GetBounds(bounds);
  p.planeRep->PlaceWidget(bounds);
  stack_->setCurrentIndex(1);
  onResultsChanged();
  resetCamera();
}

void ModelView::onResultsChanged() {
  Pipeline& p = *p_;
  if (!session_->hasModel(role_)) return;
  const LoadedModel& m = session_->model(role_);
  p.hexGrid = nullptr;
  if (role_ == Role::Standard && m.quality.shape.size() > 0) {
    p.hexGrid = p.grid;
  } else if (role_ == Role::Patient && session_->transfer()) {
    const VolumeMesh& hex = session_->transfer()->patient_hex;
    p.hexGrid = to_vtk_grid(hex);
    for (const char* name : {"shape", "scaled_jacobian"})
      p.hexGrid->GetCellData()->AddArray(doubleArray(name, hex.cell_data.at(name).col(0)));
  }
  refresh();
}

void ModelView::refresh() {
  updateHeader();
  if (!session_->hasModel(role_)) return;
  p_->hexShown = session_->display().showHex && p_->hexGrid;
  updateConstraints();
  updateSurface();
  updateHex();
  updateSelection();
  updateHighlight();
  updateGlyphs();
  updatePlaneWidget();
  updateLandmarks();
  render();
}

void ModelView::updateHeader() {
  const bool active = session_->activeRole() == role_;
  QString text = QString("<b>%1</b>").arg(role_ == Role::Standard ? tr("Standard") : tr("Patient"));
  if (session_->hasModel(role_)) {
    const LoadedModel& m = session_->model(role_);
    const VolumeMesh& mesh = m.mesh;
    QString cells = mesh.is_tet_mesh()
                        ? tr("%L1 tets").arg(mesh.num_cells())
                        : tr("%L1 hexes, %L2 wedges").arg(mesh.count(CellType::Hex)).arg(mesh.count(CellType::Wedge));
    text += QString(" &nbsp;%1 &nbsp;<span style='color:#666'>%2 vertices, %3</span>")
                .arg(m.name.toHtmlEscaped(), QString("%L1").arg(mesh.num_vertices()), cells);
    const DisplaySettings& d = session_->display();
    if (d.showHex && !p_->hexGrid && role_ == Role::Patient)
      text += tr(" &nbsp;<i>(no hex mesh yet: run the transfer)</i>");
    else if (!d.showHex && d.field >= 0 && !session_->parameterization(role_))
      text += tr(" &nbsp;<i>(fields not computed)</i>");
  }
  if (active) text += tr(" &nbsp;<span style='color:#b07800'>\u25cf active</span>");
  header_->setText(text);
  header_->setToolTip(text);
  header_->setStyleSheet(active ? "background:#fff3c4;" : "background:#ececec;");
}

void ModelView::updateSurface() {
  Pipeline& p = *p_;
  const DisplaySettings& d = session_->display();
  const PlanePose& plane = session_->plane();
  const bool cutMoved =
      p.extractedCut && (p.extractedCut->origin != plane.origin || p.extractedCut->normal != plane.normal);
  if (!p.extracted || cutHere() != p.extractedCut.has_value() || (cutHere() && cutMoved)) {
    extractSurface();
    colourSurface();
  }
  const bool hasFields = session_->parameterization(role_) != nullptr;
  const bool coloured = d.field >= 0 && hasFields;
  const bool painted = !coloured && d.showConstraints;
  if (coloured) {
    p.surfaceMapper->SelectColorArray(kFieldNames[d.field]);
    p.surfaceMapper->SetColorModeToMapScalars();
    p.iso->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, kFieldNames[d.field]);
  } else if (painted) {
    p.surfaceMapper->SelectColorArray(kConstraintColours);
    p.surfaceMapper->SetColorModeToDirectScalars();
  }
  p.surfaceMapper->SetScalarVisibility(coloured || painted);
  // A hex mesh's element layout is worth seeing on the plain surface; under a colour map it is clutter.
  const bool hexModel = !session_->model(role_).mesh.is_tet_mesh();
  p.surfaceActor->GetProperty()->SetEdgeVisibility(hexModel && !coloured && d.glyphs == GlyphMode::Off);
  p.surfaceMapper->SetScalarRange(0, 1);
  setColour(p.surfaceActor->GetProperty(), tissueColour());
  p.surfaceActor->GetProperty()->SetOpacity(d.glyphs != GlyphMode::Off && hasFields ? 0.25 : 1.0);
  p.surfaceActor->SetVisibility(!p.hexShown);
  p.isoActor->SetVisibility(!p.hexShown && coloured && d.isoLines);
  p.scalarBar->SetVisibility(p.hexShown || coloured);
  if (coloured && !p.hexShown) {
    p.scalarBar->SetLookupTable(p.fieldLut);
    p.scalarBar->SetTitle(kFieldNames[d.field]);
  }
}

void ModelView::updateHex() {
  Pipeline& p = *p_;
  p.hexActor->SetVisibility(p.hexShown);
  p.contextActor->SetVisibility(p.hexShown);
  if (!p.hexShown) return;
  const DisplaySettings& d = session_->display();
  const char* measure = measureArray(d.measure);
  p.hexGrid->GetCellData()->SetActiveScalars(measure);
  p.threshold->SetInputData(p.hexGrid);
  p.threshold->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, measure);
  p.threshold->SetUpperThreshold(d.threshold);
  p.contextSurface->SetInputData(p.hexGrid);
  p.scalarBar->SetLookupTable(p.qualityLut);
  p.scalarBar->SetTitle(measureTitle(d.measure).toUtf8().constData());
}

int ModelView::drawnHexCells() const {
  if (!p_->hexShown) return -1;
  p_->threshold->Update();
  return static_cast<int>(p_->threshold->GetOutput()->GetNumberOfCells());
}

void ModelView::updateConstraints() {
  // Constraint vertices on the surface paint it in their constraint's colour (a side becomes a coloured patch);
  // those inside the model (a mid-sagittal plane through the volume, the plugs of a closed standard) are points.
  Pipeline& p = *p_;
  const DisplaySettings& d = session_->display();
  const LoadedModel& m = session_->model(role_);
  const int surfaceVertices = m.mesh.num_vertices();
  p.paint.assign(surfaceVertices, rgb(tissueColour()));
  PointCloud inside;
  if (d.showConstraints && !p.hexShown) {
    const ConstraintList& list = m.constraints;
    for (size_t i = 0; i < list.set.constraints.size(); ++i) {
      if (!list.visible[i]) continue;
      const QColor colour = constraintColour(list.set.constraints[i]);
      const std::array<unsigned char, 3> painted = rgb(tint(colour));
      for (int v : session_->constraintVertices(role_, static_cast<int>(i))) {
        if (v < surfaceVertices && m.boundary[v])
          p.paint[v] = painted;
        else
          inside.add(m.domain.V.row(v).transpose(), colour);
      }
    }
  }
  inside.install(p.constraintPoints);
  colourSurface();
}

// The plane lives in the active model's frame: only its view is cut open.
bool ModelView::cutHere() const { return session_->display().clipAtPlane && session_->activeRole() == role_; }

void ModelView::extractSurface() {
  Pipeline& p = *p_;
  const bool cut = cutHere();
  if (cut) {
    const PlanePose& plane = session_->plane();
    p.plane->SetOrigin(plane.origin.data());
    p.plane->SetNormal(plane.normal.data());
    p.cut->SetInputData(p.grid);
    p.surface->SetInputConnection(p.cut->GetOutputPort());
    p.extractedCut = plane;
  } else {
    p.surface->SetInputData(p.grid);
    p.extractedCut.reset();
  }
  p.normals->Update();
  p.surfacePoly->ShallowCopy(p.normals->GetOutput());
  p.extracted = true;
}

void ModelView::colourSurface() {
  Pipeline& p = *p_;
  if (!p.extracted) return;
  auto* ids = vtkIdTypeArray::SafeDownCast(p.surfacePoly->GetPointData()->GetArray(kVertexIds));
  const vtkIdType n = ids->GetNumberOfValues();
  vtkPointData* data = p.surfacePoly->GetPointData();
  auto paint = make<vtkUnsignedCharArray>();
  paint->SetName(kConstraintColours);
  paint->SetNumberOfComponents(3);
  paint->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i) paint->SetTypedTuple(i, p.paint[ids->GetValue(i)].data());
  data->AddArray(paint);
  const ModelParameterization* param = session_->parameterization(role_);
  for (int f = 0; f < 3; ++f) {
    if (!param) {
      data->RemoveArray(kFieldNames[f]);
      continue;
    }
    auto values = make<vtkDoubleArray>();
    values->SetName(kFieldNames[f]);
    values->SetNumberOfValues(n);
    for (vtkIdType i = 0; i < n; ++i) values->SetValue(i, param->fields.uvw(ids->GetValue(i), f));
    data->AddArray(values);
  }
  p.surfacePoly->Modified();
}

void ModelView::updateSelection() {
  Pipeline& p = *p_;
  const LoadedModel& m = session_->model(role_);
  PointCloud selection;
  if (session_->activeRole() == role_ && session_->display().showPlane && !p.hexShown)
    for (int v : session_->planeSelection()) selection.add(m.domain.V.row(v).transpose(), selectionColour());
  selection.install(p.selectionPoints);
}

void ModelView::updateHighlight() {
  Pipeline& p = *p_;
  PointCloud marked;
  const std::optional<Highlight>& h = session_->highlight();
  if (h && h->role == role_) {
    const LoadedModel& m = session_->model(role_);
    if (h->vertex >= 0)
      marked.add(m.domain.V.row(h->vertex).transpose(), highlightColour());
    else
      for (int v : session_->constraintVertices(role_, h->constraint))
        marked.add(m.domain.V.row(v).transpose(), highlightColour());
    p.highlightActor->GetProperty()->SetPointSize(h->vertex >= 0 ? 18 : 9);  // one vertex must stand out alone
  }
  marked.install(p.highlightPoints);
}

int ModelView::highlightedPoints() const { return static_cast<int>(p_->highlightPoints->GetNumberOfPoints()); }

void ModelView::updateGlyphs() {
  Pipeline& p = *p_;
  const DisplaySettings& d = session_->display();
  const ModelParameterization* param = session_->parameterization(role_);
  const bool show = d.glyphs != GlyphMode::Off && param && !p.hexShown;
  p.glyphActor->SetVisibility(show);
  if (!show) return;
  const GradientFields& g = d.glyphs == GlyphMode::Before ? param->fields.gradients_initial : param->fields.gradients;
  const Eigen::MatrixXi& T = param->T;
  const Eigen::MatrixXd& V = param->V;
  // One tet per cell of a coarse grid, so the arrows spread evenly whatever the mesh density, and are as long as
  // the grid spacing for the median gradient of their field (the steep w across the thin tissue and the gentle u, v
  // are equally readable); smaller gradients give shorter arrows, larger ones are capped.
  const Eigen::RowVector3d lo = V.colwise().minCoeff();
  const double spacing = (V.colwise().maxCoeff() - lo).norm() / kGlyphGridCells;
  std::set<std::array<long, 3>> taken;
  std::vector<int> seedTets;
  Eigen::MatrixXd centroids(T.rows(), 3);
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    centroids.row(t) = 0.25 * (V.row(T(t, 0)) + V.row(T(t, 1)) + V.row(T(t, 2)) + V.row(T(t, 3)));
    const Eigen::RowVector3d cell = ((centroids.row(t) - lo) / spacing).array().floor();
    if (taken.insert({long(cell[0]), long(cell[1]), long(cell[2])}).second) seedTets.push_back(int(t));
  }
  PointCloud seeds;
  auto vectors = make<vtkDoubleArray>();
  vectors->SetName("gradient");
  vectors->SetNumberOfComponents(3);
  for (int f = 0; f < 3; ++f) {
    Eigen::VectorXd norms = g[f].rowwise().norm();
    std::nth_element(norms.data(), norms.data() + norms.size() / 2, norms.data() + norms.size());
    const double typical = norms[norms.size() / 2] > 0 ? norms[norms.size() / 2] : 1.0;
    for (int t : seedTets) {
      Eigen::Vector3d v = g[f].row(t).transpose() / typical;
      if (v.norm() > 1) v.normalize();
      seeds.add(centroids.row(t).transpose(), fieldColour(f));
      vectors->InsertNextTuple(v.data());
    }
  }
  seeds.install(p.glyphSeeds);
  p.glyphSeeds->GetPointData()->SetVectors(vectors);
  p.glyphs->SetScaleFactor(0.9 * spacing);
}

void ModelView::updatePlaneWidget() {
  Pipeline& p = *p_;
  const DisplaySettings& d = session_->display();
  const bool enabled = session_->activeRole() == role_ && d.showPlane && !p.hexShown;
  const PlanePose& plane = session_->plane();
  const Eigen::Vector3d origin(p.planeRep->GetOrigin()), normal(p.planeRep->GetNormal());
  if ((origin - plane.origin).norm() > 1e-9) p.planeRep->SetOrigin(plane.origin[0], plane.origin[1], plane.origin[2]);
  if ((normal - plane.normal).norm() > 1e-9) p.planeRep->SetNormal(plane.normal[0], plane.normal[1], plane.normal[2]);
  if (enabled != static_cast<bool>(p.planeWidget->GetEnabled())) p.planeWidget->SetEnabled(enabled);
}

bool ModelView::planeWidgetEnabled() const { return p_->planeWidget->GetEnabled() != 0; }

void ModelView::movePlaneWidget(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal) {
  p_->planeRep->SetOrigin(origin[0], origin[1], origin[2]);
  p_->planeRep->SetNormal(normal[0], normal[1], normal[2]);
  onPlaneInteraction();
}

void ModelView::onPlaneInteraction() {
  PlanePose pose = session_->plane();
  pose.origin = Eigen::Vector3d(p_->planeRep->GetOrigin());
  pose.normal = Eigen::Vector3d(p_->planeRep->GetNormal());
  session_->setPlane(pose);
}

void ModelView::updateLandmarks() {
  Pipeline& p = *p_;
  const std::optional<FaceLandmarks>& landmarks = session_->landmarks(role_);
  const bool shown = landmarks && session_->display().showLandmarks && !p.hexShown;
  PointCloud markers;
  for (const Ptr<vtkTextActor>& label : p.labels) p.overlay->RemoveActor2D(label);
  p.labels.clear();
  std::map<std::string, Ptr<vtkHandleWidget>> handles;
  if (shown) {
    for (const auto& [name, x] : landmarks->points) {
      markers.add(x, landmarkColour());
      p.labels.push_back(landmarkLabel(patient_side_name(name, landmarks->scan_frame)));
      p.overlay->AddActor2D(p.labels.back());
      // A handle slides on the model's surface: one that lies off it (a tragus) is shown, not dragged.
      if (!lies_on_model_skin(name)) continue;
      Ptr<vtkHandleWidget>& handle = handles[name];
      const auto old = p.handles.find(name);
      if (old != p.handles.end()) {
        handle = old->second;
      } else {
        auto rep = make<vtkPointHandleRepresentation3D>();
        rep->SetPointPlacer(p.placer);
        rep->SmoothMotionOff();  // the handle follows the pointer onto the surface, not a motion in the focal plane
        rep->SetHandleSize(24);
        rep->GetProperty()->SetColor(1, 1, 1);
        handle = make<vtkHandleWidget>();
        handle->SetRepresentation(rep);
        handle->SetInteractor(p.widget->interactor());
        handle->SetCurrentRenderer(p.renderer);
        handle->AddObserver(vtkCommand::InteractionEvent, this, &ModelView::onLandmarkDragged);
        handle->AddObserver(vtkCommand::EndInteractionEvent, this, &ModelView::onLandmarkDragged);
      }
      handle->GetHandleRepresentation()->SetWorldPosition(const_cast<double*>(x.data()));
      handle->EnabledOn();
    }
  }
  for (auto& [name, handle] : p.handles)
    if (!handles.count(name)) {
      handle->Off();
      handle->RemoveAllObservers();
    }
  p.handles = std::move(handles);
  markers.install(p.landmarkPoints);
  p.landmarkActor->SetVisibility(shown);
  p.leaderActor->SetVisibility(shown);
  p.labelBoxes.clear();
}

void ModelView::layOutLandmarkLabels() {
  Pipeline& p = *p_;
  const vtkIdType n = p.landmarkPoints->GetNumberOfPoints();
  auto lines = make<vtkCellArray>();
  auto ends = make<vtkPoints>();
  p.labelBoxes.clear();
  if (p.landmarkActor->GetVisibility() && n == static_cast<vtkIdType>(p.labels.size())) {
    Eigen::MatrixX2d anchors(n, 2), sizes(n, 2);
    for (vtkIdType i = 0; i < n; ++i) {
      double x[3];
      p.landmarkPoints->GetPoint(i, x);
      p.overlay->SetWorldPoint(x[0], x[1], x[2], 1.0);
      p.overlay->WorldToDisplay();
      anchors.row(i) << p.overlay->GetDisplayPoint()[0], p.overlay->GetDisplayPoint()[1];
      double size[2];
      p.labels[i]->GetSize(p.overlay, size);
      sizes.row(i) << size[0], size[1];
    }
    LabelLayoutOptions layout;
    layout.marker_radius = kLandmarkHandleRadius;
    const int* view = p.overlay->GetSize();
    layout.viewport = Eigen::Vector2d(view[0], view[1]);
    const Eigen::MatrixX2d corners = place_labels(anchors, sizes, layout);
    for (vtkIdType i = 0; i < n; ++i) {
      p.labels[i]->SetDisplayPosition(static_cast<int>(std::lround(corners(i, 0))),
                                      static_cast<int>(std::lround(corners(i, 1))));
      p.labelBoxes.emplace_back(corners(i, 0), corners(i, 1), sizes(i, 0), sizes(i, 1));
      // A name that had to move away from its marker points back to it: a line from the marker's edge to the name's
      // nearest point.
      const Eigen::Vector2d a = anchors.row(i).transpose();
      const Eigen::Vector2d nearest =
          a.cwiseMax(corners.row(i).transpose()).cwiseMin((corners.row(i) + sizes.row(i)).transpose());
      const double distance = (nearest - a).norm();
      if (distance <= layout.marker_radius + 2 * layout.gap) continue;
      const Eigen::Vector2d from = a + (nearest - a) * (layout.marker_radius / distance);
      const vtkIdType ids[2] = {ends->InsertNextPoint(from.x(), from.y(), 0),
                                ends->InsertNextPoint(nearest.x(), nearest.y(), 0)};
      lines->InsertNextCell(2, ids);
    }
  }
  p.leaderLines->SetPoints(ends);
  p.leaderLines->SetLines(lines);
}

std::vector<QRectF> ModelView::landmarkLabelBoxes() const { return p_->labelBoxes; }

void ModelView::showSessionLandmarks() {
  if (!session_->hasModel(role_)) return;
  updateLandmarks();
  render();
}

int ModelView::shownLandmarks() const {
  return p_->landmarkActor->GetVisibility() ? static_cast<int>(p_->landmarkPoints->GetNumberOfPoints()) : 0;
}

void ModelView::onLandmarkDragged(vtkObject* handle, unsigned long event, void*) {
  Pipeline& p = *p_;
  const auto dragged = std::find_if(p.handles.begin(), p.handles.end(),
                                    [handle](const auto& h) { return h.second.GetPointer() == handle; });
  if (dragged == p.handles.end()) return;
  const Eigen::Vector3d x(dragged->second->GetHandleRepresentation()->GetWorldPosition());
  if (event == vtkCommand::EndInteractionEvent) {
    const std::string name = dragged->first;  // the handles are rebuilt when the session takes the move
    emit landmarkMoved(role_, name, x);
    return;
  }
  // While dragging only the marker moves: the features are placed again on release.
  const auto& points = session_->landmarks(role_)->points;
  const vtkIdType i = std::distance(points.begin(), points.find(dragged->first));
  p.landmarkPoints->GetPoints()->SetPoint(i, x.data());
  p.landmarkPoints->Modified();
}

QPoint ModelView::widgetPosition(const Eigen::Vector3d& x) const {
  vtkRenderer* r = p_->renderer;
  r->SetWorldPoint(x[0], x[1], x[2], 1.0);
  r->WorldToDisplay();
  const double* d = r->GetDisplayPoint();
  const double scale = p_->widget->devicePixelRatioF();
  return QPoint(int(std::lround(d[0] / scale)), int(std::lround((p_->window->GetSize()[1] - d[1]) / scale)));
}

QWidget* ModelView::renderWidget() const { return p_->widget; }

void ModelView::dragLandmark(const std::string& name, const Eigen::Vector3d& point) {
  const auto handle = p_->handles.find(name);
  if (handle == p_->handles.end()) return;
  handle->second->GetHandleRepresentation()->SetWorldPosition(const_cast<double*>(point.data()));
  onLandmarkDragged(handle->second, vtkCommand::InteractionEvent, nullptr);
  onLandmarkDragged(handle->second, vtkCommand::EndInteractionEvent, nullptr);
}

void ModelView::onCameraInteraction() {
  autoFrame_ = false;
  vtkCamera* c = p_->renderer->GetActiveCamera();
  emit cameraOrientationChanged(Eigen::Vector3d(c->GetDirectionOfProjection()), Eigen::Vector3d(c->GetViewUp()));
}

void ModelView::setCameraOrientation(const Eigen::Vector3d& direction, const Eigen::Vector3d& viewUp) {
  autoFrame_ = false;
  vtkCamera* c = p_->renderer->GetActiveCamera();
  const Eigen::Vector3d focal(c->GetFocalPoint());
  const Eigen::Vector3d position = focal - c->GetDistance() * direction.normalized();
  c->SetPosition(position.data());
  c->SetViewUp(viewUp.data());
  p_->renderer->ResetCameraClippingRange();
  render();
}

void ModelView::resetCamera() {
  autoFrame_ = true;
  framedSize_ = {};
  render();
}

// The renderer's aspect ratio is only known once the window has its final size, so framing happens just before a
// frame is drawn, whenever the size changed.
void ModelView::onRenderStart() {
  const int* size = p_->window->GetSize();
  if (autoFrame_ && (size[0] != framedSize_[0] || size[1] != framedSize_[1])) {
    framedSize_ = {size[0], size[1]};
    frameModel();
  }
  layOutLandmarkLabels();  // the names follow the camera
}

void ModelView::frameModel() {
  // A three-quarter view of the face: the FaceHex frame has +y anterior and +z superior.
  vtkCamera* c = p_->renderer->GetActiveCamera();
  c->SetFocalPoint(0, 0, 0);
  c->SetPosition(0.45, 1.0, 0.25);
  c->SetViewUp(0, 0, 1);
  p_->renderer->ResetCamera();
  c->Zoom(1.1);
  p_->renderer->ResetCameraClippingRange();
}

void ModelView::render() { p_->window->Render(); }

}  // namespace facehex::gui

#include "ui/constraint_panel.h"

#include <QAction>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPainter>
#include <QPushButton>
#include <QSignalBlocker>
#include <QStandardItemModel>
#include <QTableWidget>
#include <QToolButton>
#include <QVBoxLayout>

#include "ui/palette.h"

namespace facehex::gui {
namespace {

enum Column { kShown, kName, kField, kValue, kVertices, kSelection, kColumns };
// The list is as tall as its rows up to this many, so the automatic set (six sides, four features) is seen whole;
// longer lists scroll.
constexpr int kRowsShown = 12;

QIcon swatch(const QColor& c) {
  QPixmap pm(12, 12);
  pm.fill(Qt::transparent);
  QPainter painter(&pm);
  painter.setRenderHint(QPainter::Antialiasing);
  painter.setBrush(c);
  painter.setPen(c.darker(140));
  painter.drawEllipse(1, 1, 10, 10);
  return QIcon(pm);
}

QString describe(const Selection& s) {
  if (!s.ids.empty()) return QObject::tr("%L1 picked vertices").arg(s.ids.size());
  if (s.side) return QObject::tr("side %1").arg(kSideNames[*s.side]);
  const PlaneSelection& p = *s.plane;
  return QObject::tr("plane through (%1, %2, %3) normal (%4, %5, %6), band %7 mm, %8")
      .arg(p.point.x(), 0, 'f', 1)
      .arg(p.point.y(), 0, 'f', 1)
      .arg(p.point.z(), 0, 'f', 1)
      .arg(p.normal.x(), 0, 'f', 2)
      .arg(p.normal.y(), 0, 'f', 2)
      .arg(p.normal.z(), 0, 'f', 2)
      .arg(p.band, 0, 'g', 3)
      .arg(QString::fromStdString(p.region));
}

QComboBox* fieldCombo(QWidget* parent) {
  auto* c = new QComboBox(parent);
  for (const char* f : kFieldNames) c->addItem(f);
  return c;
}

}  // namespace

ConstraintPanel::ConstraintPanel(SessionModel* session, const QList<QAction*>& actions, QWidget* parent)
    : QWidget(parent), session_(session) {
  setObjectName("constraintPanel");
  modelChoice_ = new QComboBox(this);
  modelChoice_->setObjectName("modelChoice");
  modelChoice_->addItem(tr("Patient"), static_cast<int>(Role::Patient));
  modelChoice_->addItem(tr("Standard"), static_cast<int>(Role::Standard));
  modelChoice_->setToolTip(tr("The model the cutting plane and the constraint list act on"));

  QGroupBox* planeBox = buildPlaneBox();
  QGroupBox* addBox = buildNewConstraintBox();
  buildTable();
  QGridLayout* buttons = buildListButtons(actions);

  auto* top = new QHBoxLayout;
  top->addWidget(new QLabel(tr("Model:"), this));
  top->addWidget(modelChoice_, 1);
  // The list first: reviewing the constraints placed (the automatic ones) comes before placing more.
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(top);
  layout->addWidget(new QLabel(tr("Constraints:"), this));
  layout->addWidget(table_, 1);
  layout->addLayout(buttons);
  layout->addWidget(planeBox);
  layout->addWidget(addBox);

  connect(modelChoice_, qOverload<int>(&QComboBox::currentIndexChanged), this,
          [this](int i) { session_->setActiveRole(static_cast<Role>(modelChoice_->itemData(i).toInt())); });
  connect(session_, &SessionModel::activeRoleChanged, this, [this] {
    refreshModelChoice();
    refreshList();
  });
  connect(session_, &SessionModel::modelChanged, this, &ConstraintPanel::refreshModelChoice);
  connect(session_, &SessionModel::constraintsChanged, this, [this](Role r) {
    if (r == session_->activeRole()) refreshList();
  });
  connect(session_, &SessionModel::planeChanged, this, &ConstraintPanel::refreshPlane);
  connect(session_, &SessionModel::planeSelectionChanged, this, &ConstraintPanel::refreshPlane);
  connect(session_, &SessionModel::highlightChanged, this, [this] {
    const std::optional<Highlight>& h = session_->highlight();
    if (h && h->constraint >= 0 && h->role == session_->activeRole()) {
      table_->selectRow(h->constraint);
      table_->scrollTo(table_->model()->index(h->constraint, kName));
    }
  });
  refreshModelChoice();
  refreshPlane();
  refreshList();
}

// The cutting plane: its normal, band, region and what it selects.
QGroupBox* ConstraintPanel::buildPlaneBox() {
  band_ = new QDoubleSpinBox(this);
  band_->setObjectName("bandWidth");
  band_->setRange(0.01, 50);
  band_->setDecimals(2);
  band_->setSingleStep(0.5);
  band_->setSuffix(" mm");
  band_->setToolTip(tr("Full width of the slab around the plane: vertices within half of it are selected"));
  region_ = new QComboBox(this);
  region_->setObjectName("region");
  region_->addItem(tr("whole volume"), "volume");
  region_->addItem(tr("boundary surface"), "boundary");
  for (int s = 0; s < kNumSides; ++s)
    region_->addItem(tr("side %1: %2").arg(kSideNames[s], kSideDescriptions[s]), kSideNames[s]);
  auto* axes = new QHBoxLayout;
  axes->addWidget(new QLabel(tr("Normal:"), this));
  for (int axis = 0; axis < 3; ++axis) {
    auto* b = new QPushButton(QString("xyz"[axis]), this);
    b->setToolTip(tr("Turn the plane to face the %1 axis").arg(QString("xyz"[axis])));
    b->setMaximumWidth(34);
    connect(b, &QPushButton::clicked, this, [this, axis] { snapNormal(axis); });
    axes->addWidget(b);
  }
  auto* centre = new QPushButton(tr("Centre"), this);
  centre->setToolTip(tr("Move the plane to the centre of the model"));
  connect(centre, &QPushButton::clicked, this, [this] {
    if (session_->hasModel(session_->activeRole())) session_->centrePlane();
  });
  axes->addWidget(centre);
  axes->addStretch();
  selectionCount_ = new QLabel(this);
  selectionCount_->setObjectName("selectionCount");
  selectionCount_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);  // its numbers never widen the panel
  auto* planeBox = new QGroupBox(tr("Cutting plane (drag it in the highlighted view)"), this);
  auto* planeForm = new QFormLayout(planeBox);
  planeForm->addRow(axes);
  planeForm->addRow(tr("Band width:"), band_);
  planeForm->addRow(tr("Restrict to:"), region_);
  planeForm->addRow(selectionCount_);
  connect(band_, qOverload<double>(&QDoubleSpinBox::valueChanged), this,
          [this](double b) { editPlane([b](PlanePose& p) { p.band = b; }); });
  connect(region_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this](int i) {
    const std::string r = region_->itemData(i).toString().toStdString();
    editPlane([&r](PlanePose& p) { p.region = r; });
  });

  return planeBox;
}

// A new constraint from the plane's selection.
QGroupBox* ConstraintPanel::buildNewConstraintBox() {
  name_ = new QLineEdit(this);
  name_->setObjectName("constraintName");
  name_->setPlaceholderText(tr("e.g. mid-sagittal, eyebrow"));
  field_ = fieldCombo(this);
  field_->setObjectName("constraintField");
  value_ = new QDoubleSpinBox(this);
  value_->setObjectName("constraintValue");
  value_->setRange(0, 1);
  value_->setDecimals(3);
  value_->setSingleStep(0.05);
  value_->setValue(0.5);
  value_->setToolTip(tr("0 or 1 for a shape end, a value in between (0.5, 0.7) for a feature"));
  add_ = new QPushButton(tr("Add the selection as a constraint"), this);
  add_->setObjectName("addFromPlane");
  connect(add_, &QPushButton::clicked, this, &ConstraintPanel::addFromPlane);
  auto* addBox = new QGroupBox(tr("New constraint"), this);
  auto* addForm = new QFormLayout(addBox);
  addForm->addRow(tr("Name:"), name_);
  auto* fieldValue = new QHBoxLayout;
  fieldValue->addWidget(field_);
  fieldValue->addWidget(new QLabel(tr("= value"), this));
  fieldValue->addWidget(value_, 1);
  addForm->addRow(tr("Field:"), fieldValue);
  addForm->addRow(add_);

  return addBox;
}

// The constraint list.
void ConstraintPanel::buildTable() {
  table_ = new QTableWidget(0, kColumns, this);
  table_->setObjectName("constraintTable");
  table_->setHorizontalHeaderLabels({"", tr("Name"), tr("Field"), tr("Value"), tr("Vertices"), tr("Selection")});
  table_->horizontalHeaderItem(kShown)->setToolTip(tr("Show or hide the constraint's vertices"));
  table_->verticalHeader()->hide();
  table_->verticalHeader()->setSectionResizeMode(QHeaderView::Fixed);
  table_->verticalHeader()->setDefaultSectionSize(table_->fontMetrics().height() + 10);
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setSelectionMode(QAbstractItemView::SingleSelection);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setSectionResizeMode(kSelection, QHeaderView::Stretch);
  connect(table_, &QTableWidget::cellChanged, this, &ConstraintPanel::onCellChanged);
}

// Under the list: delete, the six sides and the given actions (facial features, load, save ...).
QGridLayout* ConstraintPanel::buildListButtons(const QList<QAction*>& actions) {
  remove_ = new QPushButton(tr("Delete"), this);
  remove_->setObjectName("deleteConstraint");
  connect(remove_, &QPushButton::clicked, this, [this] {
    const int row = table_->currentRow();
    if (row >= 0) session_->removeConstraint(session_->activeRole(), row);
  });
  sides_ = new QPushButton(tr("Six sides"), this);
  sides_->setObjectName("sixSides");
  sides_->setToolTip(tr("Add the six shape-end constraints (u0 ... w1) from the model's side labels"));
  connect(sides_, &QPushButton::clicked, this, [this] { session_->addSideConstraints(session_->activeRole()); });
  auto* buttons = new QGridLayout;
  buttons->addWidget(remove_, 0, 0);
  buttons->addWidget(sides_, 0, 1);
  for (int i = 0; i < actions.size(); ++i) {
    auto* b = new QToolButton(this);
    b->setDefaultAction(actions[i]);
    b->setToolButtonStyle(Qt::ToolButtonTextOnly);
    b->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
    buttons->addWidget(b, (i + 2) / 3, (i + 2) % 3);
  }

  return buttons;
}

void ConstraintPanel::refreshModelChoice() {
  const QSignalBlocker block(modelChoice_);
  modelChoice_->setCurrentIndex(modelChoice_->findData(static_cast<int>(session_->activeRole())));
  // Side regions and the six-sides button need the model's "side_mask".
  const Role r = session_->activeRole();
  const bool loaded = session_->hasModel(r);
  const bool sides = loaded && session_->model(r).domain.side_mask.size() > 0;
  auto* items = qobject_cast<QStandardItemModel*>(region_->model());
  for (int i = 2; i < region_->count(); ++i) items->item(i)->setEnabled(sides);
  sides_->setEnabled(sides);
  remove_->setEnabled(loaded);
  refreshPlane();
}

void ConstraintPanel::refreshPlane() {
  const PlanePose& p = session_->plane();
  {
    const QSignalBlocker b1(band_), b2(region_);
    band_->setValue(p.band);
    region_->setCurrentIndex(region_->findData(QString::fromStdString(p.region)));
  }
  const size_t n = session_->planeSelection().size();
  selectionCount_->setText(tr("<b>%L1</b> vertices selected, origin (%2, %3, %4) mm")
                               .arg(n)
                               .arg(p.origin.x(), 0, 'f', 1)
                               .arg(p.origin.y(), 0, 'f', 1)
                               .arg(p.origin.z(), 0, 'f', 1));
  add_->setEnabled(n > 0);
}

void ConstraintPanel::refreshList() {
  const QSignalBlocker block(table_);
  const Role r = session_->activeRole();
  const int rows = session_->hasModel(r) ? static_cast<int>(session_->constraints(r).set.constraints.size()) : 0;
  table_->setRowCount(rows);
  table_->setMinimumHeight(table_->horizontalHeader()->sizeHint().height() +
                           std::min(std::max(rows, 1), kRowsShown) * table_->verticalHeader()->defaultSectionSize() +
                           2 * table_->frameWidth());
  for (int i = 0; i < rows; ++i) {
    const Constraint& c = session_->constraints(r).set.constraints[i];
    auto* shown = new QTableWidgetItem(swatch(constraintColour(c)), "");
    shown->setFlags(Qt::ItemIsEnabled | Qt::ItemIsUserCheckable | Qt::ItemIsSelectable);
    shown->setCheckState(session_->constraints(r).visible[i] ? Qt::Checked : Qt::Unchecked);
    table_->setItem(i, kShown, shown);
    table_->setItem(i, kName, new QTableWidgetItem(QString::fromStdString(c.name)));
    auto* field = fieldCombo(table_);
    field->setCurrentIndex(c.field);
    connect(field, qOverload<int>(&QComboBox::activated), this, [this, i](int f) {
      Constraint edited = session_->constraints(session_->activeRole()).set.constraints.at(i);
      edited.field = f;
      session_->updateConstraint(session_->activeRole(), i, edited);
    });
    table_->setCellWidget(i, kField, field);
    table_->setItem(i, kValue, new QTableWidgetItem(QString::number(c.value)));
    const QString problem = session_->constraintProblem(r, i);
    auto* count = new QTableWidgetItem(QString("%L1").arg(session_->constraintVertices(r, i).size()));
    count->setFlags(Qt::ItemIsEnabled | Qt::ItemIsSelectable);
    count->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    if (!problem.isEmpty()) {
      count->setForeground(Qt::red);
      count->setToolTip(problem);
    }
    table_->setItem(i, kVertices, count);
    auto* selection = new QTableWidgetItem(describe(c.select));
    selection->setFlags(Qt::ItemIsEnabled | Qt::ItemIsSelectable);
    selection->setToolTip(selection->text());
    table_->setItem(i, kSelection, selection);
  }
}

void ConstraintPanel::onCellChanged(int row, int column) {
  const Role r = session_->activeRole();
  Constraint c = session_->constraints(r).set.constraints.at(row);
  const QString text = table_->item(row, column)->text().trimmed();
  bool ok = true;
  if (column == kShown) {
    session_->setConstraintVisible(r, row, table_->item(row, column)->checkState() == Qt::Checked);
    return;
  } else if (column == kName) {
    ok = !text.isEmpty();
    c.name = text.toStdString();
  } else if (column == kValue) {
    c.value = text.toDouble(&ok);
    ok = ok && c.value >= 0 && c.value <= 1;
  }
  if (ok)
    session_->updateConstraint(r, row, c);
  else
    refreshList();  // not a valid name or value in [0, 1]: put the old one back
}

void ConstraintPanel::addFromPlane() {
  const Role r = session_->activeRole();
  if (!session_->hasModel(r)) return;
  QString name = name_->text().trimmed();
  if (name.isEmpty()) name = tr("%1 = %2").arg(field_->currentText()).arg(value_->value());
  session_->addPlaneConstraint(r, name, field_->currentIndex(), value_->value());
  name_->clear();
}

void ConstraintPanel::snapNormal(int axis) {
  editPlane([axis](PlanePose& p) { p.normal = Eigen::Vector3d::Unit(axis); });
}

void ConstraintPanel::editPlane(const std::function<void(PlanePose&)>& change) {
  PlanePose pose = session_->plane();
  change(pose);
  session_->setPlane(pose);
}

}  // namespace facehex::gui

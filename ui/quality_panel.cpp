#include "ui/quality_panel.h"

#include <QHeaderView>
#include <QLabel>
#include <QTableWidget>
#include <QVBoxLayout>

namespace facehex::gui {
namespace {

// A small read-only table sized to show all its rows without scrolling.
QTableWidget* table(const QStringList& columns, const QStringList& rows, QWidget* parent) {
  auto* t = new QTableWidget(rows.size(), columns.size(), parent);
  t->setHorizontalHeaderLabels(columns);
  t->setVerticalHeaderLabels(rows);
  t->setEditTriggers(QAbstractItemView::NoEditTriggers);
  t->setSelectionMode(QAbstractItemView::NoSelection);
  t->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  t->setVerticalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  t->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  t->verticalHeader()->setSectionResizeMode(QHeaderView::Fixed);
  t->verticalHeader()->setDefaultSectionSize(t->fontMetrics().height() + 6);
  t->setFixedHeight(t->horizontalHeader()->sizeHint().height() + rows.size() * (t->fontMetrics().height() + 6) + 4);
  return t;
}

void set(QTableWidget* t, int row, int column, const QString& text) {
  auto* item = new QTableWidgetItem(text);
  item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
  t->setItem(row, column, item);
}

}  // namespace

QualityPanel::QualityPanel(SessionModel* session, QWidget* parent) : QWidget(parent), session_(session) {
  setObjectName("qualityPanel");
  // Laid out as in the paper: the angle bins (Table 1) and the measures (Table 2) are columns.
  QStringList bins;
  const auto& lo = DihedralDistortion::kBinLower;
  for (size_t b = 0; b < lo.size(); ++b)
    bins << (b + 1 < lo.size() ? QString("%1\u2013%2\u00b0").arg(lo[b]).arg(lo[b + 1])
                               : QString("\u2265 %1\u00b0").arg(lo[b]));
  bins << tr("mean") << tr("max");
  distortion_ = table(bins, {tr("patient, % of angles")}, this);
  distortion_->setObjectName("distortionTable");
  quality_ = table(
      {tr("mean shape"), tr("min shape"), tr("mean SJ"), tr("min SJ"), tr("SJ < 0.3"), tr("inverted"), tr("cells")},
      {tr("standard"), tr("patient")}, this);
  quality_->setObjectName("qualityTable");
  quality_->setToolTip(tr("SJ: scaled Jacobian (1 for a perfect cube, \u2264 0 for an inverted cell)"));
  status_ = new QLabel(this);
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(status_);
  layout->addWidget(new QLabel(tr("<b>Table 1</b> \u2014 change of the dihedral angles of the patient mesh against the "
                                  "standard"),
                               this));
  layout->addWidget(distortion_);
  layout->addWidget(new QLabel(tr("<b>Table 2</b> \u2014 element quality"), this));
  layout->addWidget(quality_);
  layout->addStretch();
  connect(session_, &SessionModel::resultsChanged, this, &QualityPanel::refresh);
  refresh();
}

void QualityPanel::refresh() {
  const TransferResult* r = session_->transfer();
  status_->setText(r ? tr("Patient hex mesh: %L1 vertices; %L2 placed inside a parametric tet, %L3 by the nearest "
                          "one.")
                           .arg(r->run.transfer.vertices)
                           .arg(r->run.transfer.located_inside)
                           .arg(r->run.transfer.located_nearest)
                     : tr("Run the transfer to fill these tables."));
  distortion_->clearContents();
  quality_->clearContents();
  if (!r) return;
  const DihedralDistortion& d = r->patient_quality.distortion;
  const int bins = static_cast<int>(d.percent.size());
  for (int b = 0; b < bins; ++b) set(distortion_, 0, b, QString::number(d.percent[b], 'f', 1));
  set(distortion_, 0, bins, QString("%1\u00b0").arg(d.mean_deg, 0, 'f', 1));
  set(distortion_, 0, bins + 1, QString("%1\u00b0").arg(d.max_deg, 0, 'f', 1));
  const std::array<const QualitySummary*, 2> rows = {&r->standard_quality.summary, &r->patient_quality.summary};
  for (int row = 0; row < 2; ++row) {
    const QualitySummary& q = *rows[row];
    set(quality_, row, 0, QString::number(q.shape_mean, 'f', 3));
    set(quality_, row, 1, QString::number(q.shape_min, 'f', 3));
    set(quality_, row, 2, QString::number(q.scaled_jacobian_mean, 'f', 3));
    set(quality_, row, 3, QString::number(q.scaled_jacobian_min, 'f', 3));
    set(quality_, row, 4, QString("%1%").arg(100 * q.fraction_scaled_jacobian_below_0_3, 0, 'f', 1));
    set(quality_, row, 5, QString::number(q.inverted));
    set(quality_, row, 6, QString("%L1").arg(q.cells));
  }
}

}  // namespace facehex::gui

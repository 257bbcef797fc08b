#include "ui/angle_histogram.h"

#include <QPainter>
#include <algorithm>
#include <cmath>

namespace facehex::gui {
namespace {

const QColor kBefore(170, 170, 170);
const QColor kAfter(38, 110, 220);

// Shares of all angles per bin, in %.
std::vector<double> percent(const AngleStatistics& a) {
  std::vector<double> p(a.histogram.size(), 0.0);
  for (size_t i = 0; i < p.size(); ++i) p[i] = a.angles > 0 ? 100.0 * a.histogram[i] / a.angles : 0.0;
  return p;
}

double niceStep(double range) {
  for (double s : {1.0, 2.0, 5.0, 10.0, 20.0, 25.0, 50.0})
    if (range / s <= 6) return s;
  return 100.0;
}

}  // namespace

AngleHistogram::AngleHistogram(SessionModel* session, QWidget* parent) : QWidget(parent), session_(session) {
  setObjectName("angleHistogram");
  setMinimumHeight(180);
  const auto repaint = [this] { update(); };
  connect(session_, &SessionModel::resultsChanged, this, repaint);
  connect(session_, &SessionModel::activeRoleChanged, this, repaint);
}

void AngleHistogram::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), Qt::white);
  const Role role = session_->activeRole();
  const ModelParameterization* param = session_->parameterization(role);
  if (!param) {
    p.setPen(palette().color(QPalette::PlaceholderText));
    p.drawText(rect(), Qt::AlignCenter | Qt::TextWordWrap,
               tr("Compute the fields to see how close the gradients of u, v, w are to orthogonal (paper Fig. 6)."));
    return;
  }
  const AngleStatistics& before = param->fields.angles_initial;
  const AngleStatistics& after = param->fields.angles;
  const std::vector<double> pb = percent(before), pa = percent(after);

  const QFontMetrics fm(font());
  const int line = fm.height();
  QFont bold = font();
  bold.setBold(true);
  p.setPen(Qt::black);
  p.setFont(bold);
  p.drawText(QRect(8, 4, width() - 16, line), Qt::AlignLeft,
             tr("Angles between the gradients of (u,v), (v,w), (u,w) per tet \u2014 %1").arg(roleName(role)));
  p.setFont(font());
  p.drawText(QRect(8, 4 + line, width() - 16, line), Qt::AlignLeft,
             tr("mean |90\u00b0 \u2212 angle|: %1\u00b0 before, %2\u00b0 after;  within 10\u00b0 of 90\u00b0: "
                "%3% \u2192 %4%")
                 .arg(before.mean_deviation_from_90, 0, 'f', 1)
                 .arg(after.mean_deviation_from_90, 0, 'f', 1)
                 .arg(100 * before.fraction_within_10_of_90, 0, 'f', 0)
                 .arg(100 * after.fraction_within_10_of_90, 0, 'f', 0));

  const QRect plot(8 + fm.horizontalAdvance("100%") + 6, 12 + 2 * line, 0, 0);
  const int left = plot.left(), top = plot.top(), right = width() - fm.horizontalAdvance("180\u00b0"),
            bottom = height() - line - 10;
  if (right - left < 60 || bottom - top < 40) return;
  const double ymax =
      std::max(1.0, std::max(*std::max_element(pb.begin(), pb.end()), *std::max_element(pa.begin(), pa.end())));
  const double step = niceStep(ymax);
  const double top_value = std::ceil(ymax / step) * step;
  auto y = [&](double v) { return bottom - (bottom - top) * v / top_value; };
  p.setPen(QColor(225, 225, 225));
  for (double v = 0; v <= top_value + 1e-9; v += step) p.drawLine(QPointF(left, y(v)), QPointF(right, y(v)));
  p.setPen(Qt::black);
  for (double v = 0; v <= top_value + 1e-9; v += step)
    p.drawText(QRectF(0, y(v) - line / 2.0, left - 4, line), Qt::AlignRight | Qt::AlignVCenter, QString("%1%").arg(v));

  const int bins = static_cast<int>(pb.size());
  const double binWidth = double(right - left) / bins;
  for (int b = 0; b < bins; ++b) {
    const double x0 = left + b * binWidth;
    p.fillRect(QRectF(x0 + 0.1 * binWidth, y(pb[b]), 0.4 * binWidth, bottom - y(pb[b])), kBefore);
    p.fillRect(QRectF(x0 + 0.5 * binWidth, y(pa[b]), 0.4 * binWidth, bottom - y(pa[b])), kAfter);
  }
  p.drawLine(left, bottom, right, bottom);
  for (int deg = 0; deg <= 180; deg += 30) {
    const double x = left + (right - left) * deg / 180.0;
    p.drawLine(QPointF(x, bottom), QPointF(x, bottom + 3));
    p.drawText(QRectF(x - 30, bottom + 3, 60, line), Qt::AlignHCenter | Qt::AlignTop, QString("%1\u00b0").arg(deg));
  }

  // Legend, top right inside the plot.
  const QString lb = tr("before"), la = tr("after orthogonalization");
  const int lw = 14 + fm.horizontalAdvance(lb) + 24 + 14 + fm.horizontalAdvance(la);
  int lx = right - lw - 4;
  const int ly = top + 4;
  p.fillRect(lx, ly + 2, 10, line - 4, kBefore);
  p.drawText(lx + 14, ly, fm.horizontalAdvance(lb) + 2, line, Qt::AlignLeft, lb);
  lx += 14 + fm.horizontalAdvance(lb) + 24;
  p.fillRect(lx, ly + 2, 10, line - 4, kAfter);
  p.drawText(lx + 14, ly, fm.horizontalAdvance(la) + 2, line, Qt::AlignLeft, la);
}

}  // namespace facehex::gui

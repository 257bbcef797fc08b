#include "app/category_png.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/util/error.h"

namespace facehex::cli {
namespace {

constexpr int kWidth = 960, kHeight = 540, kLeft = 90, kRight = kWidth - 20, kTop = 60, kBottom = kHeight - 110;
const Rgb kBlack = {0, 0, 0}, kGrid = {225, 225, 225}, kReference = {120, 120, 120};

// The value of quantile q in [0, 1] of sorted values, interpolated between neighbours.
double quantile(const std::vector<double>& sorted, double q) {
  const double at = q * static_cast<double>(sorted.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(at)), hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (at - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

// The axes, grid, labels, reference line and legend of a category plot over [lo, hi]; draw_item(canvas, i, x_left,
// x_right, y_of) draws item i within its column.
void draw_category_plot(const std::string& path, const CategoryPlot& plot, double lo, double hi,
                        const std::function<void(Canvas&, size_t, int, int, const std::function<int(double)>&)>& draw) {
  if (plot.items.empty()) throw Error(path, "a plot needs at least one item");
  if (!(hi > lo)) hi = lo + 1;
  const double step = tick_step(hi - lo);
  lo = step * std::floor(lo / step);
  hi = step * std::ceil(hi * 1.04 / step);
  Canvas canvas(kWidth, kHeight);
  const std::function<int(double)> y_of = [&](double v) {
    return kBottom - static_cast<int>(std::lround((kBottom - kTop) * (v - lo) / (hi - lo)));
  };
  for (double t = lo; t <= hi + 1e-9 * (hi - lo); t += step) {
    canvas.fill(kLeft, y_of(t), kRight, y_of(t) + 1, kGrid);
    canvas.text(tick_label(std::abs(t) < 1e-12 * step ? 0.0 : t), kLeft - 8, y_of(t), 14, 1.0, 0.5);
  }
  const int n = static_cast<int>(plot.items.size());
  const auto x_of = [&](double column) { return kLeft + static_cast<int>(std::lround((kRight - kLeft) * column / n)); };
  // Names under their columns: level when they fit, else rotated.
  const bool rotate = (kRight - kLeft) / n < 80;
  for (int i = 0; i < n; ++i) {
    draw(canvas, static_cast<size_t>(i), x_of(i + 0.2), x_of(i + 0.8), y_of);
    if (rotate)
      canvas.text(plot.items[i].name, x_of(i + 0.5), kBottom + 8, 13, 1.0, 0.5, 60);
    else
      canvas.text(plot.items[i].name, x_of(i + 0.5), kBottom + 8, 14, 0.5, 0.0);
  }
  if (plot.reference) {
    const int y = y_of(*plot.reference);
    for (int x = kLeft; x < kRight; x += 12) canvas.fill(x, y - 1, std::min(x + 7, kRight), y + 1, kReference);
    canvas.text(plot.reference_label, kRight - 4, y - 4, 13, 1.0, 1.0);
  }
  canvas.fill(kLeft, kBottom, kRight, kBottom + 1, kBlack);
  canvas.fill(kLeft, kTop, kLeft + 1, kBottom, kBlack);
  canvas.text(plot.title, kWidth / 2, 16, 18, 0.5, 0.0);
  canvas.text(plot.y_label, 22, (kTop + kBottom) / 2, 15, 0.5, 0.5, 90);
  const int ns = static_cast<int>(plot.legend.size());
  for (int s = 0; s < ns; ++s) {
    const int y = kTop + 10 + 24 * s, lx = kRight - 150;
    canvas.fill(lx + 8, y, lx + 24, y + 16, plot.legend[s].second);
    canvas.text(plot.legend[s].first, lx + 32, y + 8, 14, 0.0, 0.5);
  }
  canvas.write_png(path);
}

}  // namespace

void write_box_plot_png(const std::string& path, const CategoryPlot& plot) {
  std::vector<std::vector<double>> sorted;
  double lo = plot.reference.value_or(INFINITY), hi = plot.reference.value_or(-INFINITY);
  for (const CategoryItem& item : plot.items) {
    if (item.values.empty()) throw Error(path, "box plot item '" + item.name + "' has no values");
    sorted.push_back(item.values);
    std::sort(sorted.back().begin(), sorted.back().end());
    lo = std::min(lo, sorted.back().front());
    hi = std::max(hi, sorted.back().back());
  }
  draw_category_plot(path, plot, plot.y_min.value_or(lo), hi,
                     [&](Canvas& canvas, size_t i, int x0, int x1, const std::function<int(double)>& y_of) {
                       const std::vector<double>& v = sorted[i];
                       const Rgb& c = plot.items[i].color;
                       const int xm = (x0 + x1) / 2, q1 = y_of(quantile(v, 0.25)), q3 = y_of(quantile(v, 0.75));
                       canvas.fill(xm - 1, y_of(v.back()), xm + 1, q3, c);
                       canvas.fill(xm - 1, q1, xm + 1, y_of(v.front()) + 1, c);
                       canvas.fill(xm - 12, y_of(v.back()) - 1, xm + 12, y_of(v.back()) + 1, c);
                       canvas.fill(xm - 12, y_of(v.front()) - 1, xm + 12, y_of(v.front()) + 1, c);
                       canvas.fill(x0, q3, x1, q1 + 1, c, 0.35);
                       canvas.fill(x0, q3 - 1, x1, q3 + 1, c);
                       canvas.fill(x0, q1 - 1, x1, q1 + 1, c);
                       canvas.fill(x0, q3, x0 + 2, q1, c);
                       canvas.fill(x1 - 2, q3, x1, q1, c);
                       const int median = y_of(quantile(v, 0.5));
                       canvas.fill(x0, median - 2, x1, median + 2, kBlack);
                     });
}

void write_bar_chart_png(const std::string& path, const CategoryPlot& plot) {
  double hi = 0;
  for (const CategoryItem& item : plot.items) {
    if (item.values.size() != 1) throw Error(path, "bar '" + item.name + "' needs exactly one value");
    hi = std::max(hi, item.values[0]);
  }
  draw_category_plot(path, plot, 0.0, hi,
                     [&](Canvas& canvas, size_t i, int x0, int x1, const std::function<int(double)>& y_of) {
                       canvas.fill(x0, y_of(plot.items[i].values[0]), x1, y_of(0.0), plot.items[i].color);
                     });
}

}  // namespace facehex::cli

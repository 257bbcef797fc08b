#include "app/histogram_png.h"

#include <algorithm>
#include <cmath>

#include "app/png_canvas.h"
#include "core/util/error.h"

namespace facehex::cli {

std::vector<double> percent_histogram(const Eigen::VectorXd& values, const std::vector<double>& edges) {
  if (edges.size() < 2) throw Error("histogram", "needs at least two bin edges");
  std::vector<double> percent(edges.size() - 1, 0.0);
  if (values.size() == 0) return percent;
  for (const double v : values) {
    const long bin = std::upper_bound(edges.begin(), edges.end(), v) - edges.begin() - 1;
    ++percent[std::clamp<long>(bin, 0, static_cast<long>(percent.size()) - 1)];
  }
  for (double& p : percent) p *= 100.0 / static_cast<double>(values.size());
  return percent;
}

void write_histogram_png(const std::string& path, const HistogramPlot& plot) {
  const int bins = static_cast<int>(plot.edges.size()) - 1;
  if (bins < 1) throw Error(path, "a histogram needs at least one bin");
  double top = 0;
  for (const auto& s : plot.series) {
    if (static_cast<int>(s.percent.size()) != bins)
      throw Error(path, "histogram series '" + s.name + "' has " + std::to_string(s.percent.size()) + " values for " +
                            std::to_string(bins) + " bins");
    for (const double p : s.percent) top = std::max(top, p);
  }
  const double step = tick_step(std::max(top, 1e-9) * 1.08);
  top = std::min(step * std::ceil(std::max(top, 1e-9) * 1.08 / step), std::max(top, 100.0));  // percentages: <= 100

  const int width = 960, height = 540, x0 = 90, x1 = width - 20, y0 = 60, y1 = height - 75;
  Canvas canvas(width, height);
  const Rgb black = {0, 0, 0}, grid = {225, 225, 225};
  auto y_of = [&](double percent) { return y1 - static_cast<int>(std::lround((y1 - y0) * percent / top)); };
  auto x_of = [&](double bin) { return x0 + static_cast<int>(std::lround((x1 - x0) * bin / bins)); };

  for (double t = 0; t <= top + 1e-9 * top; t += step) {
    canvas.fill(x0, y_of(t), x1, y_of(t) + 1, grid);
    canvas.text(tick_label(t), x0 - 8, y_of(t), 14, 1.0, 0.5);
  }
  const int ns = static_cast<int>(plot.series.size());
  for (int s = 0; s < ns; ++s) {
    const HistogramSeries& series = plot.series[s];
    for (int b = 0; b < bins; ++b) {
      if (!plot.overlaid) {
        const double left = b + 0.08 + 0.84 * s / ns, right = b + 0.08 + 0.84 * (s + 1) / ns;
        canvas.fill(x_of(left), y_of(series.percent[b]), std::max(x_of(left) + 1, x_of(right)), y1, series.color);
        continue;
      }
      // The top of the bar, and the step up or down from the bar before (from the axis for the first and to the
      // axis after the last), two pixels wide.
      const int y = y_of(series.percent[b]), before = b > 0 ? y_of(series.percent[b - 1]) : y1;
      canvas.fill(x_of(b), y - 1, x_of(b + 1) + 1, y + 1, series.color);
      canvas.fill(x_of(b) - 1, std::min(y, before) - 1, x_of(b) + 1, std::max(y, before) + 1, series.color);
      if (b == bins - 1) canvas.fill(x_of(bins) - 1, y - 1, x_of(bins) + 1, y1, series.color);
    }
  }
  canvas.fill(x0, y1, x1, y1 + 1, black);
  canvas.fill(x0, y0, x0 + 1, y1, black);
  int label_every = (bins + 11) / 12;  // at most 13 labels, on edges that divide the axis evenly
  while (bins % label_every != 0) ++label_every;
  for (int e = 0; e <= bins; e += label_every) {
    canvas.fill(x_of(e), y1, x_of(e) + 1, y1 + 5, black);
    canvas.text(tick_label(plot.edges[e]), x_of(e), y1 + 8, 14, 0.5, 0.0);
  }
  canvas.text(plot.title, width / 2, 16, 18, 0.5, 0.0);
  canvas.text(plot.x_label, (x0 + x1) / 2, height - 30, 15, 0.5, 0.0);
  canvas.text(plot.y_label, 22, (y0 + y1) / 2, 15, 0.5, 0.5, 90);
  // The legend goes in the top corner over the lower bars (on a translucent backdrop).
  double half_max[2] = {0, 0};  // the highest bar in the left and in the right half
  for (const auto& series : plot.series)
    for (int b = 0; b < bins; ++b) half_max[2 * b >= bins] = std::max(half_max[2 * b >= bins], series.percent[b]);
  const int lx = half_max[1] <= half_max[0] ? x1 - 258 : x0 + 10;
  canvas.fill(lx, y0 + 2, lx + 256, y0 + 18 + 24 * ns, {255, 255, 255}, 0.8);
  for (int s = 0; s < ns; ++s) {
    const int y = y0 + 10 + 24 * s;
    canvas.fill(lx + 8, y, lx + 24, y + 16, plot.series[s].color);
    canvas.text(plot.series[s].name, lx + 32, y + 8, 14, 0.0, 0.5);
  }
  canvas.write_png(path);
}

}  // namespace facehex::cli

#include "app/error_map_png.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "app/png_canvas.h"
#include "core/util/error.h"

namespace facehex::cli {
namespace {

// Blue, green, yellow, red at 0, 1/3, 2/3 and 1 of the scale.
Rgb colour(double t) {
  static const double stops[4][3] = {{40, 70, 200}, {40, 170, 80}, {240, 210, 40}, {210, 30, 30}};
  t = std::clamp(t, 0.0, 1.0) * 3;
  const int i = std::min(2, static_cast<int>(t));
  const double f = t - i;
  Rgb c;
  for (int k = 0; k < 3; ++k)
    c[k] = static_cast<unsigned char>(std::lround((1 - f) * stops[i][k] + f * stops[i + 1][k]));
  return c;
}

std::string mm(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g mm", x);
  return buf;
}

}  // namespace

void write_error_map_png(const std::string& path, const std::string& title, const std::vector<ErrorMapPanel>& panels,
                         double scale_top_mm) {
  // At least min_w wide, the panels centred: the title and the colour bar need that much even over one panel.
  const int panel_w = 360, panel_h = 420, top = 50, bar_h = 70, min_w = 640;
  const int n = std::max<int>(1, static_cast<int>(panels.size()));
  Canvas canvas(std::max(panel_w * n, min_w), top + panel_h + bar_h);
  const int left = (canvas.width() - panel_w * n) / 2;
  canvas.text(title, canvas.width() / 2, 12, 18, 0.5, 0.0);
  for (int p = 0; p < static_cast<int>(panels.size()); ++p) {
    const ErrorMapPanel& panel = panels[p];
    if (panel.points.rows() != panel.error.size() || panel.points.cols() != 3)
      throw Error(path, "error map panel '" + panel.title + "' has " + std::to_string(panel.points.rows()) +
                            " points and " + std::to_string(panel.error.size()) + " errors");
    const int x0 = left + p * panel_w;
    canvas.text(panel.title, x0 + panel_w / 2, top - 4, 13, 0.5, 1.0);
    if (panel.points.rows() == 0) continue;
    const Eigen::Vector3d lo = panel.points.colwise().minCoeff(), hi = panel.points.colwise().maxCoeff();
    const double scale =
        std::min((panel_w - 20) / std::max(hi.x() - lo.x(), 1e-9), (panel_h - 20) / std::max(hi.z() - lo.z(), 1e-9));
    const double cx = 0.5 * (lo.x() + hi.x()), cz = 0.5 * (lo.z() + hi.z());
    std::vector<int> order(static_cast<size_t>(panel.points.rows()));
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return panel.points(a, 1) < panel.points(b, 1); });
    for (const int i : order) {
      const int x = x0 + panel_w / 2 + static_cast<int>(std::lround((panel.points(i, 0) - cx) * scale));
      const int y = top + panel_h / 2 - static_cast<int>(std::lround((panel.points(i, 2) - cz) * scale));
      canvas.fill(x - 2, y - 2, x + 3, y + 3, colour(panel.error(i) / scale_top_mm));
    }
  }
  const int bx0 = canvas.width() / 2 - 200, bx1 = canvas.width() / 2 + 200, by = top + panel_h + 15;
  for (int x = bx0; x < bx1; ++x) canvas.fill(x, by, x + 1, by + 16, colour((x - bx0) / double(bx1 - bx0)));
  for (int k = 0; k <= 4; ++k) {
    const int x = bx0 + (bx1 - bx0) * k / 4;
    canvas.fill(x, by + 16, x + 1, by + 21, {0, 0, 0});
    canvas.text(mm(scale_top_mm * k / 4) + (k == 4 ? " and more" : ""), x, by + 24, 12, 0.5, 0.0);
  }
  canvas.write_png(path);
}

}  // namespace facehex::cli

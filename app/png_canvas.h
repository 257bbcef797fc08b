#pragma once
// An RGB raster for the reports' PNG plots, drawn without a display: rectangles, text rendered with FreeType
// (vtkFreeTypeTools, VTK's embedded font), written with vtkPNGWriter, atomically.
#include <array>
#include <string>
#include <vector>

namespace facehex::cli {

using Rgb = std::array<unsigned char, 3>;

// Row 0 at the top.
class Canvas {
 public:
  Canvas(int width, int height) : w_(width), h_(height), pixels_(3 * width * height, 255) {}

  int width() const { return w_; }
  int height() const { return h_; }

  // The rectangle [x0, x1) x [y0, y1), blended with `alpha`.
  void fill(int x0, int y0, int x1, int y1, const Rgb& c, double alpha = 1.0);

  // Text with its anchor point at (x, y): ax, ay in [0, 1] pick the anchor within the text box (0 = left / top).
  // rotation: degrees counter-clockwise.
  void text(const std::string& s, int x, int y, int size, double ax, double ay, double rotation = 0);

  // Throws facehex::Error(path, ...) when the file cannot be written.
  void write_png(const std::string& path) const;

 private:
  void blend(int x, int y, const Rgb& c, double alpha);

  int w_, h_;
  std::vector<unsigned char> pixels_;
};

// A tick step of 1, 2 or 5 times a power of ten giving 4 to 10 ticks over an axis of length `range` (> 0).
double tick_step(double range);
// A tick label: the shortest of %g.
std::string tick_label(double x);

}  // namespace facehex::cli

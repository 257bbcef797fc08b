#pragma once
// Histograms as PNG images for the reports, drawn without a display: bars are rasterized into an RGB image, labels
// rendered with FreeType (vtkFreeTypeTools, VTK's embedded font), the file written with vtkPNGWriter, atomically.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace facehex::cli {

struct HistogramSeries {
  std::string name;
  std::array<unsigned char, 3> color;  // RGB
  std::vector<double> percent;         // one value per bin
};

struct HistogramPlot {
  std::string title, x_label, y_label = "% of all";
  std::vector<double> edges;            // #bins + 1, increasing
  std::vector<HistogramSeries> series;  // drawn side by side within each bin, or:
  bool overlaid = false;                // each series as the outline of its bars, over each other (many series)
};

// Share (in %) of `values` in each bin [edges[i], edges[i+1]); values beyond the last edge count in the last bin,
// below the first in the first.
std::vector<double> percent_histogram(const Eigen::VectorXd& values, const std::vector<double>& edges);

// Throws facehex::Error(path, ...) if the plot is malformed (series and bins differ in size) or cannot be written.
void write_histogram_png(const std::string& path, const HistogramPlot& plot);

}  // namespace facehex::cli

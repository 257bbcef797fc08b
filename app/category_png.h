#pragma once
// Plots with one column per named item (a patient) as PNG images for the reports, drawn like the histograms
// (png_canvas.h): box plots of each item's values, and bars of one value per item.
#include <optional>
#include <string>
#include <vector>

#include "app/png_canvas.h"

namespace facehex::cli {

struct CategoryItem {
  std::string name;
  Rgb color;
  std::vector<double> values;  // a box plot: all of the item's values; a bar chart: one
};

struct CategoryPlot {
  std::string title, y_label;
  std::optional<double> y_min;  // the value axis starts here (default: at the least value, or 0 for bars)
  std::vector<CategoryItem> items;
  std::optional<double> reference;  // a dashed line across the plot at this value, e.g. the standard's
  std::string reference_label;
  std::vector<std::pair<std::string, Rgb>> legend;
};

// Per item a box from the first to the third quartile with a line at the median and whiskers to the least and the
// greatest value. Throws facehex::Error(path, ...) when an item has no value or the file cannot be written.
void write_box_plot_png(const std::string& path, const CategoryPlot& plot);
// Per item a bar up to its one value (the value axis starts at 0). Throws facehex::Error(path, ...) when an item has
// not exactly one value or the file cannot be written.
void write_bar_chart_png(const std::string& path, const CategoryPlot& plot);

}  // namespace facehex::cli

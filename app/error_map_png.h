#pragma once
// A per-vertex error drawn on a face seen from the front, as a PNG for the reports: each panel projects its points
// onto the x-z plane (+y anterior looks out of the picture, +z up), nearer points over farther ones, coloured from
// blue (0 mm) through green and yellow to red (the scale's top and above), with a colour bar.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace facehex::cli {

struct ErrorMapPanel {
  std::string title;
  Eigen::MatrixXd points;  // #P x 3, mm
  Eigen::VectorXd error;   // #P, mm
};

// Throws facehex::Error(path, ...) when a panel's points and errors differ in count or the file cannot be written.
void write_error_map_png(const std::string& path, const std::string& title, const std::vector<ErrorMapPanel>& panels,
                         double scale_top_mm);

}  // namespace facehex::cli

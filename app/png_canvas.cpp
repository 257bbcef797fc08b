#include "app/png_canvas.h"

#include <vtkErrorCode.h>
#include <vtkFreeTypeTools.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkStdString.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/util/atomic_file.h"
#include "core/util/error.h"

namespace facehex::cli {

double tick_step(double range) {
  const double magnitude = std::pow(10.0, std::floor(std::log10(range)));
  for (const double m : {0.1, 0.2, 0.5, 1.0, 2.0, 5.0})
    if (range / (m * magnitude) <= 10) return m * magnitude;
  return 10 * magnitude;
}

std::string tick_label(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

void Canvas::fill(int x0, int y0, int x1, int y1, const Rgb& c, double alpha) {
  for (int y = std::max(0, y0); y < std::min(h_, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(w_, x1); ++x) blend(x, y, c, alpha);
}

void Canvas::text(const std::string& s, int x, int y, int size, double ax, double ay, double rotation) {
  vtkNew<vtkTextProperty> property;
  property->SetFontFamilyToArial();
  property->SetFontSize(size);
  property->SetColor(0, 0, 0);
  property->SetOrientation(rotation);
  vtkNew<vtkImageData> image;
  int dims[2] = {0, 0};
  vtkFreeTypeTools* freetype = vtkFreeTypeTools::GetInstance();
  const bool power_of_two = freetype->GetScaleToPowerTwo();
  freetype->ScaleToPowerTwoOff();
  const bool ok = freetype->RenderString(property, vtkStdString(s), 72, image, dims);
  freetype->SetScaleToPowerTwo(power_of_two);
  if (!ok) return;
  int extent[6];
  image->GetExtent(extent);
  const int tw = extent[1] - extent[0] + 1, th = extent[3] - extent[2] + 1;
  const int left = x - static_cast<int>(std::lround(ax * tw)), top = y - static_cast<int>(std::lround(ay * th));
  for (int j = 0; j < th; ++j)
    for (int i = 0; i < tw; ++i) {
      const auto* p = static_cast<unsigned char*>(image->GetScalarPointer(extent[0] + i, extent[2] + j, 0));
      if (p[3] > 0) blend(left + i, top + (th - 1 - j), {p[0], p[1], p[2]}, p[3] / 255.0);  // image rows go up
    }
}

void Canvas::write_png(const std::string& path) const {
  vtkNew<vtkImageData> image;
  image->SetDimensions(w_, h_, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int y = 0; y < h_; ++y)
    std::copy_n(&pixels_[3 * w_ * y], 3 * w_, static_cast<unsigned char*>(image->GetScalarPointer(0, h_ - 1 - y, 0)));
  write_atomically(path, [&](const std::string& tmp) {
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(tmp.c_str());
    writer->SetInputData(image);
    writer->Write();
    if (writer->GetErrorCode() != vtkErrorCode::NoError)
      throw Error(path, std::string("cannot write the PNG: ") +
                            vtkErrorCode::GetStringFromErrorCode(static_cast<unsigned long>(writer->GetErrorCode())));
  });
}

void Canvas::blend(int x, int y, const Rgb& c, double alpha) {
  if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
  unsigned char* p = &pixels_[3 * (w_ * y + x)];
  for (int k = 0; k < 3; ++k) p[k] = static_cast<unsigned char>(std::lround((1 - alpha) * p[k] + alpha * c[k]));
}

}  // namespace facehex::cli

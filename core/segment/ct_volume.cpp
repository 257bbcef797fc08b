#include "core/segment/ct_volume.h"

#include <vtkAlgorithm.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkMetaImageReader.h>
#include <vtkMetaImageWriter.h>
#include <vtkNIFTIImageReader.h>
#include <vtkNew.h>
#include <vtkNrrdReader.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLImageDataReader.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <functional>

#include "core/io/vtk_util.h"
#include "core/segment/dicom_series.h"
#include "core/segment/metaimage_header.h"
#include "core/segment/nifti_header.h"
#include "core/segment/nrrd_header.h"
#include "core/util/atomic_file.h"
#include "core/util/child_process.h"
#include "core/util/error.h"

namespace facehex {
namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// Signed axis "+x" ... "-z" -> (axis, sign).
std::pair<int, int> parse_axis(const std::string& text, const std::string& what) {
  if (text.size() == 2 && (text[0] == '+' || text[0] == '-') && text[1] >= 'x' && text[1] <= 'z')
    return {text[1] - 'x', text[0] == '+' ? 1 : -1};
  throw Error("orientation", what + " axis must be one of +x, -x, +y, -y, +z, -z (got '" + text + "')");
}

// A volume and the axes of its voxel grid that point anterior and superior by the file (empty: not stated).
struct FileVolume {
  CtVolume ct;
  CtOrientation axes;
};

// LPS from RAS and back: x and y negated.
const Eigen::Matrix3d kLpsFromRas = Eigen::Vector3d(-1, -1, 1).asDiagonal();

// The scan frame of a NIfTI file: its orientation matrix takes VTK's image coordinates to RAS.
ScanFrame nifti_scan_frame(vtkMatrix4x4* m) {
  ScanFrame f;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) f.rotation(r, c) = m->GetElement(r, c);
    f.translation(r) = m->GetElement(r, 3);
  }
  // Orthonormal columns (the matrix is a rotation, possibly with a flip; kept exact for the frame's check).
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(f.rotation, Eigen::ComputeFullU | Eigen::ComputeFullV);
  f.rotation = kLpsFromRas * svd.matrixU() * svd.matrixV().transpose();
  f.translation = kLpsFromRas * f.translation;
  return f;
}

// The axes by a NIfTI orientation (VTK image coordinates -> RAS, spacing factored out; vtkNIFTIImageReader has already
// reversed the slices when qfac is -1). Each voxel axis must lie along a patient axis: an oblique volume is refused.
CtOrientation nifti_axes(const std::string& path, vtkMatrix4x4* m) {
  constexpr double kAligned = 0.999;  // cosine: within about 2.5 degrees of a patient axis
  CtOrientation axes;
  bool used[3] = {false, false, false};
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d column =
        Eigen::Vector3d(m->GetElement(0, a), m->GetElement(1, a), m->GetElement(2, a)).normalized();
    int world = 0;
    if (!(column.cwiseAbs().maxCoeff(&world) > kAligned) || used[world])
      throw Error(path, std::string("its NIfTI orientation is oblique or degenerate (voxel axis ") + char('x' + a) +
                            " is not along a patient axis of its own): resample it to the patient axes, or give the "
                            "axes with --anterior and --superior");
    used[world] = true;
    const std::string axis = std::string(column(world) > 0 ? "+" : "-") + char('x' + a);
    if (world == 1) axes.anterior = axis;
    if (world == 2) axes.superior = axis;
  }
  return axes;
}

// The axes as 2 characters each ("+y", or blanks when not stated).
constexpr size_t kAxesBytes = 4;
constexpr size_t kVolumeHeaderBytes = kAxesBytes + 3 * sizeof(int) + 6 * sizeof(double) + 12 * sizeof(double);

// Voxel values as floats, rescaled by slope * v + intercept; from the first component of each tuple.
template <typename T>
void rescaled_to_float(const T* values, int components, size_t count, double slope, double intercept, float* out) {
  for (size_t i = 0; i < count; ++i)
    out[i] = static_cast<float>(slope * static_cast<double>(values[i * components]) + intercept);
}

// A volume file through VTK's readers (in the file's voxel axes), as the bytes the reading child sends its parent:
// the axes, the geometry, the scan frame, then the voxels as floats, converted straight from the file's type (a volume
// is hundreds of MB: each copy on the way costs). `given` axes make the file's own unneeded.
std::vector<char> read_volume_bytes_here(const std::string& path, const CtOrientation& given) {
  const std::string name = lower(path);
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ends_with(name, ".mhd") || ends_with(name, ".mha")) {
    auto meta = vtkSmartPointer<vtkMetaImageReader>::New();
    meta->SetFileName(path.c_str());
    reader = meta;
  } else if (ends_with(name, ".nii") || ends_with(name, ".nii.gz")) {
    auto nifti = vtkSmartPointer<vtkNIFTIImageReader>::New();
    nifti->SetFileName(path.c_str());
    reader = nifti;
  } else if (ends_with(name, ".nrrd") || ends_with(name, ".nhdr")) {
    auto nrrd = vtkSmartPointer<vtkNrrdReader>::New();
    nrrd->SetFileName(path.c_str());
    reader = nrrd;
  } else if (ends_with(name, ".vti")) {
    auto xml = vtkSmartPointer<vtkXMLImageDataReader>::New();
    xml->SetFileName(path.c_str());
    reader = xml;
  } else {
    throw Error(path, "unknown CT format (expected .mhd, .mha, .nii, .nii.gz, .nrrd, .nhdr, .vti or a DICOM folder)");
  }
  io::run_vtk(path, "reading the CT", reader);  // VTK's messages become one line of the exception

  CtOrientation axes;
  ScanFrame frame;
  double slope = 1, intercept = 0;
  if (auto* nifti = vtkNIFTIImageReader::SafeDownCast(reader)) {
    if (nifti->GetRescaleSlope() != 0) slope = nifti->GetRescaleSlope(), intercept = nifti->GetRescaleIntercept();
    vtkMatrix4x4* orientation = nifti->GetSFormMatrix() ? nifti->GetSFormMatrix() : nifti->GetQFormMatrix();
    if (orientation && (given.anterior.empty() || given.superior.empty())) axes = nifti_axes(path, orientation);
    if (orientation) frame = nifti_scan_frame(orientation);
  }

  vtkImageData* image = vtkImageData::SafeDownCast(reader->GetOutputDataObject(0));
  vtkDataArray* scalars = image ? image->GetPointData()->GetScalars() : nullptr;
  int dims[3] = {0, 0, 0};
  if (image) image->GetDimensions(dims);
  if (!scalars || scalars->GetNumberOfTuples() == 0) throw Error(path, "could not read a volume");
  const size_t count = static_cast<size_t>(dims[0]) * dims[1] * dims[2];
  if (static_cast<size_t>(scalars->GetNumberOfTuples()) != count)
    throw Error(path, "its voxel values do not fill its grid");
  double spacing[3], origin[3];
  image->GetSpacing(spacing);
  image->GetOrigin(origin);
  for (double& h : spacing) h = std::abs(h);

  std::vector<char> bytes(kVolumeHeaderBytes + count * sizeof(float));
  char* p = bytes.data();
  for (const std::string& axis : {axes.anterior, axes.superior})
    p[0] = axis.empty() ? ' ' : axis[0], p[1] = axis.empty() ? ' ' : axis[1], p += 2;
  std::memcpy(p, dims, sizeof dims), p += sizeof dims;
  std::memcpy(p, spacing, sizeof spacing), p += sizeof spacing;
  std::memcpy(p, origin, sizeof origin), p += sizeof origin;
  std::memcpy(p, frame.rotation.data(), 9 * sizeof(double)), p += 9 * sizeof(double);
  std::memcpy(p, frame.translation.data(), 3 * sizeof(double)), p += 3 * sizeof(double);
  float* voxels = reinterpret_cast<float*>(p);
  const int components = scalars->GetNumberOfComponents();
  switch (scalars->GetDataType()) {
    vtkTemplateMacro(rescaled_to_float(static_cast<const VTK_TT*>(scalars->GetVoidPointer(0)), components, count, slope,
                                       intercept, voxels));
    default:
      throw Error(path, std::string("voxels of type ") + scalars->GetDataTypeAsString() + " are not a CT's");
  }
  return bytes;
}

FileVolume volume_from_bytes(const std::vector<char>& bytes, const std::string& path) {
  FileVolume out;
  CtVolume& ct = out.ct;
  ct.source = path;
  GridGeometry& g = ct.intensity.geometry;
  const size_t header = kVolumeHeaderBytes;
  if (bytes.size() < header) throw Error(path, "incomplete volume from the reading process");
  const char* p = bytes.data();
  for (std::string* axis : {&out.axes.anterior, &out.axes.superior})
    *axis = p[0] == ' ' ? "" : std::string(p, 2), p += 2;
  std::memcpy(g.dims.data(), p, sizeof g.dims), p += sizeof g.dims;
  std::memcpy(g.spacing.data(), p, 3 * sizeof(double)), p += 3 * sizeof(double);
  std::memcpy(g.origin.data(), p, 3 * sizeof(double)), p += 3 * sizeof(double);
  std::memcpy(ct.scan_frame.rotation.data(), p, 9 * sizeof(double)), p += 9 * sizeof(double);
  std::memcpy(ct.scan_frame.translation.data(), p, 3 * sizeof(double)), p += 3 * sizeof(double);
  if (bytes.size() != header + g.size() * sizeof(float))
    throw Error(path, "incomplete volume from the reading process");
  ct.intensity.data.resize(g.size());
  std::memcpy(ct.intensity.data.data(), p, g.size() * sizeof(float));
  return out;
}

// VTK's image readers trust the sizes a file declares; a MetaImage, NIfTI or NRRD header is checked first, and the
// reading runs in a child process with a time and memory budget that grow with the file (core/util/child_process.h).
FileVolume read_volume_file(const std::string& path, const CtOrientation& given) {
  const std::string name = lower(path);
  if (ends_with(name, ".mhd") || ends_with(name, ".mha")) check_metaimage_header(path);
  if (ends_with(name, ".nii") || ends_with(name, ".nii.gz")) check_nifti_header(path);
  const bool ras_space = (ends_with(name, ".nrrd") || ends_with(name, ".nhdr")) && check_nrrd_header(path).ras_space;
  const ChildLimits limits = limits_for_reading(path, size_t{4} << 30);  // the voxels in the file's type and as floats
  FileVolume volume =
      volume_from_bytes(compute_in_child(
                            path, "reading the CT", [&] { return read_volume_bytes_here(path, given); }, limits),
                        path);
  if (ras_space) volume.ct.scan_frame.rotation = kLpsFromRas;
  return volume;
}

}  // namespace

CtVolume read_ct_volume(const std::string& path, const CtOrientation& orientation, const std::string& dicom_series) {
  namespace fs = std::filesystem;
  if (!fs::exists(path)) throw Error(path, "no such file or folder");
  if (!dicom_series.empty() && !fs::is_directory(path))
    throw Error(path, "is a file, not a DICOM folder: --series names a series of a folder's");
  CtVolume ct;
  CtOrientation axes = orientation;  // a side not stated: the file's own orientation if it has one, else +y / +z
  if (fs::is_directory(path)) {
    DicomVolume dicom = read_dicom_series(path, dicom_series);
    ct = CtVolume{std::move(dicom.intensity), path, dicom.gantry_tilt_degrees};
    ct.scan_frame.rotation = dicom.patient_axes;
    if (axes.anterior.empty()) axes.anterior = dicom.anterior;
    if (axes.superior.empty()) axes.superior = dicom.superior;
  } else {
    FileVolume volume = read_volume_file(path, orientation);
    ct = std::move(volume.ct);
    if (axes.anterior.empty()) axes.anterior = volume.axes.anterior;
    if (axes.superior.empty()) axes.superior = volume.axes.superior;
  }
  if (axes.anterior.empty()) axes.anterior = "+y";
  if (axes.superior.empty()) axes.superior = "+z";
  const GridGeometry& g = ct.intensity.geometry;
  if (g.dims[0] < 2 || g.dims[1] < 2 || g.dims[2] < 2)
    throw Error(path, "is not a 3D volume (" + std::to_string(g.dims[0]) + " x " + std::to_string(g.dims[1]) + " x " +
                          std::to_string(g.dims[2]) + " voxels)");
  if (!(g.spacing.minCoeff() > 0)) throw Error(path, "has a zero voxel spacing");
  // A blank volume has no tissue to find: say so here, naming the file, rather than at the thresholds.
  const auto [lo, hi] = std::minmax_element(ct.intensity.data.begin(), ct.intensity.data.end());
  if (*lo == *hi) throw Error(path, "every voxel has the same intensity: a blank volume, not a CT");
  return reorient(std::move(ct), axes);
}

void write_ct_volume(const std::string& path, const CtVolume& ct) {
  if (!ends_with(lower(path), ".mha")) throw Error(path, "CT volumes are written as .mha (single-file MetaImage)");
  const GridGeometry& g = ct.intensity.geometry;
  vtkNew<vtkImageData> image;
  image->SetDimensions(g.dims[0], g.dims[1], g.dims[2]);
  image->SetSpacing(g.spacing.data());
  image->SetOrigin(g.origin.data());
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfValues(static_cast<vtkIdType>(g.size()));
  std::copy(ct.intensity.data.begin(), ct.intensity.data.end(), values->GetPointer(0));
  image->GetPointData()->SetScalars(values);
  write_atomically(path, [&](const std::string& tmp) {
    vtkNew<vtkMetaImageWriter> writer;
    writer->SetInputData(image);
    writer->SetFileName(tmp.c_str());
    writer->SetCompression(false);
    io::run_vtk(path, "writing the CT", writer, [&] {
      writer->Write();
      return 1;
    });
  });
}

bool is_ct_input(const std::string& path) {
  if (std::filesystem::is_directory(path)) return true;
  const std::string name = lower(std::filesystem::path(path).filename().string());
  const auto& exts = ct_volume_extensions();
  return std::any_of(exts.begin(), exts.end(),
                     [&name](const std::string& ext) { return name.size() > ext.size() && ends_with(name, ext); });
}

const std::vector<std::string>& ct_volume_extensions() {
  static const std::vector<std::string> extensions = {".mhd", ".mha", ".nii", ".nii.gz", ".nrrd", ".nhdr"};
  return extensions;
}

CtVolume reorient(CtVolume ct, const CtOrientation& orientation) {
  const auto [anterior_axis, anterior_sign] = parse_axis(orientation.anterior, "anterior");
  const auto [superior_axis, superior_sign] = parse_axis(orientation.superior, "superior");
  if (anterior_axis == superior_axis)
    throw Error("orientation", "anterior and superior must be different axes (got " + orientation.anterior + " and " +
                                   orientation.superior + ")");
  // New axis a reads the old axis source[a] with direction sign[a]; x = y cross z keeps the frame right-handed.
  int source[3], sign[3];
  source[1] = anterior_axis, sign[1] = anterior_sign;
  source[2] = superior_axis, sign[2] = superior_sign;
  source[0] = 3 - anterior_axis - superior_axis;
  Eigen::Vector3d y = Eigen::Vector3d::Zero(), z = Eigen::Vector3d::Zero();
  y(anterior_axis) = anterior_sign;
  z(superior_axis) = superior_sign;
  sign[0] = y.cross(z)(source[0]) > 0 ? 1 : -1;
  if (source[0] == 0 && source[1] == 1 && sign[0] == 1 && sign[1] == 1 && sign[2] == 1) return ct;

  const GridGeometry& old_g = ct.intensity.geometry;
  CtVolume out;
  out.source = ct.source;
  out.gantry_tilt_degrees = ct.gantry_tilt_degrees;
  Eigen::Matrix3d new_from_old = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 3; ++a) new_from_old(a, source[a]) = sign[a];
  out.scan_frame = ct.scan_frame.after_model_change(new_from_old, Eigen::Vector3d::Zero());
  GridGeometry& g = out.intensity.geometry;
  for (int a = 0; a < 3; ++a) {
    const int s = source[a];
    g.dims[a] = old_g.dims[s];
    g.spacing(a) = old_g.spacing(s);
    // Physical coordinate along the new axis = sign * old coordinate, so the new frame is a rotation of the old one.
    g.origin(a) = sign[a] > 0 ? old_g.origin(s) : -old_g.upper(s);
  }
  out.intensity.data.resize(g.size());
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const int n[3] = {i, j, k};
        int o[3];
        for (int a = 0; a < 3; ++a) o[source[a]] = sign[a] > 0 ? n[a] : g.dims[a] - 1 - n[a];
        out.intensity(i, j, k) = ct.intensity(o[0], o[1], o[2]);
      }
  return out;
}

}  // namespace facehex

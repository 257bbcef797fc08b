#include "tests/fuzz/fuzz_readers.h"

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <stdexcept>

#include "core/face/landmark_file.h"
#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/segment/ct_volume.h"
#include "core/util/error.h"

namespace facehex::fuzz {
namespace {

namespace fs = std::filesystem;

// One way to read an input: the names of the files its parts go to, and the read of the first.
struct Variant {
  std::vector<std::string> files;
  std::function<void(const std::string& path)> read;
};

void read_mesh(const std::string& path) { read_volume_mesh(path); }
// Surfaces are not tetrahedralized here: TetGen runs in a child of its own and is tested on sound surfaces; what a
// damaged file meets is the surface reader.
void read_surface(const std::string& path) { read_surface_mesh(path); }
void read_ct(const std::string& path) { read_ct_volume(path); }
void read_constraints(const std::string& path) { read_constraint_set(path); }
void read_landmarks(const std::string& path) { read_landmark_file(path); }

const std::map<std::string, std::vector<Variant>>& readers() {
  static const std::map<std::string, std::vector<Variant>> table = {
      {"vtu", {{{"input.vtu"}, read_mesh}}},
      {"vtk", {{{"input.vtk"}, read_mesh}}},
      {"msh", {{{"input.msh"}, read_mesh}}},
      {"tetgen", {{{"input.node", "input.ele"}, read_mesh}}},
      {"ansys", {{{"input.node", "input.elem"}, read_mesh}}},
      {"inp", {{{"input.inp"}, read_mesh}}},
      {"feb", {{{"input.feb"}, read_mesh}}},
      {"surface",
       {{{"input.stl"}, read_surface},
        {{"input.obj"}, read_surface},
        {{"input.ply"}, read_surface},
        {{"input.vtp"}, read_surface}}},
      {"metaimage", {{{"input.mha"}, read_ct}, {{"input.mhd", "input.raw"}, read_ct}}},
      {"nifti", {{{"input.nii"}, read_ct}}},
      {"nrrd", {{{"input.nrrd"}, read_ct}, {{"input.nhdr", "input.raw"}, read_ct}}},
      {"constraints", {{{"input.json"}, read_constraints}}},
      {"landmarks", {{{"input.json"}, read_landmarks}, {{"input.mrk.json"}, read_landmarks}}},
  };
  return table;
}

const std::vector<Variant>& variants_of(const std::string& reader) {
  const auto it = readers().find(reader);
  if (it == readers().end()) throw std::invalid_argument("no fuzz reader '" + reader + "'");
  return it->second;
}

// The variant the input chooses and the bytes left for its files.
const Variant& choose(const std::string& reader, std::string_view* bytes) {
  const std::vector<Variant>& variants = variants_of(reader);
  if (variants.size() == 1 || bytes->empty()) return variants.front();
  const Variant& v = variants[static_cast<unsigned char>(bytes->front()) % variants.size()];
  bytes->remove_prefix(1);
  return v;
}

}  // namespace

const std::vector<std::string>& reader_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& [name, variants] : readers()) n.push_back(name);
    return n;
  }();
  return names;
}

std::string input_path(const std::string& reader, const std::uint8_t* data, std::size_t size, const std::string& dir) {
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  return (fs::path(dir) / choose(reader, &bytes).files.front()).string();
}

std::optional<std::string> read_input(const std::string& reader, const std::uint8_t* data, std::size_t size,
                                      const std::string& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) fs::remove_all(entry.path());
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const Variant& variant = choose(reader, &bytes);
  for (size_t f = 0; f < variant.files.size(); ++f) {
    const bool last = f + 1 == variant.files.size();
    const size_t end = last ? std::string_view::npos : bytes.find(kFileSeparator);
    std::ofstream out(fs::path(dir) / variant.files[f], std::ios::binary);
    out << bytes.substr(0, end);
    bytes.remove_prefix(end == std::string_view::npos ? bytes.size() : end + kFileSeparator.size());
  }
  try {
    variant.read((fs::path(dir) / variant.files.front()).string());
    return std::nullopt;
  } catch (const Error& e) {
    return e.what();
  }
}

}  // namespace facehex::fuzz

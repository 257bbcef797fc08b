#pragma once
// Helpers shared by the core/io tests: a scratch folder, small files, a sample mesh with every cell type, and the
// "throws a facehex::Error that names the file" check.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/util/error.h"

namespace facehex::test {

namespace fs = std::filesystem;

inline std::string data_dir() { return std::string(FACEHEX_TEST_DATA_DIR) + "/io"; }

// A fresh folder under /tmp, removed with everything in it at the end of the test.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "facehex_io_test_XXXXXX").string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const fs::path& path() const { return path_; }
  // Every entry of the folder, for "nothing else was left behind" checks.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

// This test program's scratch folder, removed with everything in it when the program exits.
inline const fs::path& program_scratch_dir() {
  static const TempDir dir;
  return dir.path();
}

inline void write_file(const std::string& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << content;
  ASSERT_TRUE(out.good()) << path;
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Copies the first `bytes` bytes of `from` to `to`.
inline void write_prefix(const std::string& from, const std::string& to, size_t bytes) {
  write_file(to, read_file(from).substr(0, bytes));
}

// Two hexes, a wedge and a tet, all positively oriented in VTK's conventions, sharing faces, with coordinates that
// have no short decimal form (so that a writer printing too few digits fails the round trips) and a point and cell
// data array each of one and of three components.
inline VolumeMesh sample_mesh() {
  VolumeMesh m;
  m.V.resize(18, 3);
  m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1,  // hex 0
      2, 0, 0, 2, 1, 0, 2, 0, 1, 2, 1, 1,                                         // hex 1 (shares x=1 face)
      0, 0, 2, 1, 0, 2, 0, 1, 2,                                                  // wedge top
      2, 0, 2, 1, 1, 2, 0.5, 0.5, 3;                                              // spare points
  for (int i = 0; i < m.V.rows(); ++i)
    for (int k = 0; k < 3; ++k) m.V(i, k) += 1e-3 * std::sin(7.0 * i + k) + 1.0 / 3.0;
  m.C = Eigen::MatrixXi::Constant(4, 8, -1);
  m.C.row(0) << 0, 1, 2, 3, 4, 5, 6, 7;
  m.C.row(1) << 1, 8, 9, 2, 5, 10, 11, 6;
  // Wedge on top of hex 0: its bottom triangle (4, 7, 5) has its normal pointing down, away from the top (12, 14, 13).
  m.C.row(2) << 4, 7, 5, 12, 14, 13, -1, -1;
  m.C.row(3) << 5, 10, 6, 13, -1, -1, -1, -1;
  m.types = {CellType::Hex, CellType::Hex, CellType::Wedge, CellType::Tet};
  m.point_data["temperature"] = Eigen::VectorXd::LinSpaced(18, -1.0 / 7.0, 36.6);
  m.point_data["displacement"] = m.V * 0.1;
  Eigen::MatrixXd quality(4, 3);
  quality << 0.1, 0.2, 0.3, 1e-300, -2.5e17, 3.14159, 0, -0.0, 42, 1.0 / 3.0, 2.0 / 3.0, 1;
  m.cell_data["quality"] = quality;
  m.cell_data["gmsh_physical"] = Eigen::Vector4d(1, 1, 2, 7);
  return m;
}

// Fails the test unless `f` throws a facehex::Error whose message contains `needle` (normally the file name).
inline void expect_error(const std::function<void()>& f, const std::string& needle, const std::string& context = "") {
  try {
    f();
    ADD_FAILURE() << "no facehex::Error thrown " << context;
  } catch (const facehex::Error& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
        << "message '" << e.what() << "' does not contain '" << needle << "' " << context;
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "message is not one line: " << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw " << typeid(e).name() << " instead of facehex::Error: " << e.what() << " " << context;
  }
}

// Signed volume of tet (a, b, c, d): positive when d lies on the side the right-hand normal of (a, b, c) points to.
inline double signed_volume(const Eigen::MatrixXd& V, int a, int b, int c, int d) {
  const Eigen::Vector3d pa = V.row(a), pb = V.row(b), pc = V.row(c), pd = V.row(d);
  return (pb - pa).cross(pc - pa).dot(pd - pa) / 6.0;
}

// For a hex or wedge: the right-hand normal of its base polygon (nodes 0..3 or 0..2) dotted with the vector from the
// base centroid to the top centroid. VTK: positive for hexes, negative for wedges (see core/mesh.h).
inline double base_normal_towards_top(const VolumeMesh& m, int c) {
  const int n = node_count(m.types[c]) / 2;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero(), base = Eigen::Vector3d::Zero(), top = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d p = m.V.row(m.C(c, k)), q = m.V.row(m.C(c, (k + 1) % n));
    normal += p.cross(q);  // Newell: exact for planar polygons, a good average otherwise
    base += p / n;
    top += Eigen::Vector3d(m.V.row(m.C(c, n + k))) / n;
  }
  return normal.dot(top - base);
}

}  // namespace facehex::test

#include "core/io/mesh_bytes.h"

#include <cstdint>
#include <cstring>
#include <string>

#include "core/util/error.h"

namespace facehex::io {
namespace {

class Writer {
 public:
  template <class T>
  void value(T x) {
    append(&x, sizeof x);
  }
  void append(const void* data, size_t size) {
    const char* p = static_cast<const char*>(data);
    bytes.insert(bytes.end(), p, p + size);
  }
  template <class Matrix>
  void matrix(const Matrix& m) {
    value<std::int64_t>(m.rows());
    value<std::int64_t>(m.cols());
    append(m.data(), static_cast<size_t>(m.size()) * sizeof(typename Matrix::Scalar));
  }
  void arrays(const std::map<std::string, Eigen::MatrixXd>& named) {
    value<std::int64_t>(static_cast<std::int64_t>(named.size()));
    for (const auto& [name, m] : named) {
      value<std::int64_t>(static_cast<std::int64_t>(name.size()));
      append(name.data(), name.size());
      matrix(m);
    }
  }
  std::vector<char> bytes;
};

class Reader {
 public:
  Reader(const std::vector<char>& bytes, const std::string& subject) : bytes_(bytes), subject_(subject) {}
  void take(void* out, size_t size) {
    if (size > bytes_.size() - at_) throw Error(subject_, "incomplete mesh data from the reading process");
    std::memcpy(out, bytes_.data() + at_, size);
    at_ += size;
  }
  template <class T>
  T value() {
    T x;
    take(&x, sizeof x);
    return x;
  }
  std::int64_t count() {
    const auto n = value<std::int64_t>();
    if (n < 0 || static_cast<std::uint64_t>(n) > bytes_.size()) throw Error(subject_, "bad mesh data size");
    return n;
  }
  template <class Matrix>
  Matrix matrix() {
    const std::int64_t rows = count(), cols = count();
    if (cols > 0 && rows > static_cast<std::int64_t>(bytes_.size()) / cols) throw Error(subject_, "bad mesh data size");
    Matrix m(rows, cols);
    take(m.data(), static_cast<size_t>(m.size()) * sizeof(typename Matrix::Scalar));
    return m;
  }
  std::map<std::string, Eigen::MatrixXd> arrays() {
    std::map<std::string, Eigen::MatrixXd> named;
    for (std::int64_t n = count(); n > 0; --n) {
      std::string name(static_cast<size_t>(count()), '\0');
      take(name.data(), name.size());
      named[name] = matrix<Eigen::MatrixXd>();
    }
    return named;
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  const std::vector<char>& bytes_;
  const std::string& subject_;
  size_t at_ = 0;
};

}  // namespace

std::vector<char> to_bytes(const VolumeMesh& mesh) {
  Writer w;
  w.matrix(mesh.V);
  w.matrix(mesh.C);
  w.value<std::int64_t>(static_cast<std::int64_t>(mesh.types.size()));
  for (CellType t : mesh.types) w.value<std::int32_t>(static_cast<std::int32_t>(t));
  w.arrays(mesh.point_data);
  w.arrays(mesh.cell_data);
  w.arrays(mesh.field_data);
  return std::move(w.bytes);
}

std::vector<char> to_bytes(const SurfaceMesh& surface) {
  Writer w;
  w.matrix(surface.V);
  w.matrix(surface.F);
  w.matrix(surface.labels);
  return std::move(w.bytes);
}

SurfaceMesh surface_from_bytes(const std::vector<char>& bytes, const std::string& subject) {
  Reader r(bytes, subject);
  SurfaceMesh s;
  s.V = r.matrix<Eigen::MatrixXd>();
  s.F = r.matrix<Eigen::MatrixXi>();
  s.labels = r.matrix<Eigen::VectorXi>();
  if (!r.done()) throw Error(subject, "unexpected surface data from the reading process");
  return s;
}

VolumeMesh mesh_from_bytes(const std::vector<char>& bytes, const std::string& subject) {
  Reader r(bytes, subject);
  VolumeMesh mesh;
  mesh.V = r.matrix<Eigen::MatrixXd>();
  mesh.C = r.matrix<Eigen::MatrixXi>();
  mesh.types.resize(static_cast<size_t>(r.count()));
  for (CellType& t : mesh.types) t = static_cast<CellType>(r.value<std::int32_t>());
  mesh.point_data = r.arrays();
  mesh.cell_data = r.arrays();
  mesh.field_data = r.arrays();
  if (!r.done()) throw Error(subject, "unexpected mesh data from the reading process");
  return mesh;
}

}  // namespace facehex::io

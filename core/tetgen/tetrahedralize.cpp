// TetGen 1.5 as a library: the closed surface goes in as a PLC of triangular facets (one facet per triangle, facet
// marker = face label), TetGen runs with -p (PLC), -q (radius-edge ratio / min dihedral), -a (max volume of a
// regular tet of the target edge), -Q (quiet) and optionally -Y (keep the boundary as given). Its boundary subfaces
// come back with the marker of the facet they lie on; we match them to the boundary faces we extract ourselves from
// the tets, so the result does not depend on TetGen's face orientation conventions.
//
// TetGen runs in a forked child process. TetGen 1.5.0 is not safe to call in-process on bad input: in library mode
// terminatetetgen() frees the mesh and throws, then the unwinding frees it again (double free: the process dies before
// any catch), some inputs trip internal assert()s (abort), and a self-intersecting surface can make the refinement
// loop forever (hence the -d self-intersection check, in a second child at the same time, which stops the first when
// it finds one). The children (core/util/child_process.h) send their results back through pipes and die with their
// parent; a child that dies becomes a facehex::Error.
#include "core/tetgen/tetrahedralize.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <tetgen.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "core/mesh/side_mask.h"
#include "core/mesh/sides.h"
#include "core/mesh/tet_topology.h"
#include "core/util/child_process.h"
#include "core/util/error.h"

namespace facehex {
namespace {

using FaceKey = std::array<int, 3>;

FaceKey sorted_key(int a, int b, int c) {
  FaceKey k = {a, b, c};
  std::sort(k.begin(), k.end());
  return k;
}

// TetGen's tets per volume of a regular tet of the target edge: TetGen's quality meshes of segmented faces.
constexpr double kTetsPerRegularVolume = 1.8;
// Memory of the whole pipeline per tet (TetGen, the Laplacian's factorization, the locator, the outputs), with margin.
constexpr double kPipelineBytesPerTet = 3 * 1024;

std::string count_text(double n) {
  char text[32];
  std::snprintf(text, sizeof text, n >= 1e6 ? "%.1f million" : "%.0f", n >= 1e6 ? n / 1e6 : n);
  return text;
}

// A surface that would make more tets than the budget is refused up front, with the estimate, instead of failing after
// minutes (or exhausting the machine).
void check_tet_budget(const SurfaceMesh& surface, const TetrahedralizeOptions& options) {
  const double budget = options.max_tets > 0 ? options.max_tets : max_tets_for_memory();
  const double predicted = predicted_tet_count(std::abs(enclosed_volume(surface)), options);
  if (predicted > budget) {
    char edge[32];
    std::snprintf(edge, sizeof edge, "%.3g", options.target_edge_length);
    throw Error("tetgen", "at an edge length of " + std::string(edge) + " mm the model would have about " +
                              count_text(predicted) + " tets, more than " +
                              (options.max_tets > 0 ? "the limit of " : "this machine's memory allows, about ") +
                              count_text(budget) + "; raise --edge-length");
  }
}

// Every undirected edge must be used by exactly two faces, once in each direction: closed, manifold along edges and
// consistently oriented (TetGen itself would mesh an open surface's convex hull or fail obscurely).
void check_closed(const SurfaceMesh& s) {
  if (s.F.rows() < 4) throw Error("tetgen", "the surface has fewer than 4 triangles, it cannot enclose a volume");
  if (s.labels.size() != 0 && s.labels.size() != s.F.rows())
    throw Error("tetgen", "the surface has " + std::to_string(s.labels.size()) + " face labels for " +
                              std::to_string(s.F.rows()) + " faces");
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < s.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
      if (a < 0 || a >= s.V.rows() || b < 0 || b >= s.V.rows())
        throw Error("tetgen", "face " + std::to_string(f) + " refers to a vertex that does not exist");
      if (a == b) throw Error("tetgen", "face " + std::to_string(f) + " is degenerate (repeated vertex)");
      if (++directed[{a, b}] > 1)
        throw Error("tetgen", "the surface is not manifold or not consistently oriented (edge " + std::to_string(a) +
                                  "-" + std::to_string(b) + " used twice in the same direction)");
    }
  }
  for (const auto& [edge, count] : directed)
    if (!directed.count({edge.second, edge.first}))
      throw Error("tetgen", "the surface is not closed (edge " + std::to_string(edge.first) + "-" +
                                std::to_string(edge.second) + " has only one face)");
}

double signed_volume(const Eigen::MatrixXd& V, int a, int b, int c, int d) {
  const Eigen::Vector3d p0 = V.row(a), p1 = V.row(b), p2 = V.row(c), p3 = V.row(d);
  return (p1 - p0).dot((p2 - p0).cross(p3 - p0)) / 6.0;
}

std::string tetgen_failure(int code) {
  switch (code) {
    case 1:
      return "out of memory";
    case 3:
      return "the surface intersects itself";
    case 4:
      return "the surface has a feature (edge or gap) too small for TetGen's tolerance";
    case 5:
      return "the surface has two (nearly) coincident facets";
    case 10:
      return "the input surface is invalid";
    default:
      return "TetGen failed (internal error " + std::to_string(code) + ")";
  }
}

// TetGen's output, 0-based: #points x 3 coordinates, #tets x 4 corners, boundary subfaces x 3 and their markers.
struct RawMesh {
  std::vector<double> points;
  std::vector<int> tets, faces, markers;
};

// Child -> parent message: a Status, a count, then (for kOk) the four arrays, each as a size and its elements.
enum Status : std::int32_t { kOk = 0, kSelfIntersecting = 1, kFailed = 2 };

template <class T>
void write_array(int fd, const T* data, std::int64_t count) {
  write_to_parent(fd, &count, sizeof count);
  if (count > 0) write_to_parent(fd, data, static_cast<size_t>(count) * sizeof(T));
}

// The children. Each runs TetGen once, writes its message to fd and ends; TetGen's assert() messages would only
// confuse the user (the parent reports the failure), so their output goes to /dev/null.
void silence_output() {
  const int devnull = ::open("/dev/null", O_WRONLY);
  if (devnull >= 0) ::dup2(devnull, STDOUT_FILENO), ::dup2(devnull, STDERR_FILENO);
}

// -d: are any two facets intersecting? Sends {kSelfIntersecting, count} or {kOk, 0}.
[[noreturn]] void diagnose_child(int fd, tetgenio& in) {
  silence_output();
  try {
    tetgenbehavior diagnose;
    char diagnose_switches[] = "pdQ";
    diagnose.parse_commandline(diagnose_switches);
    tetgenio found;
    ::tetrahedralize(&diagnose, &in, &found);
    const std::int32_t message[2] = {found.numberoftrifaces > 0 ? kSelfIntersecting : kOk, found.numberoftrifaces};
    write_to_parent(fd, message, sizeof message);
  } catch (int code) {
    const std::int32_t message[2] = {kFailed, code};
    write_to_parent(fd, message, sizeof message);
  }
  ::_exit(0);
}

// The quality mesh. Sends {kOk, 0} and the four arrays, or {kFailed, TetGen's code}.
[[noreturn]] void mesh_child(int fd, tetgenio& in, const TetrahedralizeOptions& options) {
  silence_output();
  try {
    // The volume bound is that of a regular tetrahedron with the target edge: a^3 / (6 sqrt 2).
    const double max_volume = std::pow(options.target_edge_length, 3) / (6.0 * std::sqrt(2.0));
    char switches[256];
    std::snprintf(switches, sizeof switches, "pq%.6g/%.6ga%.9gQ%s", options.max_radius_edge_ratio,
                  options.min_dihedral_deg, max_volume, options.preserve_surface ? "Y" : "");
    tetgenbehavior behavior;
    behavior.parse_commandline(switches);
    // Set the bounds exactly (the switch string rounds them).
    behavior.minratio = options.max_radius_edge_ratio;
    behavior.mindihedral = options.min_dihedral_deg;
    behavior.maxvolume = max_volume;
    tetgenio out;
    ::tetrahedralize(&behavior, &in, &out);

    const std::int32_t message[2] = {kOk, 0};
    write_to_parent(fd, message, sizeof message);
    write_array(fd, out.pointlist, 3 * static_cast<std::int64_t>(out.numberofpoints));
    std::vector<int> tets(4 * static_cast<size_t>(out.numberoftetrahedra));
    for (int t = 0; t < out.numberoftetrahedra; ++t)
      for (int k = 0; k < 4; ++k) tets[4 * t + k] = out.tetrahedronlist[t * out.numberofcorners + k] - out.firstnumber;
    write_array(fd, tets.data(), static_cast<std::int64_t>(tets.size()));
    std::vector<int> faces(3 * static_cast<size_t>(out.numberoftrifaces));
    for (size_t i = 0; i < faces.size(); ++i) faces[i] = out.trifacelist[i] - out.firstnumber;
    write_array(fd, faces.data(), static_cast<std::int64_t>(faces.size()));
    std::vector<int> markers(out.numberoftrifaces, 0);
    if (out.trifacemarkerlist)
      std::copy(out.trifacemarkerlist, out.trifacemarkerlist + out.numberoftrifaces, markers.begin());
    write_array(fd, markers.data(), static_cast<std::int64_t>(markers.size()));
  } catch (int code) {  // only reached where TetGen threw before building its mesh
    const std::int32_t message[2] = {kFailed, code};
    write_to_parent(fd, message, sizeof message);
  }
  ::_exit(0);
}

// Reads a whole array written by write_array from `buffer` at `at`.
template <class T>
bool read_array(const std::vector<char>& buffer, size_t& at, std::vector<T>& out) {
  std::int64_t count = 0;
  if (at + sizeof count > buffer.size()) return false;
  std::memcpy(&count, buffer.data() + at, sizeof count);
  at += sizeof count;
  if (count < 0 || at + static_cast<size_t>(count) * sizeof(T) > buffer.size()) return false;
  out.resize(static_cast<size_t>(count));
  if (count > 0) std::memcpy(out.data(), buffer.data() + at, static_cast<size_t>(count) * sizeof(T));
  at += static_cast<size_t>(count) * sizeof(T);
  return true;
}

std::array<std::int32_t, 2> message_of(const ChildProcess& child) {
  std::array<std::int32_t, 2> message = {-1, 0};
  if (child.output().size() >= sizeof message) std::memcpy(message.data(), child.output().data(), sizeof message);
  return message;
}

void throw_if_crashed(const ChildProcess& child) {
  if (child.crashed())
    throw Error("tetgen", "TetGen crashed (" + child.signal_name() +
                              ") on this surface; it probably has nearly intersecting or degenerate triangles");
}

// The self-intersection check and the quality mesh run at the same time, in two processes, so the check adds no wall
// time when a core is free; a surface found intersecting stops the mesh, whose refinement could loop forever on it.
RawMesh run_tetgen(tetgenio& in, const TetrahedralizeOptions& options) {
  ChildProcess diagnose = ChildProcess::spawn("tetgen", [&](int fd) { diagnose_child(fd, in); });
  ChildProcess mesh_run = ChildProcess::spawn("tetgen", [&](int fd) { mesh_child(fd, in, options); });
  while (diagnose.fd() >= 0 || mesh_run.fd() >= 0) {
    std::array<pollfd, 2> watch = {pollfd{diagnose.fd(), POLLIN, 0}, pollfd{mesh_run.fd(), POLLIN, 0}};
    if (::poll(watch.data(), watch.size(), -1) < 0) {
      if (errno == EINTR) continue;
      diagnose.kill();  // cannot wait on the pipes: stop both rather than wait for them blindly
      mesh_run.kill();
      break;
    }
    if (diagnose.fd() >= 0 && watch[0].revents != 0 && !diagnose.read_some() && message_of(diagnose)[0] != kOk) {
      mesh_run.kill();  // the surface is bad (or the check failed): the mesh is not wanted
      break;
    }
    if (mesh_run.fd() >= 0 && watch[1].revents != 0) mesh_run.read_some();
  }
  diagnose.reap();
  mesh_run.reap();

  throw_if_crashed(diagnose);
  const auto check = message_of(diagnose);
  if (check[0] == kSelfIntersecting) throw SelfIntersectingSurface(check[1]);
  if (check[0] == kFailed) throw Error("tetgen", tetgen_failure(check[1]));
  if (check[0] != kOk) throw Error("tetgen", "TetGen's self-intersection check ended without a result");
  throw_if_crashed(mesh_run);
  const auto message = message_of(mesh_run);
  if (message[0] == kFailed) throw Error("tetgen", tetgen_failure(message[1]));
  RawMesh mesh;
  size_t at = sizeof message;
  if (message[0] != kOk || !read_array(mesh_run.output(), at, mesh.points) ||
      !read_array(mesh_run.output(), at, mesh.tets) || !read_array(mesh_run.output(), at, mesh.faces) ||
      !read_array(mesh_run.output(), at, mesh.markers) || mesh.faces.size() != 3 * mesh.markers.size())
    throw Error("tetgen", "TetGen's process ended without a result");
  return mesh;
}

}  // namespace

double predicted_tet_count(double volume, const TetrahedralizeOptions& options) {
  const double regular = std::pow(options.target_edge_length, 3) / (6.0 * std::sqrt(2.0));
  return kTetsPerRegularVolume * volume / regular;
}

double edge_length_for_tet_count(double volume, double tets, const TetrahedralizeOptions&) {
  return std::cbrt(kTetsPerRegularVolume * volume * 6.0 * std::sqrt(2.0) / tets);
}

double enclosed_volume(const SurfaceMesh& s) {
  double six_v = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    six_v += a.dot(b.cross(c));
  }
  return six_v / 6;
}

double max_tets_for_memory() {
  const double bytes = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGESIZE));
  return bytes / kPipelineBytesPerTet;
}

TetrahedralizeResult tetrahedralize(const SurfaceMesh& surface, const TetrahedralizeOptions& options) {
  if (!(options.target_edge_length > 0) || !std::isfinite(options.target_edge_length))
    throw Error("tetgen", "the target edge length must be a positive number of millimetres");
  check_closed(surface);
  check_tet_budget(surface, options);

  // Only the vertices the faces use go to TetGen: an unused one would become an isolated interior/exterior point.
  std::vector<int> to_tetgen(surface.V.rows(), -1);
  std::vector<int> used;
  for (int f = 0; f < surface.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (to_tetgen[surface.F(f, k)] < 0) {
        to_tetgen[surface.F(f, k)] = static_cast<int>(used.size());
        used.push_back(surface.F(f, k));
      }

  tetgenio in;  // owns (and frees) every array we hand it
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(used.size());
  in.pointlist = new REAL[3 * used.size()];
  for (size_t i = 0; i < used.size(); ++i)
    for (int d = 0; d < 3; ++d) in.pointlist[3 * i + d] = surface.V(used[i], d);
  in.numberoffacets = static_cast<int>(surface.F.rows());
  in.facetlist = new tetgenio::facet[in.numberoffacets];
  in.facetmarkerlist = new int[in.numberoffacets];
  for (int f = 0; f < in.numberoffacets; ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&facet.polygonlist[0]);
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k) facet.polygonlist[0].vertexlist[k] = to_tetgen[surface.F(f, k)];
    in.facetmarkerlist[f] = surface.labels.size() ? surface.labels(f) : 0;
  }

  const RawMesh out = run_tetgen(in, options);
  if (out.tets.empty())
    throw Error("tetgen", "TetGen produced no tetrahedra (is the surface closed and non-degenerate?)");

  const int num_points = static_cast<int>(out.points.size() / 3), num_tets = static_cast<int>(out.tets.size() / 4);
  Eigen::MatrixXd V(num_points, 3);
  for (int i = 0; i < num_points; ++i)
    for (int d = 0; d < 3; ++d) V(i, d) = out.points[3 * i + d];
  Eigen::MatrixXi T(num_tets, 4);
  for (int t = 0; t < num_tets; ++t) {
    for (int k = 0; k < 4; ++k) T(t, k) = out.tets[4 * t + k];
    for (int k = 0; k < 4; ++k)
      if (T(t, k) < 0 || T(t, k) >= num_points) throw Error("tetgen", "TetGen returned an invalid tetrahedron");
    if (signed_volume(V, T(t, 0), T(t, 1), T(t, 2), T(t, 3)) < 0) std::swap(T(t, 2), T(t, 3));
  }

  // Drop vertices no tet uses (TetGen may keep jettisoned or duplicate input points).
  std::vector<int> new_index(V.rows(), -1);
  int nv = 0;
  for (int t = 0; t < T.rows(); ++t)
    for (int k = 0; k < 4; ++k)
      if (new_index[T(t, k)] < 0) new_index[T(t, k)] = nv++;
  Eigen::MatrixXd Vc(nv, 3);
  for (int i = 0; i < V.rows(); ++i)
    if (new_index[i] >= 0) Vc.row(new_index[i]) = V.row(i);
  for (int t = 0; t < T.rows(); ++t)
    for (int k = 0; k < 4; ++k) T(t, k) = new_index[T(t, k)];

  // Labels of TetGen's boundary subfaces, by vertex triple.
  std::map<FaceKey, int> subface_label;
  for (size_t f = 0; f < out.markers.size(); ++f) {
    int corner[3];
    for (int k = 0; k < 3; ++k) {
      const int v = out.faces[3 * f + k];
      corner[k] = v >= 0 && v < num_points ? new_index[v] : -1;
    }
    if (corner[0] < 0 || corner[1] < 0 || corner[2] < 0) continue;
    subface_label[sorted_key(corner[0], corner[1], corner[2])] = out.markers[f];
  }

  // Boundary faces (tet faces used once, oriented out of the mesh) with the label of TetGen's subface on each.
  const BoundaryFaces boundary = boundary_faces(T);
  std::vector<int> labels(static_cast<size_t>(boundary.F.rows()), 0);
  for (Eigen::Index f = 0; f < boundary.F.rows(); ++f) {
    const auto it = subface_label.find(sorted_key(boundary.F(f, 0), boundary.F(f, 1), boundary.F(f, 2)));
    if (it != subface_label.end()) labels[static_cast<size_t>(f)] = it->second;
  }

  TetrahedralizeResult result;
  result.mesh = VolumeMesh::from_tets(Vc, T);
  result.boundary_faces = boundary.F;
  result.boundary_labels = Eigen::Map<const Eigen::VectorXi>(labels.data(), static_cast<Eigen::Index>(labels.size()));
  return result;
}

TetrahedralizeResult tetrahedralize_with_sides(const SurfaceMesh& surface, const TetrahedralizeOptions& options) {
  TetrahedralizeResult r = tetrahedralize(surface, options);
  Eigen::VectorXi mask =
      side_mask_from_faces(r.mesh.num_vertices(), r.boundary_faces, (r.boundary_labels.array() - 1).matrix());
  clear_opposite_sides(mask);
  r.mesh.point_data[kSideMaskArray] = mask.cast<double>();
  return r;
}

}  // namespace facehex

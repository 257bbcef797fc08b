#include "core/mapping/transfer_pipeline.h"

#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "core/fields/fold_location.h"
#include "core/mapping/param_locator.h"
#include "core/mesh/cell_rings.h"
#include "core/mesh/corner_jacobian.h"
#include "core/mesh/sides.h"
#include "core/shape/corner_energy.h"
#include "core/util/error.h"
#include "core/util/stopwatch.h"

namespace facehex {
namespace {

// Vertex rings about a cut within which folds count as lying against it (fold_location.h): a few cells, the reach of
// a cut that runs close along a bone surface or over thin tissue.
constexpr int kFoldRings = 4;

std::string health_problem(const ParamHealth& h) {
  return std::to_string(h.inverted) + " of " + std::to_string(h.tets) + " parametric tets are inverted and " +
         std::to_string(h.degenerate - h.flat_by_constraint) +
         " degenerate (the fields fold); check the constraint set (sides, feature values) of this model";
}

// The untangler moves mapped standard vertices through their (u, v, w) and places them with the patient map: a
// coordinate pinned in the standard (a shape end: on the patient's boundary; a feature value: on its feature surface)
// stays pinned, so those vertices stay exactly on their side or feature.
VertexPlacement parametric_placement(const TransferRun& run, const PatientMap& patient, int hex_vertices) {
  VertexPlacement placement;
  placement.p = hex_vertex_uvw(run, hex_vertices);
  placement.movable.assign(hex_vertices, Eigen::Matrix3d::Identity());
  for (int v = 0; v < hex_vertices; ++v)
    for (int f = 0; f < 3; ++f)
      if (run.standard.fixed(v, f)) placement.movable[v](f, f) = 0;
  auto hints = std::make_shared<Eigen::VectorXi>(run.transfer.tet);
  placement.place = [&patient, hints](int v, const Eigen::Vector3d& q, Eigen::Vector3d& x, Eigen::Matrix3d& dxdq) {
    if ((q.array() < 0).any() || (q.array() > 1).any()) return false;  // outside the common domain
    const PatientMap::Placement p = patient.place(q, (*hints)(v));
    if (p.violation > 0) return false;
    (*hints)(v) = p.tet;
    x = p.x;
    dxdq = patient.jacobian(p.tet);
    return true;
  };
  return placement;
}

// True if coordinate f of standard vertex v is pinned to a shape end (0 or 1): the vertex lies on that side.
bool pinned_to_side(const TransferRun& run, const Eigen::MatrixXd& uvw, int v, int f) {
  return run.standard.fixed(v, f) && (uvw(v, f) == 0.0 || uvw(v, f) == 1.0);
}

// The last resort's placement: the vertices not fixed move in space, a vertex on a side only along that side's tangent
// plane (normal: the gradient of the side's field in the patient tet the vertex was placed in), so it stays on the
// patient's surface to first order; on two sides it slides along their common edge. uvw: the standard's hex vertex
// parameters.
VertexPlacement sliding_placement(const TransferRun& run, const PatientMap& patient, const Eigen::MatrixXd& uvw,
                                  const std::vector<char>& fixed) {
  VertexPlacement placement = spatial_placement(run.patient_hex.V, fixed);
  for (int v = 0; v < static_cast<int>(fixed.size()); ++v) {
    if (fixed[v]) continue;
    const Eigen::Matrix3d gradients = patient.jacobian(run.transfer.tet(v)).inverse();  // rows: grad u, v, w
    Eigen::MatrixXd normals(3, 0);
    for (int f = 0; f < 3; ++f)
      if (pinned_to_side(run, uvw, v, f)) {
        normals.conservativeResize(3, normals.cols() + 1);
        normals.col(normals.cols() - 1) = gradients.row(f).transpose();
      }
    if (normals.cols() == 0) continue;
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(normals);
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(3, normals.cols());
    placement.movable[v] = Eigen::Matrix3d::Identity() - Q * Q.transpose();
  }
  return placement;
}

// Bounds a spatial placement's moves: each vertex stays within twice the mean length of its edges in `sizes` (the
// standard: its cells have the sizes the mapped mesh should have, which a fold's stretched cells do not) of where it
// is in `mesh` now. A side vertex steps along its side's tangent plane and leaves the curved side by about the square
// of the distance over the side's radius: over a pass's many sweeps, an unbounded drift would carry it out of the
// patient.
void bound_reach(VertexPlacement& placement, const VolumeMesh& mesh, const VolumeMesh& sizes) {
  constexpr double kEdges = 2;
  const int nv = mesh.num_vertices();
  Eigen::VectorXd length = Eigen::VectorXd::Zero(nv), edges = Eigen::VectorXd::Zero(nv);
  for (int c = 0; c < mesh.num_cells(); ++c)
    for (int k = 0; k < node_count(mesh.types[c]); ++k) {
      const auto& n = corner_nodes(mesh.types[c], k);
      const int v = mesh.C(c, n[0]);
      for (int j = 1; j < 4; ++j) {
        length(v) += (sizes.V.row(mesh.C(c, n[j])) - sizes.V.row(v)).norm();
        edges(v) += 1;
      }
    }
  const Eigen::VectorXd reach = kEdges * length.cwiseQuotient(edges.cwiseMax(1));
  auto start = std::make_shared<const Eigen::MatrixXd>(mesh.V);
  placement.place = [inner = placement.place, start, reach](int v, const Eigen::Vector3d& q, Eigen::Vector3d& x,
                                                            Eigen::Matrix3d& dxdq) {
    return (q - start->row(v).transpose()).norm() <= reach(v) && inner(v, q, x, dxdq);
  };
}

// Moves each free vertex to the mean of the other nodes of its cells, ten times: a collapsed cluster of vertices
// (a fold the local untangling steps cannot open one vertex at a time) is spread out before the last passes.
void spread_free_vertices(VolumeMesh& mesh, const std::vector<char>& fixed) {
  for (int iteration = 0; iteration < 10; ++iteration) {
    Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(mesh.num_vertices(), 3);
    Eigen::VectorXd count = Eigen::VectorXd::Zero(mesh.num_vertices());
    for (int c = 0; c < mesh.num_cells(); ++c)
      for (int i = 0; i < node_count(mesh.types[c]); ++i) {
        const int v = mesh.C(c, i);
        if (fixed[v]) continue;
        for (int j = 0; j < node_count(mesh.types[c]); ++j)
          if (j != i) {
            sum.row(v) += mesh.V.row(mesh.C(c, j));
            ++count(v);
          }
      }
    for (int v = 0; v < mesh.num_vertices(); ++v)
      if (!fixed[v] && count(v) > 0) mesh.V.row(v) = sum.row(v) / count(v);
  }
}

}  // namespace

TransferRun run_transfer(const VolumeMesh& standard, const TetDomain& domain, const ConstraintSet& standard_constraints,
                         const std::string& standard_source, const VolumeMesh& patient,
                         const ConstraintSet& patient_constraints, const std::string& patient_source,
                         const TransferOptions& options, const ProgressCallback& progress,
                         const ModelParameterization* standard_parameterization,
                         const SideConditions* side_conditions) {
  TransferRun run;
  Stopwatch clock;
  if (domain.hex_vertices != standard.num_vertices() ||
      (domain.V.topRows(domain.hex_vertices) - standard.V).cwiseAbs().maxCoeff() > 0)
    throw Error(standard_source, "the parameterization domain was not built from this standard mesh");
  run.standard_domain = domain.description;
  run.standard_domain_non_positive = domain.non_positive_tets;
  run.standard_relaxed_corner_vertices = domain.relaxed_corner_vertices;
  if (standard_parameterization) {
    if (standard_parameterization->V.rows() != domain.V.rows() ||
        standard_parameterization->T.rows() != domain.T.rows())
      throw Error(standard_source, "the given parameterization was not made on this standard's domain");
    run.standard = *standard_parameterization;
    run.standard_parameterization_source = "given";
  } else {
    run.standard = parameterize_model(domain.V, domain.T, domain.side_mask, standard_constraints, standard_source,
                                      options.fields, sub_progress(progress, 0.0, 0.2));
  }
  if (side_conditions)  // the relaxation and the repair hold what the standard's fixed flags pin
    for (Eigen::Index v = 0; v < static_cast<Eigen::Index>(side_conditions->held.size()); ++v)
      if (side_conditions->held[static_cast<size_t>(v)]) run.standard.fixed(v, 0) = run.standard.fixed(v, 1) = 1;
  run.seconds["standard_parameterization"] = clock.lap();
  run.patient = parameterize_model(patient.V, patient.tets(), side_mask_of(patient), patient_constraints,
                                   patient_source, options.fields, sub_progress(progress, 0.2, 0.6),
                                   side_conditions ? &side_conditions->fields : nullptr);
  run.seconds["patient_parameterization"] = clock.lap();
  map_parameterized(run, standard, patient_source, options, sub_progress(progress, 0.6, 1.0));
  return run;
}

namespace {

// The patient's parameterization is usable for the mapping: folds within the accepted fraction, the same handedness.
void check_patient_parameterization(const TransferRun& run, const std::string& patient_source,
                                    const TransferOptions& options) {
  const ParamHealth& health = run.patient.health;
  const int folded = health.inverted + health.degenerate - health.flat_by_constraint;
  if (!options.allow_inverted_parameterization && folded > options.max_inverted_fraction * health.tets)
    throw Error(patient_source, "parameterization: " + health_problem(health) +
                                    fold_location_text(fold_location(
                                        VolumeMesh::from_tets(run.patient.V, run.patient.T), run.patient.fields.uvw,
                                        run.patient.fixed, health.folded_tets, kFoldRings)));
  if (run.standard.health.orientation != run.patient.health.orientation)
    throw Error(patient_source,
                "the model frame has the opposite handedness to the standard's (mirrored scan?): swap the u0 and u1 "
                "sides of its constraint set");
}

// Every vertex of the result lies in the patient's bounding box, up to a twentieth of its diagonal (half of it when
// the polish may move side vertices off the patient in space, as a template's does): the mapping places vertices in
// the patient's tets, and the relaxation and the repair move them by cell sizes; a vertex far outside means a step
// diverged, and such a mesh must not be written as if it were usable.
void check_inside_patient(const TransferRun& run, const std::string& patient_source, const TransferOptions& options) {
  const Eigen::RowVector3d lo = run.patient.V.colwise().minCoeff(), hi = run.patient.V.colwise().maxCoeff();
  const double margin = (options.polish_moves_sides ? 0.5 : 0.05) * (hi - lo).norm();
  int outside = 0;
  double farthest = 0;
  for (Eigen::Index v = 0; v < run.patient_hex.V.rows(); ++v) {
    const Eigen::RowVector3d x = run.patient_hex.V.row(v);
    const double d = std::max((lo - x).maxCoeff(), (x - hi).maxCoeff());
    if (!(d <= margin)) {
      ++outside;
      farthest = std::max(farthest, std::isfinite(d) ? d : std::numeric_limits<double>::infinity());
    }
  }
  if (outside > 0)
    throw Error(patient_source, "the relaxation and repair of folded cells moved " + std::to_string(outside) +
                                    " vertices out of the patient model (up to " +
                                    std::to_string(static_cast<long long>(std::min(farthest, 1e15))) +
                                    " mm beyond its bounding box): they diverged where the parameterization folds (" +
                                    health_problem(run.patient.health) +
                                    "); try --skin-correspondence features or --shape-relaxation off");
}

int unusable_after(const UntangleReport& r) { return r.inverted_after + r.degenerate_after; }

// A cell's shape as Verdict measures a hex's: the smallest mean ratio of its corners against the ideal cell's,
// (sigma)^(2/3) with sigma the corner's normalized determinant (corner_energy.h); 1 for the ideal cell, 0 when flat.
double cell_shape(CellType type, const CellNodes& X) {
  double sigma = 1;
  for (int k = 0; k < node_count(type); ++k)
    sigma = std::min(sigma, normalized_determinant(corner_jacobian(type, X, k) * ideal_corner_inverse(type, k)));
  return sigma > 0 ? std::cbrt(sigma * sigma) : 0;
}

// The repair of the cells the mapping and the relaxation left unusable (inverted or flat) or below their bound, in
// passes that give the untangler more room each time (Repair::run). Its report accumulates in run.untangle.
class Repair {
 public:
  Repair(TransferRun& run, const VolumeMesh& standard, const PatientMap& patient_map, const TransferOptions& options,
         UntangleOptions shape, const ProgressCallback& progress)
      : run_(run),
        standard_(standard),
        patient_map_(patient_map),
        options_(options),
        uvw_(hex_vertex_uvw(run, standard.num_vertices())),
        pass_(std::move(shape)),
        progress_(progress) {
    if (pass_.reference_scaled_jacobian.size() == 0) {
      pass_.reference_scaled_jacobian.resize(standard.num_cells());
      for (int c = 0; c < standard.num_cells(); ++c)
        pass_.reference_scaled_jacobian(c) = scaled_jacobian(standard.types[c], cell_nodes(standard, c));
    }
  }

  void run(VertexPlacement& placement) {
    unrepaired_ = run_.patient_hex.V;
    run_.untangle = pass(placement, pass_);
    widen_and_release(placement);
    last_resort(false);
    if (remaining() > 0) last_resort(true);
    return_to_pins();
    polish();
    report_progress(progress_, "", 1.0);
  }

 private:
  int remaining() const { return unusable_after(run_.untangle); }
  // Pinned in all three parameters: where a feature line meets a side or two sides meet one, and the landmarks held
  // where the mapping put them (SideConditions::held). A fold can nearly always be untangled around them, and moving
  // one in space moves the anatomy it marks.
  bool anchored(int v) const { return run_.standard.fixed.row(v).all(); }
  bool on_side(int v) const {
    return pinned_to_side(run_, uvw_, v, 0) || pinned_to_side(run_, uvw_, v, 1) || pinned_to_side(run_, uvw_, v, 2);
  }

  // Progress by passes (at most 1 + 3 + 8 + 1 of them; most runs need a few).
  UntangleReport pass(VertexPlacement& moves, const UntangleOptions& o) {
    report_progress(progress_, "", std::min(1.0, passes_++ / 13.0));
    return untangle(run_.patient_hex, moves, o);
  }

  // The counts that describe the mesh after a pass (run.patient_hex as it then is).
  void set_state(const UntangleReport& state) {
    run_.untangle.inverted_after = state.inverted_after;
    run_.untangle.degenerate_after = state.degenerate_after;
    run_.untangle.bad_after = state.bad_after;
    run_.untangle.min_scaled_jacobian_after = state.min_scaled_jacobian_after;
  }

  void take(const UntangleReport& again) {
    set_state(again);
    run_.untangle.free_vertices = std::max(run_.untangle.free_vertices, again.free_vertices);
    run_.untangle.sweeps += again.sweeps;
    run_.untangle.vertex_steps += again.vertex_steps;
    run_.untangle.stalled_passes += again.stalled_passes;
  }

  // While unusable cells remain: widen the region that may move (a fold may need room beyond two rings; not after the
  // relaxation, which moved every vertex already), then release the feature pins (never the sides) of the vertices of
  // the cells still unusable: where the patient's anatomy squeezes a feature (a flat nose), a valid element matters
  // more than an exact feature line.
  void widen_and_release(VertexPlacement& placement) {
    for (int attempt = options_.shape_relaxation ? 2 : 0; attempt < 3 && remaining() > 0; ++attempt) {
      // The first two passes improved the bad cells around the folds; the later ones finish the untangling.
      pass_.seed_unusable_only = attempt > 0;
      if (attempt < 2) {
        pass_.rings += 2;
      } else {
        for (int c : check_corner_jacobians(run_.patient_hex).unusable())
          for (int i = 0; i < node_count(standard_.types[c]); ++i) {
            const int v = standard_.C(c, i);
            for (int f = 0; f < 3; ++f)
              if (!pinned_to_side(run_, uvw_, v, f)) placement.movable[v](f, f) = 1;
            ++run_.untangle.released_feature_vertices;
          }
      }
      take(pass(placement, pass_));
    }
  }

  // Last resort, in up to eight passes: the vertices of the cells still unusable, and of the cells within 1 to 8
  // rings around them, move in space; side vertices only if they belong to an unusable cell, and along their side
  // (to first order: they may leave it by a little, reported as side_vertex_distance); no vertex further in one pass
  // than twice its edges in the standard (bound_reach). From the third pass on, the
  // free vertices off the sides are first spread out (a collapsed cluster, which one-vertex-at-a-time steps cannot
  // open). From the fifth, all vertices within the rings, side vertices too, move freely (where the standard's side
  // meets a patient side far away, as the inner wall of the standard's nostrils the patient's bone), since a valid
  // element matters more than an exact boundary there. Side vertices are never spread: spreading them too moves
  // many of them by millimetres on a longer face, for no fewer inverted cells. Each spread starts the untangling from
  // another configuration, so a pass can end with more folds than the one before; the best state is kept.
  // Anchored vertices (anchored()) stay where they are unless move_anchors: run() first tries without moving them.
  void last_resort(bool move_anchors) {
    constexpr int kLastResortPasses = 8, kFirstFreePass = 5;
    const int nv = standard_.num_vertices();
    Eigen::MatrixXd best_V = run_.patient_hex.V;
    UntangleReport best = run_.untangle;
    for (int rings = 1; rings <= kLastResortPasses && remaining() > 0; ++rings) {
      const bool free_pass = rings >= kFirstFreePass;
      std::vector<char> in_cell(nv, 0);  // vertices of the unusable cells
      for (int c : check_corner_jacobians(run_.patient_hex).unusable())
        for (int i = 0; i < node_count(standard_.types[c]); ++i) in_cell[standard_.C(c, i)] = 1;
      const std::vector<char> free = within_cell_rings(run_.patient_hex, in_cell, rings);
      // Side vertices move only if they belong to an unusable cell, except in the free passes.
      std::vector<char> fixed(nv);
      int released = 0;
      for (int v = 0; v < nv; ++v) {
        fixed[v] = !free[v] || (!free_pass && on_side(v) && !in_cell[v]) || (!move_anchors && anchored(v));
        released += !fixed[v] && on_side(v);
      }
      run_.untangle.released_side_vertices = std::max(run_.untangle.released_side_vertices, released);
      if (rings >= 3) {
        std::vector<char> kept = fixed;  // side vertices are not spread
        for (int v = 0; v < nv; ++v) kept[v] |= on_side(v);
        spread_free_vertices(run_.patient_hex, kept);
      }
      freed_sides_ |= free_pass;
      VertexPlacement last =
          free_pass ? spatial_placement(run_.patient_hex.V, fixed) : sliding_placement(run_, patient_map_, uvw_, fixed);
      bound_reach(last, run_.patient_hex, standard_);
      pass_.max_sweeps = 2 * options_.untangle_options.max_sweeps;  // few vertices: cheap, and a long way may remain
      take(pass(last, pass_));
      if (remaining() < unusable_after(best)) {
        best_V = run_.patient_hex.V;
        best = run_.untangle;
      }
    }
    if (remaining() > unusable_after(best)) {
      run_.patient_hex.V = best_V;
      set_state(best);
    }
  }

  // Vertices the repair moved off what pins them (a side, a feature line, a landmark held where the mapping put it:
  // the passes after the first release feature pins, the last resort's free passes side pins; a vertex the repair did
  // not move is where the pinned placement put it) step back towards
  // it: towards the patient's point with the vertex's own parameters but for those pinned (which places it exactly
  // on its sides, feature and landmark), as far of the way (all, half, a quarter, an eighth) as keeps every cell
  // around it usable and no cell at or above the relaxation's floor below it. A vertex whose fold is still in the way
  // stays where it is. Three rounds: a vertex that has stepped back can make room for its neighbour.
  void return_to_pins() {
    if (!freed_sides_ && run_.untangle.released_feature_vertices == 0) return;
    constexpr int kRounds = 3;
    constexpr double kOnPins = 1e-6;     // mm
    constexpr double kShapeFloor = 0.3;  // no cell's shape (cell_shape) drops below this, or below its own if lower
    const double floor = relaxation_options(pass_).keep_above;
    const int nv = standard_.num_vertices();
    VolumeMesh& mesh = run_.patient_hex;
    std::vector<std::vector<int>> cells_of(nv);
    for (int c = 0; c < mesh.num_cells(); ++c)
      for (int i = 0; i < node_count(mesh.types[c]); ++i) cells_of[mesh.C(c, i)].push_back(c);
    const ParamLocator in_space(run_.patient.V, run_.patient.T);
    const Eigen::MatrixXd& patient_uvw = run_.patient.fields.uvw;
    for (int round = 0; round < kRounds; ++round) {
      int moved = 0;
      for (int v = 0; v < nv; ++v) {
        if (!run_.standard.fixed.row(v).any() || mesh.V.row(v) == unrepaired_.row(v)) continue;
        const Eigen::Vector3d x = mesh.V.row(v).transpose();
        const ParamLocator::Hit hit = in_space.locate(x);
        if (hit.tet < 0) continue;
        Eigen::Vector3d q = Eigen::Vector3d::Zero();
        for (int k = 0; k < 4; ++k) q += hit.bary(k) * patient_uvw.row(run_.patient.T(hit.tet, k)).transpose();
        for (int f = 0; f < 3; ++f)
          if (run_.standard.fixed(v, f)) q(f) = uvw_(v, f);
        const PatientMap::Placement on = patient_map_.place(q.cwiseMax(0).cwiseMin(1), run_.transfer.tet(v));
        if (on.violation > 0 || (on.x - x).norm() <= kOnPins) continue;
        // What each cell around v may not fall below: its scaled Jacobian and shape where it is, or the floors.
        std::vector<std::pair<double, double>> least;
        for (int c : cells_of[v]) {
          const CellNodes X = cell_nodes(mesh, c);
          least.emplace_back(std::min(scaled_jacobian(mesh.types[c], X), floor),
                             std::min(cell_shape(mesh.types[c], X), kShapeFloor));
        }
        for (const double t : {1.0, 0.5, 0.25, 0.125}) {
          mesh.V.row(v) = (x + t * (on.x - x)).transpose();
          bool kept = true;
          for (size_t i = 0; i < cells_of[v].size() && kept; ++i) {
            const int c = cells_of[v][i];
            const CellNodes X = cell_nodes(mesh, c);
            const CellJacobians j = cell_jacobians(mesh.types[c], X);
            kept = !is_unusable(j) && j.scaled_jacobian >= least[i].first &&
                   cell_shape(mesh.types[c], X) >= least[i].second;
          }
          if (kept) {
            ++moved;
            break;
          }
          mesh.V.row(v) = x.transpose();
        }
      }
      if (moved == 0) break;
    }
  }

  // Polish: cells still below their bound (a cell next to a fold can come out of the untangling nearly flat, valid
  // but useless to a solver) get one more pass in space, their vertices that are on no side and no feature free (all
  // of them with options.polish_moves_sides). Nothing is inverted now, so the energy's regularization is off and its
  // barrier against flat corners whole.
  void polish() {
    if (run_.untangle.bad_after == 0) return;
    std::vector<char> fixed(standard_.num_vertices());
    for (int v = 0; v < standard_.num_vertices(); ++v)
      fixed[v] = !options_.polish_moves_sides && run_.standard.fixed.row(v).any();
    VertexPlacement polish = spatial_placement(run_.patient_hex.V, fixed);
    UntangleOptions last = pass_;
    last.rings = 1;
    last.seed_unusable_only = false;
    take(pass(polish, last));
  }

  TransferRun& run_;
  const VolumeMesh& standard_;
  const PatientMap& patient_map_;
  const TransferOptions& options_;
  const Eigen::MatrixXd uvw_;   // the standard's hex vertex parameters
  Eigen::MatrixXd unrepaired_;  // the vertices as the repair found them
  UntangleOptions pass_;
  ProgressCallback progress_;
  int passes_ = 0;
  bool freed_sides_ = false;  // a last-resort pass moved side vertices in space
};

}  // namespace

void map_parameterized(TransferRun& run, const VolumeMesh& standard, const std::string& patient_source,
                       const TransferOptions& options, const ProgressCallback& progress) {
  Stopwatch clock;
  check_patient_parameterization(run, patient_source, options);
  const PatientMap patient_map(run.patient.V, run.patient.T, run.patient.fields.uvw);
  run.seconds["locator_build"] = clock.lap();
  run.patient_hex = transfer_hex_mesh(standard, hex_vertex_uvw(run, standard.num_vertices()), patient_map,
                                      &run.transfer, sub_progress(progress, 0.0, 0.05));
  run.seconds["mapping"] = clock.lap();
  run.mapped_hex = run.patient_hex;
  // One placement for both steps: its parameters follow the vertices' moves.
  VertexPlacement placement = parametric_placement(run, patient_map, standard.num_vertices());
  // With the relaxation, the repair keeps the standard's shapes too (the same energy), else it aims at ideal cells.
  UntangleOptions shape = options.untangle_options;
  if (options.shape_relaxation) {
    shape.target = options.ideal_cell_targets ? nullptr : &standard;
    shape.target_towards_ideal = options.relaxation_towards_ideal;
    if (options.relaxation_tether > 0) {
      shape.tether = run.mapped_hex.V;
      shape.tether_weight = options.relaxation_tether;
    }
    UntangleOptions relax = relaxation_options(shape);
    relax.progress = sub_progress(progress, 0.05, 0.8, "shape relaxation");
    run.relaxation = untangle(run.patient_hex, placement, relax);
    run.seconds["shape_relaxation"] = clock.lap();
  }
  if (options.repair_folds) {
    Repair(run, standard, patient_map, options, shape,
           sub_progress(progress, options.shape_relaxation ? 0.8 : 0.05, 1.0, "repairing folded cells"))
        .run(placement);
    run.seconds["untangle"] = clock.lap();
  }
  check_inside_patient(run, patient_source, options);
}

Eigen::VectorXd moved_from_mapping(const TransferRun& run) {
  return (run.patient_hex.V - run.mapped_hex.V).rowwise().norm();
}

Eigen::MatrixXd hex_vertex_uvw(const TransferRun& run, int hex_vertices) {
  return run.standard.fields.uvw.topRows(hex_vertices);
}

}  // namespace facehex

#pragma once
// Point location in the parametric image of a tet model (paper 3.4): which tet's image contains a point (u,v,w),
// and with which barycentric coordinates.
//
// A uniform grid over the images' bounding box indexes every non-degenerate parametric tet by its bounding box
// (built once, O(#T)). A query first walks from a hint tet (the previous hit, the paper's neighbour search: mesh
// vertices come in spatially coherent order, so the walk is usually a few steps), and falls back to the grid.
#include <Eigen/Core>
#include <atomic>
#include <vector>

namespace facehex {

class ParamLocator {
 public:
  struct Hit {
    int tet = -1;                                    // -1 when the model has no tet at all
    Eigen::Vector4d bary = Eigen::Vector4d::Zero();  // barycentric coordinates, summing to 1
    double violation = 0;                            // 0 inside; otherwise -min(bary) of the nearest tet found
  };

  // P (#V x 3) parametric coordinates of the vertices, T (#T x 4).
  ParamLocator(const Eigen::MatrixXd& P, const Eigen::MatrixXi& T);

  // Locates q. hint is a tet id to start walking from (or -1). Points outside every tet (numerically outside the
  // image, or in a gap left by inverted tets) get the tet of least violation within a few grid cells.
  Hit locate(const Eigen::Vector3d& q, int hint = -1) const;

  int walk_hits() const { return walk_hits_; }  // statistics: queries answered by walking

 private:
  bool barycentric(int t, const Eigen::Vector3d& q, Eigen::Vector4d& bary) const;
  int cell_index(int i, int j, int k) const { return (k * dims_[1] + j) * dims_[0] + i; }
  Eigen::Vector3i cell_of(const Eigen::Vector3d& q) const;

  const Eigen::MatrixXd& P_;
  const Eigen::MatrixXi& T_;
  Eigen::MatrixXi neighbors_;
  std::vector<char> usable_;  // non-degenerate tets
  Eigen::Vector3d lo_, cell_size_;
  Eigen::Vector3i dims_;
  std::vector<int> cell_start_, cell_tets_;  // CSR: tets overlapping each grid cell
  mutable std::atomic<int> walk_hits_{0};    // atomic: the untangler places vertices from several threads
};

}  // namespace facehex

#ifndef VCG_EXT_QUADRIC_PLACEMENT_H
#define VCG_EXT_QUADRIC_PLACEMENT_H
// Where the vertices of a mesh LOD go: each sample moves to the point nearest,
// in the least-squares sense, to the planes of the input's triangles in its
// region (Garland and Heckbert's quadrics summed over the sample's geodesic
// Voronoi region, area-weighted, as Lindstrom's clustering places its
// representatives). Along directions the planes leave free (a flat region, a
// crease's line) it stays where it is; a region with border edges (edges of one
// triangle) moves only along its borders, never across them. Flat LOD triangles
// then pass through the surface instead of lying under it.
// Cost: O(triangles log triangles) for the boundary edges, O(samples) 3 x 3 SVDs.
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>
#include <vcg/space/point3.h>
#include "triangle_borders.h"

namespace vcg_ext {

/// How a mesh LOD's vertices are placed.
enum class Placement {
  InputVertices = 0,  ///< copies of the input's vertices
  Quadric = 1,        ///< moved to fit the input's triangles of their region (QuadricPlacement)
  Optimized = 2       ///< so moved, then the mesh fitted to the input's points (MeshOptimization)
};

template <class Scalar>
class QuadricPlacement {
 public:
  /// Singular values of a region's quadric below this share of its largest
  /// leave their direction free (where the sample stays).
  static constexpr double kFreeShare = 1e-3;

  /// `pos`: the points; `tri`: triangles over them; `owner`: per point, the rank
  /// of the sample whose region holds it (-1: none); `samples`: the point of
  /// each rank. Returns each sample's placed position, in rank order.
  static std::vector<vcg::Point3<Scalar>> Compute(const std::vector<vcg::Point3<Scalar>>& pos,
                                                  const std::vector<std::array<int, 3>>& tri,
                                                  const std::vector<int>& owner, const std::vector<int>& samples) {
    const size_t k = samples.size();
    std::vector<Eigen::Matrix3d> A(k, Eigen::Matrix3d::Zero());
    std::vector<Eigen::Vector3d> b(k, Eigen::Vector3d::Zero());
    std::vector<Eigen::Matrix3d> across(k, Eigen::Matrix3d::Zero());  // per region: its borders' normals
    auto add = [&](int point, const Eigen::Vector3d& n, double d, double w) {
      const int r = owner[size_t(point)];
      if (r < 0) return;
      A[size_t(r)] += w * n * n.transpose();
      b[size_t(r)] += w * d * n;
    };
    auto at = [&](int i) { return Eigen::Vector3d(double(pos[size_t(i)][0]), double(pos[size_t(i)][1]), double(pos[size_t(i)][2])); };
    // Each triangle's plane, a third of its area to each corner's region.
    for (size_t f = 0; f < tri.size(); ++f) {
      const Eigen::Vector3d a = at(tri[f][0]), c = (at(tri[f][1]) - a).cross(at(tri[f][2]) - a);
      const double twiceArea = c.norm();
      if (!(twiceArea > 0)) continue;
      const Eigen::Vector3d n = c / twiceArea;
      for (int corner = 0; corner < 3; ++corner) add(tri[f][size_t(corner)], n, -n.dot(a), twiceArea / 6);
    }
    // Border edges (in one triangle only): the direction across them, in the plane of the triangle.
    for (const auto& e : TriangleBorders::Edges(tri)) {
      const auto& t = tri[e.face];
      const Eigen::Vector3d along = at(e.v) - at(e.u);
      const Eigen::Vector3d m = along.cross((at(t[1]) - at(t[0])).cross(at(t[2]) - at(t[0])));
      if (m.norm() > 0)
        for (int w : {e.u, e.v})
          if (owner[size_t(w)] >= 0) across[size_t(owner[size_t(w)])] += m.normalized() * m.normalized().transpose();
    }
    std::vector<vcg::Point3<Scalar>> placed(k);
    for (size_t r = 0; r < k; ++r) {
      const Eigen::Vector3d p0 = at(samples[r]);
      // The directions the sample may move in (N): all, or those along every border of its region.
      Eigen::MatrixXd N = Eigen::Matrix3d::Identity();
      if (across[r].trace() > 0) {
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(across[r]);  // eigenvalues ascending
        int free = 0;
        while (free < 3 && eig.eigenvalues()[free] <= 1e-9 * eig.eigenvalues()[2]) ++free;
        N = eig.eigenvectors().leftCols(free);
      }
      Eigen::Vector3d x = p0;
      if (N.cols() > 0 && A[r].norm() > 0) {
        // Minimise (p0 + N z)' A (p0 + N z) + 2 b' (p0 + N z): the least-norm z, directions the
        // planes hardly constrain left out.
        const Eigen::MatrixXd M = N.transpose() * A[r] * N;
        const Eigen::VectorXd rhs = -N.transpose() * (b[r] + A[r] * p0);
        Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
        const Eigen::VectorXd sv = svd.singularValues();
        const double largest = Eigen::JacobiSVD<Eigen::Matrix3d>(A[r]).singularValues()[0];
        Eigen::VectorXd step = svd.matrixU().transpose() * rhs;
        for (Eigen::Index i = 0; i < step.size(); ++i) step[i] = sv[i] > kFreeShare * largest ? step[i] / sv[i] : 0.0;
        x = p0 + N * (svd.matrixV() * step);
      }
      placed[r] = vcg::Point3<Scalar>(Scalar(x[0]), Scalar(x[1]), Scalar(x[2]));
    }
    return placed;
  }
};

}  // namespace vcg_ext
#endif

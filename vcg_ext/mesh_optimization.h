#ifndef VCG_EXT_MESH_OPTIMIZATION_H
#define VCG_EXT_MESH_OPTIMIZATION_H
// A mesh LOD fitted to the input's points, its vertex set fixed (Hoppe et al.,
// Mesh Optimization, SIGGRAPH 1993, without collapses and splits). Each round
// flips the edges whose flip lowers the squared distance to the LOD of the
// input points in the four regions around them, then fits the vertex
// positions by least squares to those points' nearest LOD triangles (the
// input's border points to the LOD's nearest border edge), with a spring on
// every edge and a weak pull to where they were; a border vertex is also held
// to its nearest input border point, as no point lies beyond a border. A
// flip never makes an edge of more than two triangles, never makes a triangle
// facing away from either of the two it replaces, and keeps the orientation; a
// fit never turns a triangle over, nor takes a vertex farther from its region's
// points than they lay from where it started (a vertex that would stays where it was).
// Cost per round: the flips, O(edges x points of four regions x triangles
// around them) per pass; the fit, O(points x triangles around their sample)
// and a sparse Cholesky factorization of a samples x samples system.
#include <Eigen/Sparse>
#include <algorithm>
#include <array>
#include <limits>
#include <utility>
#include <vector>
#include <vcg/space/point3.h>
#include "progress.h"
#include "triangle_borders.h"

namespace vcg_ext {

template <class Scalar>
class MeshOptimization {
 public:
  struct Param {
    int rounds = 2;           ///< flips then fit, this many times
    int flipPasses = 4;       ///< passes over the edges per round, fewer when a pass flips none
    int fitIterations = 3;    ///< nearest triangles found again, positions solved again
    double spring = 1e-2;     ///< weight of an edge's spring against one point's distance
    double anchor = 1e-6;     ///< weight of a vertex's pull to where it was
    double border = 1;        ///< weight of a border vertex's pull to its nearest input border point, as a point's
  };

  /// `pts`: the input's points; `owner`: per point, the rank of the sample
  /// whose region holds it (-1: none); `onBorder`: per point, whether it ends
  /// a border edge of the input's triangles; `normal`: per sample, the surface's
  /// normal there; `pos`: per sample, its position
  /// (replaced by the fitted one); `faces`: triangles over the samples
  /// (replaced by the flipped ones, as many, in the same slots). Throws
  /// Cancelled (leaving both as they were) when `progress` asks to stop.
  static void Compute(const std::vector<vcg::Point3<Scalar>>& pts, const std::vector<int>& owner,
                      const std::vector<char>& onBorder, const std::vector<vcg::Point3<Scalar>>& normal,
                      std::vector<vcg::Point3<Scalar>>& pos, std::vector<std::array<int, 3>>& faces,
                      Progress progress = Progress(nullptr), const Param& p = Param()) {
    if (faces.empty()) return;
    Mesh m(pts, owner, onBorder, normal, pos, faces);
    m.SetReach();
    const size_t steps = size_t(p.rounds) * size_t(p.flipPasses + p.fitIterations);
    size_t step = 0;
    for (int round = 0; round < p.rounds; ++round) {
      std::vector<char> active(pos.size(), 1);  // the fit moved every vertex
      for (int pass = 0; pass < p.flipPasses; ++pass) {
        const size_t flips = m.FlipPass(active);
        progress(++step, steps, "Optimizing the mesh");
        if (flips == 0) {
          step += size_t(p.flipPasses - pass - 1);
          break;
        }
      }
      for (int it = 0; it < p.fitIterations; ++it) {
        m.Fit(p.spring, p.anchor, p.border);
        progress(++step, steps, "Optimizing the mesh");
      }
    }
    for (size_t s = 0; s < pos.size(); ++s)
      pos[s] = vcg::Point3<Scalar>(Scalar(m.x[s][0]), Scalar(m.x[s][1]), Scalar(m.x[s][2]));
    faces = m.faces;
  }

  /// Squared distance from `q` to the triangle (a, b, c), and the
  /// barycentric coordinates of its nearest point (Ericson, Real-Time
  /// Collision Detection, 5.1.5).
  static double Nearest(const Eigen::Vector3d& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c, Eigen::Vector3d* bary = nullptr) {
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = q - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    Eigen::Vector3d w;
    const Eigen::Vector3d bp = q - b, cp = q - c;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp), d5 = ab.dot(cp), d6 = ac.dot(cp);
    const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d1 <= 0 && d2 <= 0) {
      w = {1, 0, 0};
    } else if (d3 >= 0 && d4 <= d3) {
      w = {0, 1, 0};
    } else if (d6 >= 0 && d5 <= d6) {
      w = {0, 0, 1};
    } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
      if (!(d1 - d3 > 0)) return NearestOnEdges(q, {&a, &b, &c}, bary);  // a = b: the tests took a point for an edge
      const double t = d1 / (d1 - d3);
      w = {1 - t, t, 0};
    } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
      if (!(d2 - d6 > 0)) return NearestOnEdges(q, {&a, &b, &c}, bary);  // a = c
      const double t = d2 / (d2 - d6);
      w = {1 - t, 0, t};
    } else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
      if (!((d4 - d3) + (d5 - d6) > 0)) return NearestOnEdges(q, {&a, &b, &c}, bary);  // b = c
      const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      w = {0, 1 - t, t};
    } else {
      const double den = va + vb + vc;
      if (!(den > 0)) return NearestOnEdges(q, {&a, &b, &c}, bary);  // a triangle of no area
      w = {va / den, vb / den, vc / den};
    }
    if (bary) *bary = w;
    return (q - (w[0] * a + w[1] * b + w[2] * c)).squaredNorm();
  }

  /// Nearest over the triangle's three edges as segments (one of length 0: its end).
  static double NearestOnEdges(const Eigen::Vector3d& q, const std::array<const Eigen::Vector3d*, 3>& v,
                               Eigen::Vector3d* bary) {
    double best = std::numeric_limits<double>::infinity();
    Eigen::Vector3d w(1, 0, 0);
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      const Eigen::Vector3d e = *v[size_t(j)] - *v[size_t(i)];
      const double l2 = e.squaredNorm();
      const double t = l2 > 0 ? std::clamp(e.dot(q - *v[size_t(i)]) / l2, 0.0, 1.0) : 0.0;
      const double d = (q - (*v[size_t(i)] + t * e)).squaredNorm();
      if (d < best) {
        best = d;
        w = Eigen::Vector3d::Zero();
        w[i] = 1 - t, w[j] = t;
      }
    }
    if (bary) *bary = w;
    return (q - (w[0] * *v[0] + w[1] * *v[1] + w[2] * *v[2])).squaredNorm();
  }

 private:
  struct Mesh {
    std::vector<Eigen::Vector3d> q;          // the input's points held by a region
    std::vector<char> qBorder;               // per q, whether it is on the input's border
    std::vector<size_t> first;               // sample s holds q[first[s] .. first[s + 1])
    std::vector<Eigen::Vector3d> x;          // per sample, its position
    std::vector<Eigen::Vector3d> up;         // per sample, the surface's normal
    std::vector<std::array<int, 3>> faces;
    std::vector<std::vector<int>> around;    // per sample, its faces
    std::vector<double> reach;               // per sample, how far (squared) from its region's points it may go

    Mesh(const std::vector<vcg::Point3<Scalar>>& pts, const std::vector<int>& owner, const std::vector<char>& onBorder,
         const std::vector<vcg::Point3<Scalar>>& normal, const std::vector<vcg::Point3<Scalar>>& pos,
         const std::vector<std::array<int, 3>>& f)
        : first(pos.size() + 1, 0), faces(f), around(pos.size()) {
      for (size_t i = 0; i < owner.size(); ++i)
        if (owner[i] >= 0) ++first[size_t(owner[i]) + 1];
      for (size_t s = 0; s < pos.size(); ++s) first[s + 1] += first[s];
      q.resize(first.back());
      qBorder.resize(first.back());
      std::vector<size_t> at(first.begin(), first.end() - 1);
      for (size_t i = 0; i < owner.size(); ++i)
        if (owner[i] >= 0) {
          const size_t k = at[size_t(owner[i])]++;
          q[k] = Eigen::Vector3d(pts[i][0], pts[i][1], pts[i][2]);
          qBorder[k] = onBorder[i];
        }
      for (const auto& v : pos) x.emplace_back(v[0], v[1], v[2]);
      for (const auto& v : normal) up.emplace_back(v[0], v[1], v[2]);
      for (size_t t = 0; t < faces.size(); ++t)
        for (int v : faces[t]) around[size_t(v)].push_back(int(t));
    }

    // The squared distance from `y` to the nearest point of sample s's region (infinite: none).
    double ToRegion(size_t s, const Eigen::Vector3d& y) const {
      double best = std::numeric_limits<double>::infinity();
      for (size_t i = first[s]; i < first[s + 1]; ++i) best = std::min(best, (q[i] - y).squaredNorm());
      return best;
    }
    // A vertex may end no farther from its region's points than the farthest
    // of them lay from where it started: the region's own scale (squared; a
    // vertex whose region holds no point is not held).
    void SetReach() {
      reach.assign(x.size(), std::numeric_limits<double>::infinity());
      for (size_t s = 0; s < x.size(); ++s) {
        if (first[s] == first[s + 1]) continue;
        double farthest = 0;
        for (size_t i = first[s]; i < first[s + 1]; ++i) farthest = std::max(farthest, (q[i] - x[s]).squaredNorm());
        reach[s] = farthest;
      }
    }

    double Dist(size_t k, const std::array<int, 3>& t) const {
      return Nearest(q[k], x[size_t(t[0])], x[size_t(t[1])], x[size_t(t[2])]);
    }
    Eigen::Vector3d Normal(int a, int b, int c) const {
      return (x[size_t(b)] - x[size_t(a)]).cross(x[size_t(c)] - x[size_t(a)]);
    }
    bool HasEdge(int a, int b) const {
      for (int t : around[size_t(a)])
        if (faces[size_t(t)][0] == b || faces[size_t(t)][1] == b || faces[size_t(t)][2] == b) return true;
      return false;
    }
    // Whether the triangle faces the way the surface does at its corners (their normals summed).
    bool FacesUp(const std::array<int, 3>& t) const {
      return Normal(t[0], t[1], t[2]).dot(up[size_t(t[0])] + up[size_t(t[1])] + up[size_t(t[2])]) > 0;
    }
    static void Remove(std::vector<int>& list, int t) { list.erase(std::find(list.begin(), list.end(), t)); }

    // One pass over the edges, as they stand at its start, of the triangles
    // at an `active` vertex (whose surroundings changed since they were last
    // weighed); returns the flips made, and the vertices they changed in `active`.
    size_t FlipPass(std::vector<char>& active) {
      std::vector<std::pair<int, int>> edges;
      for (const auto& t : faces)
        if (active[size_t(t[0])] || active[size_t(t[1])] || active[size_t(t[2])])
          for (size_t e = 0; e < 3; ++e)
            edges.emplace_back(std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3]));
      std::fill(active.begin(), active.end(), 0);
      std::sort(edges.begin(), edges.end());
      edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
      size_t flips = 0;
      std::vector<int> shared, others;
      for (const auto& e : edges) {
        shared.clear();
        for (int t : around[size_t(e.first)]) {
          const auto& f = faces[size_t(t)];
          if (f[0] == e.second || f[1] == e.second || f[2] == e.second) shared.push_back(t);
        }
        if (shared.size() != 2) continue;  // a border, or the edge is gone
        // f1 = (a, b, c) and f2 = (b, a, d), consistently oriented.
        const int f1 = shared[0], f2 = shared[1];
        const auto& t1 = faces[size_t(f1)];
        const auto& t2 = faces[size_t(f2)];
        size_t k = 0;
        auto onEdge = [&](int v) { return v == e.first || v == e.second; };
        while (!(onEdge(t1[k]) && onEdge(t1[(k + 1) % 3]))) ++k;
        const int a = t1[k], b = t1[(k + 1) % 3], c = t1[(k + 2) % 3];
        size_t k2 = 0;
        while (k2 < 3 && t2[k2] != b) ++k2;
        if (k2 == 3 || t2[(k2 + 1) % 3] != a) continue;  // orientations disagree
        const int d = t2[(k2 + 2) % 3];
        if (c == d || HasEdge(c, d)) continue;
        const Eigen::Vector3d o1 = Normal(a, b, c), o2 = Normal(b, a, d);
        const Eigen::Vector3d n1 = Normal(a, d, c), n2 = Normal(d, b, c);
        // Each new triangle faces the way both old ones did: else it would turn over (or vanish).
        if (!(n1.dot(o1) > 0 && n1.dot(o2) > 0 && n2.dot(o1) > 0 && n2.dot(o2) > 0)) continue;
        // Nor away from the surface, unless one of the old ones did.
        const std::array<int, 3> abc{a, b, c}, bad{b, a, d}, adc{a, d, c}, dbc{d, b, c};
        if ((!FacesUp(adc) || !FacesUp(dbc)) && FacesUp(abc) && FacesUp(bad)) continue;
        others.clear();
        for (int v : {a, b, c, d})
          for (int t : around[size_t(v)])
            if (t != f1 && t != f2) others.push_back(t);
        std::sort(others.begin(), others.end());
        others.erase(std::unique(others.begin(), others.end()), others.end());
        double now = 0, flipped = 0;
        for (int v : {a, b, c, d})
          for (size_t i = first[size_t(v)]; i < first[size_t(v) + 1]; ++i) {
            const double before = std::min(Dist(i, abc), Dist(i, bad)), after = std::min(Dist(i, adc), Dist(i, dbc));
            // Another triangle as near as both sides weighs the same either way: stop looking there.
            const double enough = std::min(before, after);
            double rest = std::numeric_limits<double>::infinity();
            for (size_t k = 0; k < others.size() && rest > enough; ++k)
              rest = std::min(rest, Dist(i, faces[size_t(others[k])]));
            now += std::min(rest, before);
            flipped += std::min(rest, after);
          }
        if (!(flipped < now * (1 - 1e-9))) continue;
        faces[size_t(f1)] = adc;
        faces[size_t(f2)] = dbc;
        Remove(around[size_t(a)], f2);
        Remove(around[size_t(b)], f1);
        around[size_t(c)].push_back(f2);
        around[size_t(d)].push_back(f1);
        for (int v : {a, b, c, d}) active[size_t(v)] = 1;
        ++flips;
      }
      return flips;
    }

    // Each point's nearest triangle among those of its sample and its
    // sample's neighbours (a border point's nearest border edge among theirs),
    // then the positions that fit those points best.
    void Fit(double spring, double anchor, double border) {
      const size_t n = x.size();
      std::vector<std::vector<std::array<int, 2>>> borderAt(n);  // per sample, the LOD's border edges at it
      for (const auto& e : TriangleBorders::Edges(faces))
        for (int v : {e.u, e.v}) borderAt[size_t(v)].push_back({e.u, e.v});
      std::vector<std::array<int, 2>> nearEdges;
      std::vector<Eigen::Triplet<double>> a;
      Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(Eigen::Index(n), 3);
      std::vector<int> near;
      for (size_t s = 0; s < n; ++s) {
        if (first[s] == first[s + 1]) continue;
        near.clear();
        for (int t : around[s])
          for (int v : faces[size_t(t)]) near.insert(near.end(), around[size_t(v)].begin(), around[size_t(v)].end());
        std::sort(near.begin(), near.end());
        near.erase(std::unique(near.begin(), near.end()), near.end());
        if (near.empty()) continue;
        nearEdges.clear();
        for (int t : around[s])
          for (int v : faces[size_t(t)]) nearEdges.insert(nearEdges.end(), borderAt[size_t(v)].begin(), borderAt[size_t(v)].end());
        for (size_t i = first[s]; i < first[s + 1]; ++i) {
          if (qBorder[i] && !nearEdges.empty()) {  // the LOD's border follows the input's
            double best = std::numeric_limits<double>::infinity(), bestT = 0;
            std::array<int, 2> bestEdge{};
            Eigen::Vector3d w;
            for (const auto& e : nearEdges) {  // the segment as a triangle with two corners at its end
              const double dd = Nearest(q[i], x[size_t(e[0])], x[size_t(e[1])], x[size_t(e[1])], &w);
              if (dd < best) {
                best = dd;
                bestT = 1 - w[0];
                bestEdge = e;
              }
            }
            const double side[2] = {1 - bestT, bestT};
            for (int r = 0; r < 2; ++r) {
              for (int c = 0; c < 2; ++c) a.emplace_back(bestEdge[size_t(r)], bestEdge[size_t(c)], side[r] * side[c]);
              rhs.row(bestEdge[size_t(r)]) += side[r] * q[i].transpose();
            }
            continue;
          }
          double best = std::numeric_limits<double>::infinity();
          int bestFace = -1;
          Eigen::Vector3d w, bestW;
          for (int t : near) {
            const auto& f = faces[size_t(t)];
            const double dd = Nearest(q[i], x[size_t(f[0])], x[size_t(f[1])], x[size_t(f[2])], &w);
            if (dd < best) {
              best = dd;
              bestFace = t;
              bestW = w;
            }
          }
          const auto& f = faces[size_t(bestFace)];
          for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) a.emplace_back(f[size_t(r)], f[size_t(c)], bestW[r] * bestW[c]);
            rhs.row(f[size_t(r)]) += bestW[r] * q[i].transpose();
          }
        }
      }
      // No point lies beyond a border, so nothing above keeps a border vertex from drifting off the
      // surface there: the nearest input border point among its own and its neighbours' regions holds it.
      for (size_t s = 0; s < n; ++s) {
        if (borderAt[s].empty()) continue;
        double best = std::numeric_limits<double>::infinity();
        Eigen::Vector3d nearest;
        for (int t : around[s])
          for (int v : faces[size_t(t)])
            for (size_t i = first[size_t(v)]; i < first[size_t(v) + 1]; ++i)
              if (qBorder[i] && (q[i] - x[s]).squaredNorm() < best) {
                best = (q[i] - x[s]).squaredNorm();
                nearest = q[i];
              }
        if (best == std::numeric_limits<double>::infinity()) continue;  // a border the input does not have
        a.emplace_back(int(s), int(s), border);
        rhs.row(Eigen::Index(s)) += border * nearest.transpose();
      }
      for (const auto& t : faces)
        for (size_t e = 0; e < 3; ++e) {
          // Each interior edge is in two triangles: half its spring from each.
          const int u = t[e], v = t[(e + 1) % 3];
          a.emplace_back(u, u, spring / 2);
          a.emplace_back(v, v, spring / 2);
          a.emplace_back(u, v, -spring / 2);
          a.emplace_back(v, u, -spring / 2);
        }
      for (size_t s = 0; s < n; ++s) {
        a.emplace_back(int(s), int(s), anchor);
        rhs.row(Eigen::Index(s)) += anchor * x[s].transpose();
      }
      Eigen::SparseMatrix<double> m(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
      m.setFromTriplets(a.begin(), a.end());
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(m);
      if (solver.info() != Eigen::Success) return;  // positions stay as they were
      const Eigen::MatrixXd solved = solver.solve(rhs);
      if (solver.info() != Eigen::Success || !solved.allFinite()) return;
      // A vertex moved so far that one of its triangles turns over (against where it faced, or away from the
      // surface where it did not) goes back where it was, until none does.
      std::vector<Eigen::Vector3d> before = x;
      std::vector<char> wasUp(faces.size());
      for (size_t t = 0; t < faces.size(); ++t) wasUp[t] = FacesUp(faces[t]);
      for (size_t s = 0; s < n; ++s) {
        const Eigen::Vector3d y = solved.row(Eigen::Index(s)).transpose();
        // A vertex few points hold (a corner of one triangle, a border's end) can
        // swing far off the surface to tilt its triangles for points near their
        // other edges: it stays where it was.
        if (ToRegion(s, y) <= reach[s]) x[s] = y;
      }
      for (bool turned = true; turned;) {
        turned = false;
        for (size_t k = 0; k < faces.size(); ++k) {
          const auto& t = faces[k];
          const Eigen::Vector3d was =
              (before[size_t(t[1])] - before[size_t(t[0])]).cross(before[size_t(t[2])] - before[size_t(t[0])]);
          if (Normal(t[0], t[1], t[2]).dot(was) > 0 && (FacesUp(t) || !wasUp[k])) continue;
          for (int v : t)
            if (x[size_t(v)] != before[size_t(v)]) {
              x[size_t(v)] = before[size_t(v)];
              turned = true;
            }
        }
      }
    }
  };
};

}  // namespace vcg_ext
#endif

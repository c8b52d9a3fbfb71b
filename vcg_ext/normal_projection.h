#ifndef VCG_EXT_NORMAL_PROJECTION_H
#define VCG_EXT_NORMAL_PROJECTION_H
// An error measure between a point set and a surface: for each point p_i with
// normal n_i, the distance from p_i to where the line <p_i, n_i> meets a
// surface. vcglib's uniform grid and its ray walk find the crossings.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>
#include <vcg/space/index/grid_static_ptr.h>
#include <vcg/space/intersection3.h>
#include <vcg/space/ray3.h>
#include "point_normals.h"
#include "point_set.h"
#include "progress.h"

namespace vcg_ext {

template <class MeshType>
class NormalProjection {
 public:
  typedef typename MeshType::ScalarType Scalar;
  typedef vcg::Point3<Scalar> Coord;
  struct Param {
    double maxDistance = 0;  ///< farther crossings count as misses; > 0
  };
  struct Result {
    size_t pointNum = 0;       ///< reference points with a valid normal, measured
    size_t noNormal = 0;       ///< reference points skipped: zero or non-finite normal
    size_t hitNum = 0;         ///< points whose line meets the surface within maxDistance
    double min = 0, mean = 0, rms = 0, max = 0;  ///< over the hits
    double missFraction() const { return pointNum ? double(pointNum - hitNum) / double(pointNum) : 0.0; }
    std::vector<double> distance;  ///< per reference vertex (m.vert order): the distance, NaN if skipped or missed
  };

  /// Neither mesh is modified. Throws std::invalid_argument for a reference
  /// without normals or a surface without triangles.
  static Result Compute(const MeshType& reference, const MeshType& surface, const Param& p,
                        vcg::CallBackPos* cb = nullptr) {
    Progress progress(cb);
    if (!(p.maxDistance > 0) || !std::isfinite(p.maxDistance))
      throw InputError(Field::MaxDistance, "must be a positive number (got " + Shown(p.maxDistance) + ")");
    // Finite coordinates in a finite box, or the grid's cells cannot be computed.
    for (const auto* layer : {&reference, &surface}) {
      try {
        FiniteBox(PointSetFromMesh<MeshType>::Compute(*layer));
      } catch (const InputError& e) {
        throw InputError(layer == &surface ? Field::Surface : Field::ReferencePoints, e.what());
      }
    }
    std::vector<Tri> tris;
    for (const auto& f : surface.face)  // live faces of live vertices, as the samplers take them
      if (!f.IsD() && !f.cV(0)->IsD() && !f.cV(1)->IsD() && !f.cV(2)->IsD())
        tris.push_back(Tri{{f.cP(0), f.cP(1), f.cP(2)}});
    if (tris.empty()) throw InputError(Field::Surface, "holds no triangles to project onto");
    // vcglib's grid computes its cells in the layer's units and overflows near
    // the ends of the float range: it is built on coordinates centred on the
    // triangles' box and scaled to its diagonal, and distances are scaled back.
    vcg::Box3d box;
    for (const Tri& t : tris)
      for (const Coord& c : t.p) box.Add(vcg::Point3d::Construct(c));
    if (!(box.Diag() > 0))
      throw InputError(Field::Surface, "holds triangles that all lie at one point: there is no surface to project onto");
    const vcg::Point3d centre = box.Center();
    const double scale = box.Diag();
    auto local = [&](const Coord& q) { return (vcg::Point3d::Construct(q) - centre) / scale; };
    for (Tri& t : tris)
      for (Coord& c : t.p) c = Coord::Construct(local(c));
    vcg::GridStaticPtr<Tri, Scalar> grid;
    grid.Set(tris.begin(), tris.end());

    Result r;
    r.distance.assign(reference.vert.size(), std::numeric_limits<double>::quiet_NaN());
    r.min = std::numeric_limits<double>::infinity();
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < reference.vert.size(); ++i) {
      const auto& v = reference.vert[i];
      if (v.IsD()) continue;
      if (!PointNormals<Scalar>::IsValid(v.cN())) {
        ++r.noNormal;
        continue;
      }
      ++r.pointNum;
      // The line, not a ray: the surface may lie on either side of the point.
      const Coord n = v.cN() / v.cN().Norm();
      // A point a million surface sizes away cannot aim its line at the surface in float: a miss.
      const vcg::Point3d o = local(v.cP());
      if (!(o.Norm() < 1e6)) continue;
      // Every crossing lies inside the box, within |o| + 1/2 of the point.
      const double reach = std::min(p.maxDistance / scale, o.Norm() + 1);
      const double t = scale * std::min(Cross(grid, Coord::Construct(o), n, reach), Cross(grid, Coord::Construct(o), -n, reach));
      if (!(t <= p.maxDistance)) continue;
      r.distance[i] = t;
      ++r.hitNum;
      r.min = std::min(r.min, t);
      r.max = std::max(r.max, t);
      sum += t;
      sum2 += t * t;
      if ((i & 4095) == 0) progress(i, reference.vert.size(), "Normal projection deviation");
    }
    if (r.pointNum == 0)
      throw InputError(Field::ReferencePoints, "holds no points with valid normals (compute normals first)");
    if (r.hitNum) {
      r.mean = sum / double(r.hitNum);
      r.rms = std::sqrt(sum2 / double(r.hitNum));
    } else {
      r.min = 0;
    }
    return r;
  }

 private:
  // A live triangle of the surface, as vcglib's grid and ray functor read it.
  struct Tri {
    typedef typename MeshType::ScalarType ScalarType;
    Coord p[3];
    const Coord& cP(int k) const { return p[k]; }
    void GetBBox(vcg::Box3<Scalar>& b) const {
      b.Set(p[0]);
      b.Add(p[1]);
      b.Add(p[2]);
    }
    bool IsD() const { return false; }
  };
  // Each triangle is tested once per cell it spans; re-testing is harmless.
  struct NoMark {
    void UnMarkAll() const {}
    bool IsMarked(const Tri*) const { return false; }
    void Mark(const Tri*) const {}
  };

  // Line-triangle crossing (Moeller-Trumbore, either face, in double) for the
  // grid's ray walk. vcglib's own test calls a line parallel when the
  // determinant is below an absolute 1e-6, which rejects every triangle
  // shorter than about 1e-3 units (a scan in metres): here "parallel" is
  // relative to the triangle's size. A tiny margin on the barycentric bounds
  // keeps a line through a shared edge or corner from slipping between
  // neighbouring triangles by rounding.
  struct LineHit {
    template <class S>
    bool operator()(const Tri& f, const vcg::Ray3<S>& ray, S& t) const {
      const vcg::Point3d o = vcg::Point3d::Construct(ray.Origin()), d = vcg::Point3d::Construct(ray.Direction());
      const vcg::Point3d v0 = vcg::Point3d::Construct(f.p[0]);
      const vcg::Point3d e1 = vcg::Point3d::Construct(f.p[1]) - v0, e2 = vcg::Point3d::Construct(f.p[2]) - v0;
      const vcg::Point3d pv = d ^ e2;
      const double det = e1 * pv;
      if (!(std::abs(det) > 1e-12 * e1.Norm() * e2.Norm())) return false;  // parallel, or a degenerate triangle
      const double inv = 1.0 / det, eps = 1e-9;
      const vcg::Point3d tv = o - v0, qv = tv ^ e1;
      const double u = (tv * pv) * inv, v = (d * qv) * inv, hit = (e2 * qv) * inv;
      if (u < -eps || v < -eps || u + v > 1 + eps || hit < 0) return false;
      t = S(hit);
      return true;
    }
  };

  // Distance along the unit direction d to the first crossing, +inf if none within maxDist.
  static double Cross(vcg::GridStaticPtr<Tri, Scalar>& grid, const Coord& o, const Coord& d, double maxDist) {
    LineHit hit;
    NoMark mark;
    Scalar t = 0;
    const vcg::Ray3<Scalar> ray(o, d);
    const Tri* f = grid.DoRay(hit, mark, ray, Scalar(maxDist), t);
    return f ? double(t) : std::numeric_limits<double>::infinity();
  }
};

}  // namespace vcg_ext
#endif

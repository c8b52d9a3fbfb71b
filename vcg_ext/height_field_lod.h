#ifndef VCG_EXT_HEIGHT_FIELD_LOD_H
#define VCG_EXT_HEIGHT_FIELD_LOD_H
// Height-field LODs: error-driven greedy insertion (Garland and Heckbert, Fast
// Polygonal Approximation of Terrains and Height Fields, 1995) under a
// Poisson-disk constraint in x, y. Each new sample is the point farthest, in
// height, from the Delaunay TIN of the samples so far (farthest-point sampling
// with the approximation error as the distance), among the points at least
// r(k) = beta sqrt(hull area / k) from every sample.
//
// Costs O(n log n) expected for n points (each insertion re-examines the points
// of the triangles it replaces), and O(n) memory beside the TIN.
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Convex_hull_traits_adapter_2.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>
#include "input_error.h"
#include "progress.h"

namespace vcg_ext {

/// Nested LODs of a height field (a DEM's nodes, an airborne cloud): the
/// samples in insertion order, so the first k are the k-sample LOD for every k
/// from the hull size up. Every sample is an input point; each after the hull's
/// corners is at least r(k) from the samples before it in x, y (k: its rank + 1;
/// hence in 3D and in any metric at least the Euclidean one), so the first k are
/// r(k)-separated but for pairs of corners; the TIN of the first k is a Delaunay
/// triangulation of them in x, y.
/// Ties go to the smaller index: the result depends on the input order only
/// through ties.
class HeightFieldLod {
 public:
  struct Param {
    size_t sampleNum = 0;  ///< exact number of samples: the hull's corners up to the distinct x, y
    /// beta: the first k samples are beta sqrt(A / k) apart in x, y (A: the area
    /// of the hull); 0 is plain greedy insertion. Below 1/sqrt(pi) the disks
    /// cannot cover the hull, so the constraint never stops the sampler. The
    /// default keeps the largest error lowest against greedy insertion's on the
    /// tuning windows, the RMS within 1% of its (bench/separation_rule.py).
    double separation = 0.1;
    /// The disks in x, y, z (a cliff's top and foot may both be samples); else in x, y.
    bool inHeight = true;
  };
  struct Result {
    std::vector<int> samples;  ///< input indices: the hull's corners, then in insertion order
    /// Per sample: its height above or below the TIN of the samples before it
    /// (0 for the hull's corners), the error the insertion removed.
    std::vector<double> error;
    /// The TIN of all samples: indices into samples, counter-clockwise in x, y.
    std::vector<std::array<int, 3>> triangles;
    size_t hullSize = 0;
    double area = 0;  ///< of the hull in x, y
    /// The samples up to this many keep their disks; it is samples.size()
    /// unless the points cover too little of their hull to hold that many disks
    /// (then the rest go by error alone).
    size_t separatedPrefix = 0;
  };

  /// `xyz`: n points, x, y, z each. Throws InputError for a count out of range,
  /// non-finite coordinates or points on one line in x, y; Cancelled on a stop.
  template <class Scalar>
  static Result Compute(const Scalar* xyz, size_t n, const Param& p, Progress progress = Progress(nullptr)) {
    Sampler s(xyz, n, p);
    return s.Run(progress);
  }

  /// Of a triangle mesh's area projected on x, y, the share whose triangles
  /// face the minority way along z: 0 for a height field's surface wound one
  /// way, either way; 1/2 for a closed one (a vertical line crosses it going in
  /// as often as out). Walls add nearly nothing: their projection is thin.
  /// Triangles wound against their neighbours count as facing down. Costs
  /// O(faces). Over the live faces of a vcglib mesh:
  template <class MeshType>
  static double DownwardShare(const MeshType& m) {
    Facing facing;
    for (const auto& f : m.face)
      if (!f.IsD()) facing.Add(f.cP(0), f.cP(1), f.cP(2));
    return facing.Share();
  }
  /// The same over `xyz` (x, y, z each) and index triples into it.
  template <class Scalar>
  static double DownwardShare(const Scalar* xyz, const std::vector<std::array<int, 3>>& triangles) {
    Facing facing;
    for (const auto& t : triangles) facing.Add(xyz + 3 * size_t(t[0]), xyz + 3 * size_t(t[1]), xyz + 3 * size_t(t[2]));
    return facing.Share();
  }
  /// Above this DownwardShare a front end tells its user the surface is no
  /// height field: a DEM's grid has none, a city's walls and overhangs little.
  static constexpr double kNoHeightFieldAbove = 0.01;

  /// The Delaunay TIN in x, y of the points `subset` (indices into xyz), as
  /// indices into subset, counter-clockwise: the TIN of a prefix of samples.
  template <class Scalar>
  static std::vector<std::array<int, 3>> Triangulate(const Scalar* xyz, const std::vector<int>& subset) {
    std::vector<std::pair<Point, int>> pts;
    pts.reserve(subset.size());
    for (size_t r = 0; r < subset.size(); ++r)
      pts.emplace_back(Point(xyz[3 * size_t(subset[r])], xyz[3 * size_t(subset[r]) + 1]), int(r));
    DT dt(pts.begin(), pts.end());
    return TrianglesOf(dt);
  }

 private:
  /// The projected area on x, y of triangles facing up and down.
  struct Facing {
    double up = 0, down = 0;
    template <class P>
    void Add(const P& a, const P& b, const P& c) {
      // z of the cross product: twice the signed area of the triangle's projection
      const double z = (double(b[0]) - a[0]) * (double(c[1]) - a[1]) - (double(b[1]) - a[1]) * (double(c[0]) - a[0]);
      (z > 0 ? up : down) += std::abs(z);
    }
    double Share() const { return up + down > 0 ? std::min(up, down) / (up + down) : 0; }
  };

  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Point = K::Point_2;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;  // the vertex's index
  using Fb = CGAL::Triangulation_face_base_with_info_2<int, K>;    // its Record, -1 for none
  using DT = CGAL::Delaunay_triangulation_2<K, CGAL::Triangulation_data_structure_2<Vb, Fb>>;
  using Face = DT::Face_handle;

  static std::vector<std::array<int, 3>> TrianglesOf(const DT& dt) {
    std::vector<std::array<int, 3>> t;
    t.reserve(dt.number_of_faces());
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
      t.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    return t;
  }

  /// The points a TIN triangle holds, not yet samples, and its worst eligible one.
  struct Record {
    std::vector<int> points;
    double z0 = 0, gx = 0, gy = 0, x0 = 0, y0 = 0;  // the triangle's plane z0 + gx (x - x0) + gy (y - y0)
    int best = -1;
    double err = -1;
    uint32_t version = 0;
    bool alive = true;
  };
  struct Candidate {
    double err;
    int point;
    int record;
    uint32_t version;
    bool operator<(const Candidate& o) const {  // the queue's top: largest error, then smallest index
      return err != o.err ? err < o.err : point > o.point;
    }
  };

  class Sampler {
   public:
    template <class Scalar>
    Sampler(const Scalar* xyz, size_t n, const Param& p) : n_(n), p_(p) {
      if (n < 3) throw InputError(Field::Points, "holds " + std::to_string(n) + " points: a TIN needs at least 3");
      x_.resize(n), y_.resize(n), z_.resize(n);
      size_t bad = 0;
      for (size_t i = 0; i < n; ++i) {
        x_[i] = double(xyz[3 * i]), y_[i] = double(xyz[3 * i + 1]), z_[i] = double(xyz[3 * i + 2]);
        bad += !std::isfinite(x_[i]) || !std::isfinite(y_[i]) || !std::isfinite(z_[i]);
      }
      if (bad) throw NonFiniteCoordinates(bad);
      // Coordinates from the box's corner: UTM eastings and northings keep their centimetres.
      const double ox = *std::min_element(x_.begin(), x_.end()), oy = *std::min_element(y_.begin(), y_.end());
      for (size_t i = 0; i < n; ++i) x_[i] -= ox, y_[i] -= oy;
      const auto [z0, z1] = std::minmax_element(z_.begin(), z_.end());
      const double dx = *std::max_element(x_.begin(), x_.end()), dy = *std::max_element(y_.begin(), y_.end());
      CheckDistanceRange(std::max({dx, dy, *z1 - *z0}));
      if (!(p.separation >= 0) || !std::isfinite(p.separation))
        throw InputError(Field::Separation, "must be a number at least 0, got " + Shown(p.separation));
    }

    Result Run(Progress& progress) {
      Result r;
      const auto [hull, distinct] = HullAndDistinct();
      r.hullSize = hull.size();
      if (p_.sampleNum < hull.size() || p_.sampleNum > distinct)
        throw InputError(Field::SampleNum, "must be between the " + Counted(hull.size()) +
                                               " points on the hull in x, y and the " + Counted(distinct) +
                                               " distinct points in x, y, got " + std::to_string(p_.sampleNum));
      r.area = Area(hull);
      r.separatedPrefix = p_.sampleNum;
      bool relaxed = false;
      eligibleAt_.assign(n_, 0);
      owner_.assign(n_, -1);
      for (int h : hull) {
        dt_.insert(Pt(h))->info() = h;
        r.samples.push_back(h), r.error.push_back(0);
        eligibleAt_[h] = kNever;
      }
      std::vector<Face> all;
      for (auto f = dt_.finite_faces_begin(); f != dt_.finite_faces_end(); ++f) all.push_back(f);
      Distribute(Others(), all);
      const double beta2A = p_.separation * p_.separation * r.area;
      while (r.samples.size() < p_.sampleNum) {
        const size_t k = r.samples.size();
        progress(k, p_.sampleNum, "Greedy insertion");
        Reactivate(k);
        if (queue_.empty()) {  // every point left is in a disk: the rest go by error alone
          if (deferred_.empty()) throw std::logic_error("HeightFieldLod: no point left to insert");
          r.separatedPrefix = k, relaxed = true;
          for (; !deferred_.empty(); deferred_.pop()) {
            const int i = deferred_.top().second;
            if (eligibleAt_[size_t(i)] != deferred_.top().first) continue;  // inserted or deferred again
            eligibleAt_[size_t(i)] = 0;
            Recompute(owner_[size_t(i)]);
          }
          continue;
        }
        const Candidate c = queue_.top();
        queue_.pop();
        Record& rec = records_[size_t(c.record)];
        if (!rec.alive || rec.version != c.version) continue;
        const Face f = faces_[size_t(c.record)];
        const Point q = Pt(c.point);
        const double d2 = relaxed ? 0 : NearestSquared(c.point, f, beta2A / double(k + 1));
        if (!relaxed && d2 * double(k + 1) < beta2A) {
          // Too near a sample for k + 1 disks; it fits once r(k') is at most its distance. A rank
          // past every point (or none: beta^2 A overflows, d^2 underflows to 0) is the same as
          // never, until the disks are given up.
          const double fits = std::ceil(beta2A / d2) - 1;
          eligibleAt_[size_t(c.point)] = std::max(k + 1, fits < double(n_) ? size_t(fits) : n_);
          deferred_.push({eligibleAt_[size_t(c.point)], c.point});
          Recompute(c.record);
          continue;
        }
        Insert(c.point, f);
        r.samples.push_back(c.point), r.error.push_back(c.err);
      }
      progress(p_.sampleNum, p_.sampleNum, "Greedy insertion");
      std::vector<int> rank(n_, -1);
      for (size_t s = 0; s < r.samples.size(); ++s) rank[size_t(r.samples[s])] = int(s);
      r.triangles = TrianglesOf(dt_);
      for (auto& t : r.triangles)
        for (int& v : t) v = rank[size_t(v)];
      return r;
    }

   private:
    static constexpr size_t kNever = size_t(-1);

    Point Pt(int i) const { return Point(x_[size_t(i)], y_[size_t(i)]); }

    /// The squared distance from point i (in face f) to its nearest sample, if
    /// below r2, else infinity (at least r2 in x, y). In x, y, or in x, y, z: the triangles the
    /// disk of radius r meets (connected, as the disk is) hold every sample
    /// nearer than r in 3D, as x, y alone is never longer.
    double NearestSquared(int i, Face f, double r2) const {
      const Point q = Pt(i);
      if (!p_.inHeight) return CGAL::squared_distance(q, dt_.nearest_vertex(q, f)->point());
      double best = r2;
      std::vector<Face> todo{f}, seen{f};
      while (!todo.empty()) {
        const Face g = todo.back();
        todo.pop_back();
        for (int e = 0; e < 3; ++e) {
          const int v = g->vertex(e)->info();
          const double dz = z_[size_t(v)] - z_[size_t(i)];
          best = std::min(best, CGAL::squared_distance(q, g->vertex(e)->point()) + dz * dz);
          const Face h = g->neighbor(e);
          if (dt_.is_infinite(h) || std::find(seen.begin(), seen.end(), h) != seen.end()) continue;
          const K::Segment_2 edge(g->vertex(g->cw(e))->point(), g->vertex(g->ccw(e))->point());
          if (CGAL::squared_distance(q, edge) < best) todo.push_back(h), seen.push_back(h);
        }
      }
      return best < r2 ? best : std::numeric_limits<double>::infinity();
    }

    /// The hull's corners in x, y, counter-clockwise (points on its edges left
    /// out), and the number of distinct points in x, y. One sort by x, y gives
    /// both: the count, and per x its lowest and highest point, the only
    /// candidates for corners (the smallest index of equal ones).
    std::pair<std::vector<int>, size_t> HullAndDistinct() const {
      struct XY {
        double x, y;
        int i;
        bool operator<(const XY& o) const { return x != o.x ? x < o.x : y != o.y ? y < o.y : i < o.i; }
      };
      std::vector<XY> xy(n_);
      for (size_t i = 0; i < n_; ++i) xy[i] = {x_[i], y_[i], int(i)};
      std::sort(xy.begin(), xy.end());
      size_t distinct = 0;
      std::vector<int> candidates;
      for (size_t a = 0, b; a < n_; a = b) {  // [a, b): one x
        size_t top = a;
        for (b = a; b < n_ && xy[b].x == xy[a].x; ++b) {
          if (b == a || xy[b].y != xy[b - 1].y) ++distinct, top = b;
        }
        candidates.push_back(xy[a].i);
        if (top != a) candidates.push_back(xy[top].i);
      }
      std::vector<Point> pts;
      std::vector<int> local(candidates.size()), out;
      for (size_t c = 0; c < candidates.size(); ++c) pts.push_back(Pt(candidates[c])), local[c] = int(c);
      using Traits = CGAL::Convex_hull_traits_adapter_2<K, CGAL::Pointer_property_map<Point>::type>;
      CGAL::convex_hull_2(local.begin(), local.end(), std::back_inserter(out), Traits(CGAL::make_property_map(pts)));
      for (int& c : out) c = candidates[size_t(c)];
      if (out.size() < 3) throw InputError(Field::Points, "holds only points on one line in x, y (no area to triangulate)");
      return {out, distinct};
    }

    double Area(const std::vector<int>& hull) const {
      double a = 0;
      for (size_t i = 0; i < hull.size(); ++i) {
        const size_t u = size_t(hull[i]), v = size_t(hull[(i + 1) % hull.size()]);
        a += x_[u] * y_[v] - x_[v] * y_[u];
      }
      return std::abs(a) / 2;
    }

    std::vector<int> Others() const {
      std::vector<int> o;
      o.reserve(n_);
      for (size_t i = 0; i < n_; ++i)
        if (eligibleAt_[i] != kNever) o.push_back(int(i));
      return o;
    }

    /// Gives each finite face of `faces` a new Record and hands `points` to the
    /// faces holding them; points on a sample in x, y are never eligible.
    /// With `center` (the vertex just inserted, `faces` its star in order
    /// around it) the points are those of the faces it replaced, all inside its
    /// star, and each is found by walking the star's wedges. Otherwise a point
    /// on an edge of those faces may be found in the face beyond it, whose
    /// record then takes it and is examined again.
    void Distribute(const std::vector<int>& points, const std::vector<Face>& faces,
                    DT::Vertex_handle center = DT::Vertex_handle()) {
      std::vector<int> fresh;
      bool fan = center != DT::Vertex_handle();
      for (Face f : faces) {
        if (dt_.is_infinite(f)) {
          fan = false;  // a sample on the hull: its star is not a closed fan
          continue;
        }
        f->info() = NewRecord(f);
        fresh.push_back(f->info());
      }
      const int firstFresh = fresh.front();
      Face hint = faces_[size_t(firstFresh)];
      size_t wedge = 0;
      for (int i : points) {
        const Point q = Pt(i);
        Face f;
        bool onSample = false;
        if (fan && FindWedge(faces, center, q, wedge)) {
          f = faces[wedge];
          for (int e = 0; e < 3; ++e) onSample |= f->vertex(e)->point() == q;
        } else {
          DT::Locate_type lt;
          int li;
          f = dt_.locate(q, lt, li, hint);
          onSample = lt == DT::VERTEX;
          if (!onSample && dt_.is_infinite(f)) f = f->neighbor(f->index(dt_.infinite_vertex()));  // on a hull edge
        }
        if (onSample) {  // the same x, y as a sample
          eligibleAt_[size_t(i)] = kNever;
          continue;
        }
        owner_[size_t(i)] = f->info();
        records_[size_t(f->info())].points.push_back(i);
        if (f->info() < firstFresh) fresh.push_back(f->info());
        hint = f;
      }
      std::sort(fresh.begin(), fresh.end());
      fresh.erase(std::unique(fresh.begin(), fresh.end()), fresh.end());
      for (int id : fresh) Recompute(id);
    }

    /// The wedge of `star` (the faces around v, counter-clockwise) holding q,
    /// a point of the star, walking from `wedge`: face j holds q when q is
    /// neither clockwise of its first edge from v nor counter-clockwise of its
    /// second. False if the walk goes once round without finding it.
    static bool FindWedge(const std::vector<Face>& star, DT::Vertex_handle v, const Point& q, size_t& wedge) {
      for (size_t step = 0; step < star.size(); ++step) {
        const Face f = star[wedge];
        const int iv = f->index(v);
        if (CGAL::orientation(v->point(), f->vertex(f->ccw(iv))->point(), q) == CGAL::RIGHT_TURN)
          wedge = (wedge + star.size() - 1) % star.size();  // clockwise of the face: go clockwise
        else if (CGAL::orientation(v->point(), f->vertex(f->cw(iv))->point(), q) == CGAL::LEFT_TURN)
          wedge = (wedge + 1) % star.size();
        else
          return true;
      }
      return false;
    }

    int NewRecord(Face f) {
      Record rec;
      const int a = f->vertex(0)->info(), b = f->vertex(1)->info(), c = f->vertex(2)->info();
      const double ux = x_[size_t(b)] - x_[size_t(a)], uy = y_[size_t(b)] - y_[size_t(a)];
      const double vx = x_[size_t(c)] - x_[size_t(a)], vy = y_[size_t(c)] - y_[size_t(a)];
      const double uz = z_[size_t(b)] - z_[size_t(a)], vz = z_[size_t(c)] - z_[size_t(a)];
      const double det = ux * vy - vx * uy;  // > 0: finite Delaunay faces are counter-clockwise, never flat
      rec.x0 = x_[size_t(a)], rec.y0 = y_[size_t(a)], rec.z0 = z_[size_t(a)];
      rec.gx = (uz * vy - vz * uy) / det, rec.gy = (ux * vz - vx * uz) / det;
      records_.push_back(std::move(rec));
      faces_.push_back(f);
      return int(records_.size() - 1);
    }

    double ErrorOf(const Record& rec, int i) const {
      return std::abs(z_[size_t(i)] - (rec.z0 + rec.gx * (x_[size_t(i)] - rec.x0) + rec.gy * (y_[size_t(i)] - rec.y0)));
    }

    /// The record's worst eligible point, queued.
    void Recompute(int id) {
      Record& rec = records_[size_t(id)];
      rec.best = -1, rec.err = -1, ++rec.version;
      for (int i : rec.points) {
        if (eligibleAt_[size_t(i)] > k()) continue;
        const double e = ErrorOf(rec, i);
        if (e > rec.err || (e == rec.err && i < rec.best)) rec.err = e, rec.best = i;
      }
      if (rec.best >= 0) queue_.push({rec.err, rec.best, id, rec.version});
    }

    size_t k() const { return dt_.number_of_vertices(); }

    /// Points deferred until k samples: eligible again, their records re-examined.
    void Reactivate(size_t k) {
      while (!deferred_.empty() && deferred_.top().first <= k) {
        const int i = deferred_.top().second;
        deferred_.pop();
        if (owner_[size_t(i)] >= 0 && eligibleAt_[size_t(i)] <= k) Recompute(owner_[size_t(i)]);
      }
    }

    /// Adds point i, found in face f: the faces it replaces give their points
    /// to the faces around it.
    void Insert(int i, Face f) {
      const Point q = Pt(i);
      std::vector<Face> conflicts;
      dt_.get_conflicts(q, std::back_inserter(conflicts), f);
      std::vector<int> points;
      for (Face g : conflicts) {
        if (dt_.is_infinite(g)) continue;
        Record& rec = records_[size_t(g->info())];
        rec.alive = false;
        for (int j : rec.points)
          if (j != i && eligibleAt_[size_t(j)] != kNever) points.push_back(j);
        std::vector<int>().swap(rec.points);
      }
      eligibleAt_[size_t(i)] = kNever;
      const auto v = dt_.insert(q, f);
      v->info() = i;
      std::vector<Face> star;
      auto fc = dt_.incident_faces(v), done = fc;
      do star.push_back(fc); while (++fc != done);
      Distribute(points, star, v);
    }

    const size_t n_;
    const Param p_;
    std::vector<double> x_, y_, z_;
    DT dt_;
    std::vector<Record> records_;
    std::vector<Face> faces_;       // per record: its face
    std::vector<size_t> eligibleAt_;  // per point: the sample count from which it may be chosen
    std::vector<int> owner_;        // per point: the record holding it
    std::priority_queue<Candidate> queue_;
    // points too near a sample, by the count at which they fit (the fewest first)
    std::priority_queue<std::pair<size_t, int>, std::vector<std::pair<size_t, int>>, std::greater<>> deferred_;
  };
};

}  // namespace vcg_ext
#endif

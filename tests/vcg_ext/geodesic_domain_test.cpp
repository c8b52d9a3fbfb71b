// vcg_ext/geodesic_domain.h: `hasFaces` tells whether the input had faces,
// usable or not; `vertexCount` is the input's vertex count, deleted vertices
// included, and at least one past the largest vertIndex of a hand-made point
// set; in Mesh mode the vertices in no triangle are left out (counted in
// `leftOut`) and never sampled; its border is the edges of one triangle;
// PointOfVertex maps every vertex back to its point, -1 for the left-out and
// the deleted ones; without orientNormals the estimated normals keep the
// fits' signs and every sample is the same; a cloud's points at one position
// are one point (the first of them), the others sampled with it or never,
// and so are points within the merge distance (a millionth of the cloud's
// size) of an earlier one, those kept further apart than it.
#include <gtest/gtest.h>
#include <algorithm>
#include <random>
#include <set>
#include <vcg_ext/geodesic_domain.h>
#include <vcg_ext/geodesic_fps_lod.h>
#include <vcg_ext/geodesic_lod_pyramid.h>
#include <vcg_ext/geodesic_poisson_lod.h>
#include <vcg_ext/mesh_lod.h>
#include <vcg_ext/mesh_triangles.h>
#include "on_threads.h"
#include "test_mesh.h"

namespace geodesic_domain_test {

namespace {
using Domain = vcg_ext::GeodesicDomain<float>;
using vcg_ext::GeodesicMode;
typedef vcg::tri::Allocator<test::TMesh> Alloc;

Domain::Param Mode(GeodesicMode mode) {
  Domain::Param p;
  p.mode = mode;
  return p;
}

// A bumpy 20 x 20 grid mesh and `extra` vertices above it that no face uses:
// far from the surface, so a sampler given them would take them first.
void GridWithStrays(test::TMesh& m, int extra) {
  test::GridMesh(m, 20, [](float x, float y) { return test::HalfBumpy(x, y); });
  const size_t base = m.vert.size();
  Alloc::AddVertices(m, size_t(extra));
  for (int i = 0; i < extra; ++i) m.vert[base + size_t(i)].P() = test::P3(0.2f * float(i), 0.5f, 0.5f);
}
// `m` followed by `copies` more copies of all its points, in turn.
void WithCopies(const test::TMesh& m, int copies, test::TMesh& out) {
  const size_t n = m.vert.size();
  Alloc::AddVertices(out, n * size_t(copies + 1));
  for (size_t v = 0; v < out.vert.size(); ++v) {
    out.vert[v].P() = m.vert[v % n].cP();
    out.vert[v].N() = m.vert[v % n].cN();
  }
}

// WithCopies, each copy moved by up to `jitter` along each axis.
void WithNearCopies(const test::TMesh& m, int copies, float jitter, test::TMesh& out) {
  WithCopies(m, copies, out);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-jitter, jitter);
  for (size_t v = m.vert.size(); v < out.vert.size(); ++v) out.vert[v].P() += test::P3(u(rng), u(rng), u(rng));
}

// The distance within which a cloud of m's vertices merges points.
double MergeDistance(const test::TMesh& m) {
  const std::vector<test::P3> pos = test::Positions(m);
  std::vector<int> id(pos.size());
  for (size_t i = 0; i < id.size(); ++i) id[i] = int(i);
  return vcg_ext::NearPoints<float>::DistanceOf(vcg_ext::BallShare<float>::SubsampleById(pos, id));
}

// The InputError `f` throws: its field and problem ("no error" when none).
template <class F>
std::pair<std::string, std::string> ErrorOf(F&& f) {
  try {
    f();
  } catch (const vcg_ext::InputError& e) {
    return {vcg_ext::FieldId(e.field), e.what()};
  }
  return {"no error", ""};
}
}  // namespace

TEST(GeodesicDomain, FacesThatAreAllSkippedStillCountAsFaces) {
  // Every face repeats a corner: none is usable, so the geodesics are the
  // point graph's, but a mesh output must still be told the input had faces.
  test::TMesh m;
  test::Plane(m, 15);
  for (size_t i = 0; i + 1 < m.vert.size(); i += 2) Alloc::AddFace(m, &m.vert[i], &m.vert[i], &m.vert[i + 1]);
  const auto ps = vcg_ext::PointSetFromMesh<test::TMesh>::Compute(m);
  const auto tris = vcg_ext::MeshTrianglesFromMesh<test::TMesh>::Compute(m, ps);
  ASSERT_TRUE(tris.tri.empty());
  ASSERT_GT(tris.skipped, 0u);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  EXPECT_TRUE(d.hasFaces);
  EXPECT_FALSE(d.meshGeodesics);
  EXPECT_TRUE(d.triangles.empty());
}

TEST(GeodesicDomain, FacesOnDeletedVerticesStillCountAsFaces) {
  test::TMesh m;
  test::GridMesh(m, 6, [](float, float) { return 0.f; });
  test::AppendShifted(m, [](test::TMesh& b) { test::Plane(b, 10); }, test::P3(2, 0, 0));
  for (int i = 0; i < 36; ++i) Alloc::DeleteVertex(m, m.vert[size_t(i)]);  // every face's corners
  const Domain d = Domain::FromMesh(m, Domain::Param());
  EXPECT_TRUE(d.hasFaces);
  EXPECT_TRUE(d.triangles.empty());
}

TEST(GeodesicDomain, ACloudHasNoFaces) {
  test::TMesh m;
  test::Plane(m, 15);
  EXPECT_FALSE(Domain::FromMesh(m, Domain::Param()).hasFaces);
  test::TMesh mesh;
  test::GridMesh(mesh, 15, [](float, float) { return 0.f; });
  EXPECT_TRUE(Domain::FromMesh(mesh, Domain::Param()).hasFaces);
}

TEST(GeodesicDomain, ItsBorderIsTheRimOfAnOpenGridAndACloudHasNone) {
  test::TMesh mesh;
  const int n = 15;
  test::GridMesh(mesh, n, [](float x, float y) { return test::HalfBumpy(x, y); });
  const Domain d = Domain::FromMesh(mesh, Mode(GeodesicMode::Mesh));
  ASSERT_EQ(d.onBorder.size(), d.size());
  EXPECT_EQ(d.borderEdges.size(), size_t(4 * (n - 1)));
  for (size_t i = 0; i < d.size(); ++i) {
    const auto& p = d.points.pos[i];
    const bool rim = p[0] == 0 || p[1] == 0 || p[0] == 1 || p[1] == 1;
    EXPECT_EQ(d.onBorder[i] != 0, rim) << "point " << i;
  }
  for (const auto& e : d.borderEdges) EXPECT_TRUE(d.onBorder[size_t(e.u)] && d.onBorder[size_t(e.v)]);
  test::TMesh cloud;
  test::Plane(cloud, n);
  const Domain c = Domain::FromMesh(cloud, Domain::Param());
  EXPECT_TRUE(c.onBorder.empty());
  EXPECT_TRUE(c.borderEdges.empty());
}

TEST(GeodesicDomain, VertexCountIsTheMeshsWithItsDeletedVertices) {
  // The last vertices deleted too: the largest live index is then well below m.vert.size().
  for (GeodesicMode mode : {GeodesicMode::PointGraph, GeodesicMode::Mesh}) {
    test::TMesh m;
    test::GridMesh(m, 20, [](float x, float y) { return test::HalfBumpy(x, y); });
    for (size_t i = 0; i < m.vert.size(); i += 3) Alloc::DeleteVertex(m, m.vert[i]);
    for (size_t i = m.vert.size() - 25; i < m.vert.size(); ++i)
      if (!m.vert[i].IsD()) Alloc::DeleteVertex(m, m.vert[i]);
    const Domain d = Domain::FromMesh(m, Mode(mode));
    EXPECT_EQ(d.vertexCount, m.vert.size());
    EXPECT_LT(*std::max_element(d.points.vertIndex.begin(), d.points.vertIndex.end()) + 1, int(m.vert.size()));
  }
}

TEST(GeodesicDomain, VertexCountIsPastTheLargestIndexOfAHandMadePointSet) {
  // A point set built by hand may leave vertexCount at 0 or below its indices.
  for (size_t given : {size_t(0), size_t(300), size_t(2000)}) {
    vcg_ext::PointSet<float> ps;
    for (int i = 0; i < 15; ++i)
      for (int j = 0; j < 15; ++j) {
        ps.pos.push_back(test::P3(float(i) / 14, float(j) / 14, 0.1f * float(i * j % 3)));
        ps.vertIndex.push_back(7 + 4 * (224 - (i * 15 + j)));  // sparse, the largest first
      }
    ps.vertexCount = given;
    const int largest = *std::max_element(ps.vertIndex.begin(), ps.vertIndex.end());
    const Domain d = Domain::Build(ps, vcg_ext::MeshTriangles(), Domain::Param());
    EXPECT_GE(d.vertexCount, size_t(largest) + 1) << "given " << given;
    EXPECT_GE(d.vertexCount, given);
    // PointOfVertex over vertexCount holds every point.
    const std::vector<int> point = d.PointOfVertex(d.vertexCount);
    for (size_t i = 0; i < d.size(); ++i) EXPECT_EQ(point[size_t(d.points.vertIndex[i])], int(i));
    EXPECT_EQ(size_t(std::count(point.begin(), point.end(), -1)), d.vertexCount - d.size());
  }
}

TEST(GeodesicDomain, MeshModeLeavesOutVerticesInNoTriangle) {
  test::TMesh m;
  GridWithStrays(m, 5);
  const Domain d = Domain::FromMesh(m, Mode(GeodesicMode::Mesh));
  ASSERT_TRUE(d.meshGeodesics);
  EXPECT_EQ(d.leftOut, 5u);
  EXPECT_EQ(d.size(), 400u);
  EXPECT_EQ(d.vertexCount, 405u);
  for (int v : d.points.vertIndex) EXPECT_LT(v, 400) << "a stray vertex became a point";
  // The point graph keeps them: they are left out for want of triangles, not for where they are.
  const Domain g = Domain::FromMesh(m, Mode(GeodesicMode::PointGraph));
  EXPECT_EQ(g.leftOut, 0u);
  EXPECT_EQ(g.size(), 405u);
}

TEST(GeodesicDomain, LeftOutVerticesAreNeverSampled) {
  test::TMesh m;
  GridWithStrays(m, 5);
  // All 400 usable points, and a few farthest ones: either takes the strays if it can.
  typedef vcg_ext::GeodesicFpsLod<float> Fps;
  for (size_t n : {size_t(400), size_t(8)}) {
    Fps::Param p;
    p.sampleNum = n;
    p.domain.mode = GeodesicMode::Mesh;
    const auto r = vcg_ext::MeshLod<Fps>(m, p);
    EXPECT_EQ(r.leftOut, 5u);
    ASSERT_EQ(r.vertIndex.size(), n);
    for (int v : r.vertIndex) EXPECT_LT(v, 400) << n << " samples";
  }
  typedef vcg_ext::GeodesicPoissonLod<float> Poisson;
  Poisson::Param p;
  p.radius = 0.05;
  const auto r = vcg_ext::MeshLod<Poisson>(m, p);  // Auto: a mesh's geodesics
  ASSERT_TRUE(r.meshGeodesics);
  ASSERT_FALSE(r.vertIndex.empty());
  for (int v : r.vertIndex) EXPECT_LT(v, 400);
}

TEST(GeodesicDomain, UnorientedNormalsDifferOnlyInSignAndChangeNoSample) {
  test::TMesh m;
  test::Sphere(m, 3000);
  Domain::Param oriented = Mode(GeodesicMode::PointGraph), unoriented = oriented;
  unoriented.orientNormals = false;
  const Domain a = Domain::FromMesh(m, oriented), b = Domain::FromMesh(m, unoriented);
  ASSERT_EQ(a.size(), b.size());
  size_t flipped = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE(a.normal[i] == b.normal[i] || a.normal[i] == -b.normal[i]) << i;
    flipped += a.normal[i] != b.normal[i];
    EXPECT_GT(a.normal[i].dot(vcg::Point3f::Construct(a.points.pos[i])), 0.f) << i;  // outward
  }
  EXPECT_GT(flipped, 0u);  // the walk did not run on b: some fit points inward
  EXPECT_EQ(a.curvature, b.curvature);
  typedef vcg_ext::GeodesicPoissonLod<float> Poisson;
  Poisson::Param p;
  p.radius = 0.1;
  EXPECT_EQ(Poisson::Compute(a, p).vertIndex, Poisson::Compute(b, p).vertIndex);
}

TEST(GeodesicDomain, PointOfVertexMapsBackAndMarksTheMissing) {
  // Deleted vertices (a cloud) and left-out ones (a mesh) both map to -1.
  test::TMesh cloud;
  test::Plane(cloud, 20);
  for (size_t i = 0; i < cloud.vert.size(); i += 4) Alloc::DeleteVertex(cloud, cloud.vert[i]);
  test::TMesh mesh;
  GridWithStrays(mesh, 3);
  for (const test::TMesh* m : {&cloud, &mesh}) {
    const Domain d = Domain::FromMesh(*m, Domain::Param());
    const std::vector<int> point = d.PointOfVertex(m->vert.size());
    ASSERT_EQ(point.size(), m->vert.size());
    std::set<int> seen;
    for (size_t v = 0; v < point.size(); ++v) {
      const bool missing = m->vert[v].IsD() || (m == &mesh && v >= 400);
      if (missing) {
        EXPECT_EQ(point[v], -1) << "vertex " << v;
        continue;
      }
      ASSERT_GE(point[v], 0) << "vertex " << v;
      ASSERT_LT(point[v], int(d.size()));
      EXPECT_EQ(d.points.vertIndex[size_t(point[v])], int(v));
      EXPECT_EQ(d.points.pos[size_t(point[v])], m->vert[v].cP());
      seen.insert(point[v]);
    }
    EXPECT_EQ(seen.size(), d.size()) << "every point is some vertex's";
  }
}

TEST(GeodesicDomain, PointsRepeatedAtOnePositionAreOnePoint) {
  // 25 copies of each position: every point's k nearest would be its own
  // copies, the graph one part per position and the normals fitted to one
  // point. The copies after the first change nothing, whatever the metric,
  // in a random visiting order (a key order's balls are scaled by the
  // spacing of the points as given, copies included).
  test::TMesh once, many;
  test::HeightField(once, 30, [](float x, float y) { return test::HalfBumpy(x, y, 0.1f); });
  WithCopies(once, 24, many);
  const size_t n = once.vert.size();
  for (vcg_ext::Metric metric : {vcg_ext::Metric::CurvatureDensity, vcg_ext::Metric::Euclidean}) {
    Domain::Param p;
    p.metric = metric;
    const Domain a = Domain::FromMesh(once, p), b = Domain::FromMesh(many, p);
    ASSERT_EQ(b.size(), n);
    EXPECT_EQ(b.repeats.size(), 24 * n);
    EXPECT_EQ(b.vertexCount, 25 * n);
    EXPECT_EQ(b.points.vertIndex, a.points.vertIndex);
    EXPECT_EQ(b.normal, a.normal);
    EXPECT_EQ(b.curvature, a.curvature);
    EXPECT_EQ(b.components, a.components);
    // Every vertex maps to the point at its position.
    const std::vector<int> point = b.PointOfVertex(b.vertexCount);
    for (size_t v = 0; v < point.size(); ++v) {
      ASSERT_GE(point[v], 0) << "vertex " << v;
      EXPECT_EQ(b.points.pos[size_t(point[v])], many.vert[v].cP());
    }
  }
  typedef vcg_ext::GeodesicPoissonLod<float> Poisson;
  Poisson::Param byRadius;
  byRadius.order = vcg_ext::VisitOrder::Random;
  byRadius.radius = 0.08;
  byRadius.regions = vcg_ext::Regions::Voronoi;
  const auto a = vcg_ext::MeshLod<Poisson>(once, byRadius), b = vcg_ext::MeshLod<Poisson>(many, byRadius);
  EXPECT_EQ(b.vertIndex, a.vertIndex);
  EXPECT_EQ(b.repeated, 24 * n);
  ASSERT_EQ(b.regionOf.size(), 25 * n);
  for (size_t v = 0; v < b.regionOf.size(); ++v) EXPECT_EQ(b.regionOf[v], a.regionOf[v % n]) << "vertex " << v;
  typedef vcg_ext::GeodesicFpsLod<float> Fps;
  Fps::Param fps;
  fps.sampleNum = 60;
  EXPECT_EQ(vcg_ext::MeshLod<Fps>(many, fps).vertIndex, vcg_ext::MeshLod<Fps>(once, fps).vertIndex);
  // Counts (searched from a first radius reckoned with the points as given): only first points, as many as asked.
  Poisson::Param byCount;
  byCount.sampleNum = 120;
  typedef vcg_ext::GeodesicLodPyramid<float> Pyramid;
  Pyramid::Param pyramid;
  pyramid.counts = {300, 100, 30};
  for (const auto& r : {vcg_ext::MeshLod<Poisson>(many, byCount).vertIndex, vcg_ext::MeshLod<Pyramid>(many, pyramid).vertIndex}) {
    EXPECT_TRUE(r.size() == 120 || r.size() == 300) << r.size();
    for (int v : r) EXPECT_LT(v, int(n));
  }
}

TEST(GeodesicDomain, OfPointsAtOnePositionTheFirstIsSampled) {
  // Copies before and after the first of a position in the input's order.
  test::TMesh once, many;
  test::Sphere(once, 800);
  WithCopies(once, 3, many);
  std::reverse(many.vert.begin() + 400, many.vert.end());  // copies of the last half first
  typedef vcg_ext::GeodesicPoissonLod<float> Poisson;
  Poisson::Param p;
  p.radius = 0.2;
  const auto r = vcg_ext::MeshLod<Poisson>(many, p);
  ASSERT_FALSE(r.vertIndex.empty());
  std::set<std::array<float, 3>> at;
  for (size_t k = 0; k < r.vertIndex.size(); ++k) {
    const vcg::Point3f q = many.vert[size_t(r.vertIndex[k])].cP();
    EXPECT_TRUE(at.insert({q[0], q[1], q[2]}).second) << "two samples at one position";
    for (int v = 0; v < r.vertIndex[k]; ++v) EXPECT_NE(many.vert[size_t(v)].cP(), q) << "not the first of its position";
  }
}

TEST(GeodesicDomain, RepeatedPositionsGiveTheSameSamplesOnAnyNumberOfThreads) {
  test::TMesh once, many;
  test::Sphere(once, 5000);
  WithCopies(once, 3, many);
  std::reverse(many.vert.begin(), many.vert.end());  // the first of each position among the last given
  typedef vcg_ext::GeodesicPoissonLod<float> Poisson;
  Poisson::Param p;
  p.sampleNum = 400;
  const auto one = test::OnThreads(1, [&] { return vcg_ext::MeshLod<Poisson>(many, p); });
  const auto all = test::OnThreads(4, [&] { return vcg_ext::MeshLod<Poisson>(many, p); });
  EXPECT_EQ(one.repeated, 15000u);
  EXPECT_EQ(all.vertIndex, one.vertIndex);
}

TEST(GeodesicDomain, CountsAndNeighboursAreOfDistinctPositions) {
  test::TMesh once, many;
  test::Sphere(once, 200);
  WithCopies(once, 4, many);
  typedef vcg_ext::GeodesicPoissonLod<float> Poisson;
  Poisson::Param p;
  p.sampleNum = 200;
  EXPECT_EQ(vcg_ext::MeshLod<Poisson>(many, p).vertIndex.size(), 200u);
  p.sampleNum = 201;
  const auto tooMany = ErrorOf([&] { vcg_ext::MeshLod<Poisson>(many, p); });
  EXPECT_EQ(tooMany.first, "SampleNum");
  EXPECT_EQ(tooMany.second,
            "must be at most the 200 distinct positions of the 1,000 points (800 repeat one and are not sampled), "
            "got 201");
  typedef vcg_ext::GeodesicFpsLod<float> Fps;
  Fps::Param f;
  f.sampleNum = 201;
  EXPECT_EQ(ErrorOf([&] { vcg_ext::MeshLod<Fps>(many, f); }).first, "SampleNum");
  // 15 positions cannot each have 20 others to fit a normal to, however often each is given.
  test::TMesh few, fewMany;
  test::Sphere(few, 15);
  WithCopies(few, 9, fewMany);
  const auto tooFew = ErrorOf([&] { Domain::FromMesh(fewMany, Domain::Param()); });
  EXPECT_EQ(tooFew.first, "Points");
  EXPECT_EQ(tooFew.second,
            "holds 15 distinct positions among its 150 points: at least 21 are needed (the neighbours each normal "
            "and the geodesics are built from)");
}

TEST(GeodesicDomain, PointsWithinTheMergeDistanceOfAnEarlierOneAreOnePoint) {
  // 25 points at each position, all but the first moved by up to 1e-7 (a
  // float's rounding here): as for exact copies, every point's k nearest
  // would be its own, the graph one part per position.
  test::TMesh once, many;
  test::HeightField(once, 30, [](float x, float y) { return test::HalfBumpy(x, y, 0.1f); });
  WithNearCopies(once, 24, 1e-7f, many);
  const size_t n = once.vert.size();
  const Domain a = Domain::FromMesh(once, Domain::Param()), b = Domain::FromMesh(many, Domain::Param());
  ASSERT_EQ(b.size(), n);
  EXPECT_EQ(b.repeats.size(), 24 * n);
  EXPECT_EQ(b.points.vertIndex, a.points.vertIndex);
  EXPECT_EQ(b.normal, a.normal);
  EXPECT_EQ(b.curvature, a.curvature);
  EXPECT_EQ(b.components, 1u);
  const double merge = MergeDistance(many);
  ASSERT_LT(merge, 1e-5);
  for (const auto& r : b.repeats)
    EXPECT_LE(vcg::Distance(many.vert[size_t(r.first)].cP(), many.vert[size_t(r.second)].cP()), merge);
  typedef vcg_ext::GeodesicPoissonLod<float> Poisson;
  Poisson::Param byRadius;
  byRadius.order = vcg_ext::VisitOrder::Random;
  byRadius.radius = 0.08;
  EXPECT_EQ(vcg_ext::MeshLod<Poisson>(many, byRadius).vertIndex, vcg_ext::MeshLod<Poisson>(once, byRadius).vertIndex);
  // The merge distance a caller gives (a cluster's, measured on the whole cloud) is the one taken: at 0 only
  // the copies that rounding left at their first's very position are one point with it.
  Domain::Param given;
  given.mergeDistance = 0;
  const Domain exact = Domain::FromMesh(many, given);
  EXPECT_GT(exact.size(), 20 * n);
  for (const auto& r : exact.repeats) EXPECT_EQ(many.vert[size_t(r.first)].cP(), many.vert[size_t(r.second)].cP());
}

TEST(GeodesicDomain, PointsCloserThanTheMergeDistanceKeepOneAboutEveryMergeDistance) {
  // A stretch of points far denser than the rest (a scanner's nearest): the
  // points kept are further apart than the merge distance and every other
  // lies within it of the kept point it is one with, so the stretch stays
  // covered however long it is.
  test::TMesh m;
  test::Sphere(m, 3000);
  const size_t sphere = m.vert.size(), line = 2000;
  Alloc::AddVertices(m, line);
  for (size_t i = 0; i < line; ++i) m.vert[sphere + i].P() = test::P3(1e-7f * float(i), 0, 1);
  const Domain d = Domain::FromMesh(m, Domain::Param());
  const double merge = MergeDistance(m);
  ASSERT_GT(merge, 1e-7);
  ASSERT_LT(merge * 10, 1e-7 * line) << "the stretch must be longer than a few merge distances";
  std::vector<int> kept;
  for (int v : d.points.vertIndex)
    if (size_t(v) >= sphere) kept.push_back(v);
  std::sort(kept.begin(), kept.end());  // along the stretch
  EXPECT_EQ(kept.size() + d.repeats.size(), line);
  for (size_t i = 1; i < kept.size(); ++i)
    EXPECT_GT(vcg::Distance(m.vert[size_t(kept[i])].cP(), m.vert[size_t(kept[i - 1])].cP()), merge);
  for (const auto& r : d.repeats) {
    EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), r.second));
    EXPECT_LE(vcg::Distance(m.vert[size_t(r.first)].cP(), m.vert[size_t(r.second)].cP()), merge);
  }
}

}  // namespace geodesic_domain_test

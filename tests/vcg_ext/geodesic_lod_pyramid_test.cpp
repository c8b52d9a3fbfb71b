// vcg_ext/geodesic_lod_pyramid.h: exact counts per level, levels nested and
// each spread evenly, each coarser level the Poisson set of its count among the
// finer's in the visiting order asked, coarsest-level labels, one triangulation and placement
// per level, bad level lists.
#include <gtest/gtest.h>
#include <algorithm>
#include <limits>
#include <set>
#include <vcg_ext/geodesic_lod_pyramid.h>
#include <vcg_ext/mesh_lod.h>
#include "test_mesh.h"

namespace geodesic_lod_pyramid_test {

namespace {
using Pyramid = vcg_ext::GeodesicLodPyramid<test::TMesh::ScalarType>;
using Domain = Pyramid::Domain;

Pyramid::Param Levels(std::vector<size_t> counts) {
  Pyramid::Param p;
  p.counts = std::move(counts);
  p.seed = 5;
  return p;
}

// Covering radius (largest distance from a point to its nearest sample) and
// separation (smallest distance between two samples) of a level, in the domain's metric.
std::pair<double, double> CoverAndSeparation(const Domain& d, const std::vector<int>& level) {
  std::vector<float> nearest(d.size(), std::numeric_limits<float>::infinity());
  double separation = std::numeric_limits<double>::infinity();
  vcg_ext::BoundedDijkstra<float> search(d.graph, d.Lengths());
  for (int a : level) {
    const auto dist = search.Distances(a);
    for (int b : level)
      if (b != a) separation = std::min(separation, double(dist[b]));
    for (size_t i = 0; i < dist.size(); ++i) nearest[i] = std::min(nearest[i], dist[i]);
  }
  return {*std::max_element(nearest.begin(), nearest.end()), separation};
}

// Each level of r is the Poisson set of p's count for it (p's order and tolerance) among the finer
// level's samples, the finest among all points.
void ExpectEachLevelIsItsPoissonSet(const test::TMesh& m, const Pyramid::Param& p, const Pyramid::Result& r) {
  using Poisson = vcg_ext::GeodesicPoissonLod<test::TMesh::ScalarType>;
  ASSERT_EQ(r.counts.size(), p.counts.size());
  for (size_t k = 0; k < p.counts.size(); ++k) {
    Poisson::Param q;
    q.sampleNum = p.counts[k];
    q.seed = p.seed;
    q.order = p.order;
    q.tolerance = p.tolerance;
    if (k > 0) q.within.assign(r.vertIndex.begin(), r.vertIndex.begin() + long(r.counts[k - 1]));
    const auto alone = vcg_ext::MeshLod<Poisson>(m, q);
    EXPECT_EQ(std::set<int>(alone.vertIndex.begin(), alone.vertIndex.end()),
              std::set<int>(r.vertIndex.begin(), r.vertIndex.begin() + long(r.counts[k])))
        << "level " << k << ", order " << int(p.order);
  }
}
}  // namespace

TEST(LodPyramid, LevelsAreNestedExactAndEvenlySpread) {
  test::TMesh m;
  test::HeightField(m, 45, [](float x, float y) { return test::HalfBumpy(x, y); });
  const Pyramid::Param p = Levels({1000, 400, 100, 25});
  const auto r = vcg_ext::MeshLod<Pyramid>(m, p);
  ASSERT_EQ(r.vertIndex.size(), 1000u);
  EXPECT_EQ(std::set<int>(r.vertIndex.begin(), r.vertIndex.end()).size(), 1000u);
  ASSERT_EQ(r.coarsest.size(), 1000u);
  for (size_t k = 0; k < p.counts.size(); ++k) {
    // Level k is the first counts[k] samples: it holds exactly the samples labelled k or coarser.
    size_t labelled = 0;
    for (size_t i = 0; i < r.coarsest.size(); ++i) {
      labelled += r.coarsest[i] >= int(k);
      EXPECT_EQ(r.coarsest[i] >= int(k), i < p.counts[k]) << "sample " << i << " level " << k;
    }
    EXPECT_EQ(labelled, p.counts[k]);
  }
  // Coarser levels are spread evenly: no point is much farther from the level
  // than two of its samples are from each other.
  const Domain d = Domain::FromMesh(m, p.domain);
  std::vector<int> pointOf(m.vert.size());
  for (size_t i = 0; i < d.size(); ++i) pointOf[d.points.vertIndex[i]] = int(i);
  for (size_t k = 1; k < p.counts.size(); ++k) {
    std::vector<int> level;
    for (size_t i = 0; i < p.counts[k]; ++i) level.push_back(pointOf[r.vertIndex[i]]);
    const auto cs = CoverAndSeparation(d, level);
    EXPECT_LE(cs.first, 2.0 * cs.second) << "level " << k;
  }
}

TEST(LodPyramid, EachCoarserLevelIsThePoissonSetOfItsCountAmongTheFiner) {
  // As the command's and a cluster's levels: each keeps the prominent points of its own scale.
  test::TMesh m;
  test::HeightField(m, 45, [](float x, float y) { return test::HalfBumpy(x, y); });
  const Pyramid::Param p = Levels({1000, 400, 100, 25});
  ExpectEachLevelIsItsPoissonSet(m, p, vcg_ext::MeshLod<Pyramid>(m, p));
}

TEST(LodPyramid, EveryLevelTakesTheVisitingOrderAsked) {
  // The finest level is the Poisson LOD of its count in that order, each coarser one the Poisson set of its
  // count among the finer's in it; the order taken is reported.
  test::TMesh m;
  test::HeightField(m, 40, [](float x, float y) { return test::HalfBumpy(x, y); });
  for (const vcg_ext::VisitOrder order :
       {vcg_ext::VisitOrder::Random, vcg_ext::VisitOrder::Prominence, vcg_ext::VisitOrder::Border}) {
    Pyramid::Param p = Levels({600, 150, 30});
    p.order = order;
    const auto r = vcg_ext::MeshLod<Pyramid>(m, p);
    EXPECT_EQ(r.order, order);
    ExpectEachLevelIsItsPoissonSet(m, p, r);
  }
  Pyramid::Param automatic = Levels({600, 150});
  EXPECT_EQ(automatic.order, vcg_ext::VisitOrder::Automatic);
  EXPECT_NE(vcg_ext::MeshLod<Pyramid>(m, automatic).order, vcg_ext::VisitOrder::Automatic) << "the order taken";
}

TEST(LodPyramid, SameSeedSameLevels) {
  test::TMesh m;
  test::HeightField(m, 30, [](float x, float y) { return test::HalfBumpy(x, y); });
  const auto a = vcg_ext::MeshLod<Pyramid>(m, Levels({300, 90, 10})), b = vcg_ext::MeshLod<Pyramid>(m, Levels({300, 90, 10}));
  EXPECT_EQ(a.vertIndex, b.vertIndex);
}

TEST(LodPyramid, EveryLevelGetsItsOwnTriangulation) {
  test::TMesh m;
  test::GridMesh(m, 30, [](float x, float y) { return test::HalfBumpy(x, y); });
  Pyramid::Param p = Levels({200, 60, 12});
  p.meshOutput = true;
  const auto r = vcg_ext::MeshLod<Pyramid>(m, p);
  ASSERT_EQ(r.levelFaces.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    // A triangulated disk with V vertices, B on its border, has 2V - B - 2 >= V - 2 faces.
    EXPECT_GE(r.levelFaces[k].size() + 2, p.counts[k]) << "level " << k;
    for (const auto& f : r.levelFaces[k])
      for (int c : f) EXPECT_LT(c, int(p.counts[k])) << "a face of level " << k << " uses a finer sample";
  }
}

// Mean height gained by the first `n` samples' placed positions over their input points.
double MeanRise(const test::TMesh& m, const std::vector<int>& vertIndex, const std::vector<vcg::Point3f>& placed,
                size_t n) {
  double rise = 0;
  for (size_t i = 0; i < n; ++i) rise += placed[i][2] - m.vert[size_t(vertIndex[i])].cP()[2];
  return rise / double(n);
}

TEST(LodPyramid, EachMeshLevelIsPlacedForItsOwnSpacing) {
  // A dome: a LOD's chords pass under it, so fitted vertices rise, and more for longer chords.
  test::TMesh m;
  test::GridMesh(m, 40, [](float x, float y) { return -((x - .5f) * (x - .5f) + (y - .5f) * (y - .5f)); });
  Pyramid::Param p = Levels({400, 100, 25});
  p.meshOutput = true;
  const auto fitted = vcg_ext::MeshLod<Pyramid>(m, p);
  ASSERT_EQ(fitted.levelPositions.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    ASSERT_EQ(fitted.levelPositions[k].size(), p.counts[k]) << "level " << k;
    EXPECT_GT(MeanRise(m, fitted.vertIndex, fitted.levelPositions[k], p.counts[k]), 0) << "level " << k;
  }
  EXPECT_EQ(fitted.position, fitted.levelPositions[0]);
  EXPECT_GT(MeanRise(m, fitted.vertIndex, fitted.levelPositions[2], 25),
            MeanRise(m, fitted.vertIndex, fitted.levelPositions[0], 25))
      << "the coarsest level's shared samples are placed as the finest level's";

  p.placement = vcg_ext::Placement::InputVertices;
  const auto kept = vcg_ext::MeshLod<Pyramid>(m, p);
  EXPECT_EQ(kept.vertIndex, fitted.vertIndex);
  for (size_t k = 0; k < 3; ++k)
    for (size_t i = 0; i < p.counts[k]; ++i)
      ASSERT_EQ(kept.levelPositions[k][i], m.vert[size_t(kept.vertIndex[i])].cP()) << "level " << k;
}

TEST(LodPyramid, WithAToleranceEachLevelIsItsPoissonSetWithinTheTolerance) {
  // Untrimmed sets within each level's window, nested, as the command's and a cluster's levels with a tolerance.
  test::TMesh m;
  test::HeightField(m, 40, [](float x, float y) { return test::HalfBumpy(x, y); });
  Pyramid::Param p = Levels({600, 150, 30});
  p.tolerance = 0.1;
  const auto r = vcg_ext::MeshLod<Pyramid>(m, p);
  ASSERT_EQ(r.counts.size(), 3u);
  ASSERT_EQ(r.vertIndex.size(), r.counts[0]);
  for (size_t k = 0; k < p.counts.size(); ++k) {
    EXPECT_GE(double(r.counts[k]), 0.9 * double(p.counts[k])) << "level " << k;
    EXPECT_LE(double(r.counts[k]), 1.1 * double(p.counts[k])) << "level " << k;
    for (size_t i = 0; i < r.coarsest.size(); ++i) EXPECT_EQ(r.coarsest[i] >= int(k), i < r.counts[k]);
  }
  ExpectEachLevelIsItsPoissonSet(m, p, r);
}

TEST(LodPyramid, RefusesLevelsTooCloseForTheTolerance) {
  // A coarser level that the tolerance lets come out as large as its finer one could not nest in fewer samples.
  test::TMesh m;
  test::Plane(m, 40);
  Pyramid::Param p = Levels({1000, 990});
  p.tolerance = 0.05;
  try {
    vcg_ext::MeshLod<Pyramid>(m, p);
    ADD_FAILURE() << "no error";
  } catch (const vcg_ext::InputError& e) {
    EXPECT_EQ(e.field, vcg_ext::Field::Levels);
    EXPECT_EQ(std::string(e.what()), "1 and 2 (1,000 and 990 samples) are too close for a tolerance of 5%: the "
                                     "coarser may come out with up to 1,039 samples, the finer with as few as 950; "
                                     "give levels further apart or a smaller tolerance");
  }
  p.counts = {1000, 900};  // up to 945, at least 950
  EXPECT_EQ(vcg_ext::MeshLod<Pyramid>(m, p).counts.size(), 2u);
}

TEST(LodPyramid, RefusesLevelsThatDoNotGetCoarser) {
  test::TMesh m;
  test::Plane(m, 10);
  for (const auto& counts : {std::vector<size_t>{}, std::vector<size_t>{50, 50}, std::vector<size_t>{10, 20}}) {
    try {
      vcg_ext::MeshLod<Pyramid>(m, Levels(counts));
      ADD_FAILURE() << "no error";
    } catch (const vcg_ext::InputError& e) {
      EXPECT_EQ(e.field, vcg_ext::Field::Levels) << e.what();
      EXPECT_TRUE(std::string(e.what()).rfind("must", 0) == 0) << e.what();
    }
  }
}

}  // namespace geodesic_lod_pyramid_test

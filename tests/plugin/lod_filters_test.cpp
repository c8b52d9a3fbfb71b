// The plugin's filter logic on CMeshO: defaults, output layer data, untouched
// input, and MLException messages for bad input.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <common/mlexception.h>
#include <vcg/complex/algorithms/create/platonic.h>
#include <vcg_ext/geodesic_lod_pyramid.h>
#include <vcg_ext/mesh_lod.h>
#include "lod_layers.h"

namespace {
using namespace geodesic_lod;

// vcglib's mesh destructor leaves named attributes allocated: free them.
struct Mesh : CMeshO {
  ~Mesh() { ClearAttributes(); }
};

// Parameter values: the specs' defaults, overridable by name. Mesh
// parameters name layers of `layers` (their index), by default the first.
class MapSource : public ParamSource {
 public:
  typedef std::vector<ParamSpec> (*Specs)(const CMeshO&);
  explicit MapSource(const CMeshO& m, bool fps = false) : MapSource(m, fps ? FpsLodParams : PoissonLodParams) {}
  MapSource(const CMeshO& m, Specs specs, std::vector<const CMeshO*> layers = {}) : layers_(std::move(layers)) {
    for (const ParamSpec& s : specs(m)) {
      v_[s.name] = s.kind == ParamKind::Mesh ? 0 : s.defaultValue;
      t_[s.name] = s.text;
    }
  }
  MapSource& set(const QString& n, double x) {
    EXPECT_TRUE(v_.count(n)) << n.toStdString();
    v_[n] = x;
    return *this;
  }
  MapSource& set(const QString& n, const QString& x) {
    EXPECT_TRUE(t_.count(n)) << n.toStdString();
    t_[n] = x;
    return *this;
  }
  double number(const QString& n) const override { return v_.at(n); }
  bool flag(const QString& n) const override { return v_.at(n) != 0; }
  int choice(const QString& n) const override { return int(v_.at(n)); }
  QString text(const QString& n) const override { return t_.at(n); }
  const CMeshO* mesh(const QString& n) const override {
    const size_t k = size_t(v_.at(n));
    return k < layers_.size() ? layers_[k] : nullptr;
  }

 private:
  std::map<QString, double> v_;
  std::map<QString, QString> t_;
  std::vector<const CMeshO*> layers_;
};

// Every output layer of a run, in `out` (one Mesh per level).
void FillAll(const CMeshO& in, const LodRun& run, std::vector<Mesh>& out) {
  const auto levels = OutputLevels(run);
  ASSERT_EQ(levels.size(), out.size());
  for (size_t k = 0; k < levels.size(); ++k) FillLodLayer(in, run, levels[k], k == 0, out[k]);
}

// The run's first output layer.
QStringList Fill(const CMeshO& in, const LodRun& run, CMeshO& out) {
  return FillLodLayer(in, run, OutputLevels(run).front(), true, out);
}

void Bumpy(CMeshO& m, int n, bool faces = false) {
  vcg::tri::Allocator<CMeshO>::AddVertices(m, size_t(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = double(i) / (n - 1), y = double(j) / (n - 1);
      auto& v = m.vert[size_t(i) * n + j];
      v.P() = Point3m(x, y, x < 0.5 ? 0 : 0.05 * std::pow(std::sin(8 * M_PI * x) * std::sin(8 * M_PI * y), 2));
      v.N() = Point3m(0, 0, 0);
      v.C() = vcg::Color4b(i, j, 7, 255);
      v.Q() = x + y;
    }
  if (faces)
    for (int i = 0; i + 1 < n; ++i)
      for (int j = 0; j + 1 < n; ++j) {
        auto* v = &m.vert[size_t(i) * n + j];
        vcg::tri::Allocator<CMeshO>::AddFace(m, v, v + n, v + n + 1);
        vcg::tri::Allocator<CMeshO>::AddFace(m, v, v + n + 1, v + 1);
      }
  vcg::tri::UpdateBounding<CMeshO>::Box(m);
}

std::string ErrorOf(const CMeshO& m, const MapSource& p) {
  try {
    RunPoissonLod(m, p, nullptr);
  } catch (const MLException& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(LodFilters, ParametersHaveThePythonNamesAndPaperDefaults) {
  Mesh m;
  Bumpy(m, 10);
  std::map<QString, ParamSpec> byName;
  for (const ParamSpec& s : PoissonLodParams(m)) byName.emplace(s.name, s);
  for (const char* n : {"radius", "metric", "curvatureexponent", "adaptivity", "normalneighbors", "graphneighbors",
                        "recomputenormals", "seed"})
    EXPECT_TRUE(byName.count(n)) << n;
  EXPECT_NEAR(byName.at("radius").defaultValue, 0.01 * m.bbox.Diag(), 1e-12);
  EXPECT_EQ(byName.at("radius").max, m.bbox.Diag());
  EXPECT_EQ(byName.at("curvatureexponent").defaultValue, 1.0);
  EXPECT_EQ(byName.at("normalneighbors").defaultValue, 20);
  EXPECT_EQ(byName.at("graphneighbors").defaultValue, 10);
  // New choices come last, so that a script's earlier choice keeps its index; automatic is the default.
  ASSERT_EQ(byName.at("metric").values.size(), 6);
  EXPECT_TRUE(byName.at("metric").values[1].startsWith("Curvature-density"));
  EXPECT_TRUE(byName.at("metric").values[5].startsWith("Automatic"));
  EXPECT_EQ(byName.at("metric").defaultValue, 5);
  ASSERT_EQ(byName.at("visitorder").values.size(), 4);
  EXPECT_TRUE(byName.at("visitorder").values[3].startsWith("Automatic"));
  EXPECT_EQ(byName.at("visitorder").defaultValue, 3);
}

TEST(LodFilters, OutputIsACopyOfChosenVerticesAndTheInputIsUnchanged) {
  Mesh in;
  Bumpy(in, 40);
  auto attr = vcg::tri::Allocator<CMeshO>::AddPerVertexAttribute<Scalarm>(in, "confidence");
  for (size_t i = 0; i < in.vert.size(); ++i) attr[i] = Scalarm(i) / 7;
  const std::vector<CVertexO> before(in.vert.begin(), in.vert.end());

  MapSource p(in);
  p.set("radius", 0.05);
  const LodRun run = RunPoissonLod(in, p, nullptr);
  Mesh out;
  const QStringList skipped = Fill(in, run, out);
  EXPECT_TRUE(skipped.isEmpty());
  ASSERT_EQ(size_t(out.vn), run.result.vertIndex.size());
  ASSERT_GT(out.vn, 10);
  auto outAttr = vcg::tri::Allocator<CMeshO>::FindPerVertexAttribute<Scalarm>(out, "confidence");
  ASSERT_TRUE(vcg::tri::Allocator<CMeshO>::IsValidHandle(out, outAttr));
  for (int k = 0; k < out.vn; ++k) {
    const CVertexO& s = in.vert[run.result.vertIndex[k]];
    EXPECT_EQ(out.vert[k].cP(), s.cP());
    EXPECT_EQ(out.vert[k].cC(), s.cC());
    EXPECT_EQ(out.vert[k].cQ(), s.cQ());
    EXPECT_EQ(outAttr[k], attr[run.result.vertIndex[k]]);
    EXPECT_NEAR(out.vert[k].cN().Norm(), 1.0, 1e-6);  // estimated: the input had none
  }
  ASSERT_EQ(before.size(), in.vert.size());
  for (size_t i = 0; i < before.size(); ++i) {
    EXPECT_EQ(before[i].cP(), in.vert[i].cP());
    EXPECT_EQ(before[i].cN(), in.vert[i].cN());
    EXPECT_EQ(before[i].cC(), in.vert[i].cC());
    EXPECT_EQ(before[i].cQ(), in.vert[i].cQ());
    EXPECT_EQ(before[i].Flags(), in.vert[i].Flags());
  }
  EXPECT_TRUE(run.summary.contains(QString::number(out.vn) + " samples"));
}

TEST(LodFilters, ValidInputNormalsAreKeptUnlessRecomputeIsAsked) {
  Mesh in;
  Bumpy(in, 30);
  for (auto& v : in.vert) v.N() = Point3m(0, 0, 3);  // valid, not unit
  MapSource p(in);
  p.set("radius", 0.1);
  Mesh kept, recomputed;
  Fill(in, RunPoissonLod(in, p, nullptr), kept);
  ASSERT_FALSE(kept.vert.empty());
  for (const auto& v : kept.vert) EXPECT_EQ(v.cN(), Point3m(0, 0, 3));
  p.set("recomputenormals", 1);
  Fill(in, RunPoissonLod(in, p, nullptr), recomputed);
  ASSERT_FALSE(recomputed.vert.empty());
  for (const auto& v : recomputed.vert) EXPECT_NEAR(v.cN().Norm(), 1.0, 1e-6);
}

TEST(LodFilters, BadInputRaisesMLExceptionWithAMessage) {
  Mesh empty;
  EXPECT_NE(ErrorOf(empty, MapSource(empty)).find("the layer holds no points"), std::string::npos);
  Mesh m;
  Bumpy(m, 10);
  EXPECT_NE(ErrorOf(m, MapSource(m).set("radius", 0)).find("radius must be a positive"), std::string::npos);
  EXPECT_NE(ErrorOf(m, MapSource(m).set("normalneighbors", 100)).find("normalneighbors must be smaller than the number of points (100)"), std::string::npos);
  Mesh three;  // too few points for the default neighbours: the message says how to go on
  vcg::tri::Allocator<CMeshO>::AddVertices(three, 3);
  for (int i = 0; i < 3; ++i) three.vert[i].P() = Point3m(i, i * i, 0);
  EXPECT_NE(ErrorOf(three, MapSource(three)).find("normalneighbors must be smaller than the number of points (3), got 20: "
                                                  "lower it or give more points"),
            std::string::npos);
  EXPECT_NE(ErrorOf(m, MapSource(m).set("graphneighbors", 0)).find("graphneighbors must be at least 1"),
            std::string::npos);
  EXPECT_NE(ErrorOf(m, MapSource(m).set("metric", 9)).find("metric must be one of"), std::string::npos);
  EXPECT_NE(ErrorOf(m, MapSource(m).set("seed", -1)).find("seed"), std::string::npos);
  m.vert[3].P()[2] = std::nan("");
  EXPECT_NE(ErrorOf(m, MapSource(m)).find("NaN or infinite"), std::string::npos);
}

TEST(LodFilters, AStopRequestBecomesAnMLException) {
  Mesh m;
  Bumpy(m, 30);
  vcg::CallBackPos* stop = [](int, const char*) { return false; };
  try {
    RunPoissonLod(m, MapSource(m), stop);
    FAIL() << "no exception";
  } catch (const MLException& e) {
    EXPECT_NE(std::string(e.what()).find("stopped"), std::string::npos);
  }
}

TEST(LodFilters, FpsGivesTheExactCountInOrderWithItsAttribute) {
  Mesh in;
  Bumpy(in, 30, true);
  MapSource p(in, true);
  EXPECT_EQ(p.number("samplenum"), 90);  // default: a tenth of the vertices
  p.set("samplenum", 57);
  const LodRun run = RunFpsLod(in, p, nullptr);
  Mesh out;
  Fill(in, run, out);
  ASSERT_EQ(out.vn, 57);
  EXPECT_EQ(out.fn, 0);
  auto order = vcg::tri::Allocator<CMeshO>::FindPerVertexAttribute<Scalarm>(out, "fps_order");
  ASSERT_TRUE(vcg::tri::Allocator<CMeshO>::IsValidHandle(out, order));
  for (int k = 0; k < out.vn; ++k) EXPECT_EQ(order[k], k);
  EXPECT_EQ(run.values.at("sample_num").toInt(), 57);
  EXPECT_GT(run.values.at("covering_radius").toDouble(), 0);
  EXPECT_TRUE(run.result.meshGeodesics);
  for (double bad : {0.0, -3.0, 901.0}) {
    p.set("samplenum", bad);
    try {
      RunFpsLod(in, p, nullptr);
      ADD_FAILURE() << bad;
    } catch (const MLException& e) {
      EXPECT_NE(std::string(e.what()).find("samplenum"), std::string::npos);
    }
  }
}

TEST(LodFilters, MeshVerticesAreOptimizedFittedOrInputVertices) {
  Mesh in;
  Bumpy(in, 40, true);
  MapSource p(in);
  p.set("radius", 0.08);
  auto run = [&](int output) {
    p.set("output", output);
    return RunPoissonLod(in, p, nullptr);
  };
  const LodRun optimized = run(1), kept = run(2), fitted = run(3);  // the default, then as scripts name them
  ASSERT_EQ(optimized.result.vertIndex, kept.result.vertIndex);
  ASSERT_EQ(fitted.result.vertIndex, kept.result.vertIndex);
  EXPECT_EQ(fitted.result.faces, kept.result.faces) << "the per-region fit moves vertices, not triangles";
  size_t moved = 0, optimizedApart = 0;
  for (size_t k = 0; k < kept.result.vertIndex.size(); ++k) {
    const Point3m at = in.vert[size_t(kept.result.vertIndex[k])].cP();
    EXPECT_EQ(kept.result.position[k], at);
    moved += fitted.result.position[k] != at;
    // Flat where the whole region, within the radius of its sample, is: nothing to fit.
    if (at[0] < 0.5 - 0.08) EXPECT_NEAR((fitted.result.position[k] - at).Norm(), 0, 1e-12);
    optimizedApart += optimized.result.position[k] != fitted.result.position[k];
  }
  EXPECT_GT(moved, 0u);
  EXPECT_GT(optimizedApart, 0u) << "the default optimizes the fitted mesh";
}

TEST(LodFilters, TriangleMeshOutputUsesSamplesAsCorners) {
  Mesh in;
  Bumpy(in, 40, true);
  for (bool fps : {false, true}) {
    MapSource p(in, fps);
    p.set("output", 1);
    if (fps) p.set("samplenum", 80);
    else p.set("radius", 0.08);
    const LodRun run = fps ? RunFpsLod(in, p, nullptr) : RunPoissonLod(in, p, nullptr);
    Mesh out;
    Fill(in, run, out);
    ASSERT_GT(out.fn, 10);
    for (const auto& f : out.face)
      for (int c = 0; c < 3; ++c) {
        const size_t k = vcg::tri::Index(out, f.cV(c));
        ASSERT_LT(k, size_t(out.vn));
        EXPECT_EQ(f.cP(c), run.result.position[k]);  // placed (optimized by default)
        EXPECT_EQ(out.vert[k].cC(), in.vert[run.result.vertIndex[k]].cC());  // the input vertex's data
      }
  }
  Mesh cloud;
  Bumpy(cloud, 10);
  MapSource p(cloud);
  p.set("output", 1);
  try {
    RunPoissonLod(cloud, p, nullptr);
    FAIL();
  } catch (const MLException& e) {
    EXPECT_NE(std::string(e.what()).find("triangle-mesh output needs faces"), std::string::npos);
  }
}

TEST(LodFilters, NormalVariationFilterGivesEq1ForEveryVertexInPlace) {
  const FilterDef& f = Filters().at(2);
  EXPECT_EQ(f.pythonName(), "compute_scalar_by_normal_variation");
  EXPECT_EQ(f.output, Output::VertexQuality);
  Mesh in;
  Bumpy(in, 30);
  const LodRun run = f.run(in, MapSource(in, NormalVariationParams), nullptr);
  ASSERT_EQ(run.result.vertIndex.size(), size_t(in.vn));
  double flat = 0, bumpy = 0, top = 0;
  for (size_t k = 0; k < run.result.vertIndex.size(); ++k) {
    const double c = run.result.curvature[k], x = in.vert[run.result.vertIndex[k]].cP()[0];
    EXPECT_GE(c, 0);
    EXPECT_LE(c, 1);
    if (x < 0.3) flat = std::max(flat, c);  // neighbourhoods (and their neighbours') all flat
    if (x > 0.6) bumpy = std::max(bumpy, c);
    top = std::max(top, c);
  }
  EXPECT_LT(flat, 1e-6);
  EXPECT_GT(bumpy, 0.01);
  EXPECT_DOUBLE_EQ(run.values.at("max").toDouble(), top);
  // Vertices given again: each gets its position's eq. 1, as the first one there.
  vcg::tri::Allocator<CMeshO>::AddVertices(in, 300);
  for (size_t v = 900; v < 1200; ++v) in.vert[v].P() = in.vert[v - 900].P();
  const LodRun again = f.run(in, MapSource(in, NormalVariationParams), nullptr);
  ASSERT_EQ(again.result.vertIndex.size(), size_t(in.vn));
  std::vector<double> of(in.vert.size(), -1);
  for (size_t k = 0; k < again.result.vertIndex.size(); ++k) of[size_t(again.result.vertIndex[k])] = again.result.curvature[k];
  for (size_t v = 0; v < 1200; ++v) EXPECT_EQ(of[v], of[v % 900]) << "vertex " << v;
  EXPECT_TRUE(again.summary.contains("in the vertex quality of 1,200 vertices")) << again.summary.toStdString();
}

TEST(LodFilters, TheLogNamesWhatTheAutomaticDefaultsTook) {
  Mesh in;
  Bumpy(in, 30);  // a surface: the curvature-density metric, the prominent points first
  MapSource p(in);
  const LodRun automatic = RunPoissonLod(in, p, nullptr);
  const std::string log = automatic.summary.toStdString();
  EXPECT_TRUE(automatic.summary.contains("in the Curvature-density geodesic metric (chosen: ")) << log;
  EXPECT_TRUE(automatic.summary.contains("of the points' neighbourhoods scatter)")) << log;
  EXPECT_TRUE(automatic.summary.contains("visiting order: Prominent points first")) << log;
  p.set("metric", 3);  // Euclidean, asked for by name: nothing chosen
  const LodRun named = RunPoissonLod(in, p, nullptr);
  EXPECT_TRUE(named.summary.contains("in the Euclidean metric")) << named.summary.toStdString();
  EXPECT_FALSE(named.summary.contains("chosen")) << named.summary.toStdString();
}

TEST(LodFilters, ThePyramidTakesTheVisitingOrderAskedAndNamesIt) {
  Mesh in;
  Bumpy(in, 30);
  MapSource p(in, PyramidParams);
  p.set("levels", "200,50");
  EXPECT_TRUE(RunPyramid(in, p, nullptr).summary.contains("visiting order: Prominent points first"));
  p.set("visitorder", 0);  // Random
  const LodRun random = RunPyramid(in, p, nullptr);
  EXPECT_TRUE(random.summary.contains("visiting order: Random")) << random.summary.toStdString();
  vcg_ext::GeodesicLodPyramid<Scalarm>::Param q;
  q.counts = {200, 50};
  q.order = vcg_ext::VisitOrder::Random;
  EXPECT_EQ(random.result.vertIndex, vcg_ext::MeshLod<vcg_ext::GeodesicLodPyramid<Scalarm>>(in, q).vertIndex);
}

TEST(LodFilters, ThePyramidTakesAToleranceAndRefusesLevelsTooCloseForIt) {
  Mesh in;
  Bumpy(in, 40);
  MapSource p(in, PyramidParams);
  EXPECT_EQ(p.number("tolerance"), 0);  // exact counts by default
  p.set("levels", "400,100");
  p.set("tolerance", 10.0);
  const LodRun run = RunPyramid(in, p, nullptr);
  vcg_ext::GeodesicLodPyramid<Scalarm>::Param q;
  q.counts = {400, 100};
  q.tolerance = 0.1;
  const auto alone = vcg_ext::MeshLod<vcg_ext::GeodesicLodPyramid<Scalarm>>(in, q);
  EXPECT_EQ(run.result.vertIndex, alone.vertIndex);
  std::vector<Mesh> out(2);
  FillAll(in, run, out);
  EXPECT_EQ(size_t(out[1].vn), alone.counts[1]);
  EXPECT_NEAR(out[1].vn, 100, 10);
  p.set("levels", "400,390");
  try {
    RunPyramid(in, p, nullptr);
    ADD_FAILURE() << "no error";
  } catch (const MLException& e) {
    EXPECT_NE(std::string(e.what()).find("are too close for a tolerance of 10%"), std::string::npos) << e.what();
  }
}

TEST(LodFilters, PoissonGivesTheAskedCountAndTheRadiusItUsed) {
  Mesh in;
  Bumpy(in, 30);
  MapSource p(in);
  EXPECT_EQ(p.number("samplenum"), 0);  // default: the radius decides
  p.set("samplenum", 123);
  const LodRun run = RunPoissonLod(in, p, nullptr);
  EXPECT_EQ(run.result.vertIndex.size(), 123u);
  EXPECT_EQ(run.values.at("sample_num").toInt(), 123);
  EXPECT_GT(run.values.at("radius").toDouble(), 0);
  EXPECT_GE(run.values.at("iterations").toInt(), 1);
  EXPECT_TRUE(run.summary.contains("123 samples asked")) << run.summary.toStdString();
  p.set("tolerance", 10);
  const size_t within = RunPoissonLod(in, p, nullptr).result.vertIndex.size();
  EXPECT_NEAR(double(within), 123, 12.3);
  for (auto bad : {std::make_pair("samplenum", -5.0), std::make_pair("samplenum", 901.0),
                   std::make_pair("tolerance", 100.0), std::make_pair("tolerance", -1.0)}) {
    MapSource q(in);
    q.set("samplenum", 50).set(bad.first, bad.second);
    EXPECT_NE(ErrorOf(in, q).find(bad.first), std::string::npos) << ErrorOf(in, q);
  }
  // A percentage of the vertices instead of a count; never both.
  MapSource rate(in);
  rate.set("samplerate", 10);
  EXPECT_EQ(RunPoissonLod(in, rate, nullptr).result.vertIndex.size(), 90u);
  for (double bad : {-1.0, 100.5}) {
    rate.set("samplerate", bad);
    EXPECT_NE(ErrorOf(in, rate).find("samplerate must be a percentage"), std::string::npos) << ErrorOf(in, rate);
  }
  rate.set("samplerate", 10).set("samplenum", 5);
  EXPECT_NE(ErrorOf(in, rate).find("give samplenum or samplerate, not both"), std::string::npos);
}

TEST(LodFilters, LevelListsAreParsedOrRefusedByName) {
  const auto l = ParseLevels(" 50% , 10%,7", 200);
  ASSERT_EQ(l.size(), 3u);
  EXPECT_EQ(l[0].count, 100u);
  EXPECT_EQ(l[1].count, 20u);
  EXPECT_EQ(l[2].count, 7u);
  EXPECT_EQ(l[0].suffix, " LOD 50%");
  EXPECT_EQ(l[2].suffix, " LOD 7");
  for (const char* bad : {"", "50%,,10%", "abc", "0%", "-5", "2.5", "150%", "201", "0.1%"}) {
    try {
      ParseLevels(bad, 200);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("levels: ", 0), 0u) << e.what();
    }
  }
}

// The level parser on random strings of the characters a list is made of: every
// string is either refused with a "levels: " message or gives counts from 1 to n,
// one per comma-separated item (the coarsening order is the pyramid's own check).
TEST(LodFilters, LevelParserOnRandomListsAnswersInRangeOrByName) {
  std::mt19937 rng(7);
  const std::string alphabet = "0123456789.,%%e+- xinfa";
  size_t accepted = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::string list;
    const int len = std::uniform_int_distribution<int>(0, 24)(rng);
    for (int c = 0; c < len; ++c) list += alphabet[std::uniform_int_distribution<size_t>(0, alphabet.size() - 1)(rng)];
    if (trial % 4 == 0) list = std::to_string(rng() % 400) + (trial % 8 ? "%" : "") + "," + list.substr(0, 3);
    static const char* huge[] = {"1e19", "99999999999999999999", "1e300", "1e19%", "50%,1e19"};
    if (trial < 5) list = huge[trial];
    const size_t n = 1 + rng() % 300;
    try {
      const auto levels = ParseLevels(QString::fromStdString(list), n);
      ++accepted;
      ASSERT_EQ(levels.size(), size_t(QString::fromStdString(list).count(',') + 1)) << list;
      for (const auto& l : levels) ASSERT_TRUE(l.count >= 1 && l.count <= n) << "'" << list << "' n " << n;
    } catch (const std::invalid_argument& e) {
      ASSERT_EQ(std::string(e.what()).rfind("levels: ", 0), 0u) << "'" << list << "': " << e.what();
      ASSERT_EQ(std::string(e.what()).find("-9223372036854775808"), std::string::npos) << e.what();
    }
  }
  EXPECT_GT(accepted, 100u) << "the strings must reach the accepting paths too";
}

TEST(LodFilters, PyramidMakesOneNestedLayerPerLevelAndLabelsTheFinest) {
  Mesh in;
  Bumpy(in, 30);
  MapSource p(in, PyramidParams);
  EXPECT_EQ(p.text("levels"), "50%,25%,10%,5%,2%");
  p.set("levels", "40%,10%,20");
  const LodRun run = RunPyramid(in, p, nullptr);
  std::vector<Mesh> out(3);
  FillAll(in, run, out);
  EXPECT_EQ(out[0].vn, 360);
  EXPECT_EQ(out[1].vn, 90);
  EXPECT_EQ(out[2].vn, 20);
  for (size_t k = 1; k < 3; ++k)  // every coarser vertex is a vertex of the finer layer
    for (const auto& v : out[k].vert)
      EXPECT_TRUE(std::any_of(out[k - 1].vert.begin(), out[k - 1].vert.end(),
                              [&](const CVertexO& w) { return w.cP() == v.cP(); }));
  auto lod = vcg::tri::Allocator<CMeshO>::FindPerVertexAttribute<Scalarm>(out[0], "lod_level");
  ASSERT_TRUE(vcg::tri::Allocator<CMeshO>::IsValidHandle(out[0], lod));
  EXPECT_FALSE(vcg::tri::Allocator<CMeshO>::IsValidHandle(
      out[1], vcg::tri::Allocator<CMeshO>::FindPerVertexAttribute<Scalarm>(out[1], "lod_level")));
  size_t coarsest = 0;
  for (int i = 0; i < out[0].vn; ++i) coarsest += lod[i] == 2;
  EXPECT_EQ(coarsest, 20u);
  EXPECT_EQ(run.values.at("level_num").toInt(), 3);
}

TEST(LodFilters, NormalProjectionMeasuresBetweenTwoLayers) {
  Mesh flat, lifted, cloud;
  Bumpy(flat, 12, true);
  Bumpy(lifted, 12, true);
  Bumpy(cloud, 5);
  for (auto& v : flat.vert) v.N() = Point3m(0, 0, 1);
  for (auto& v : lifted.vert) v.P()[2] = 0.3;
  MapSource p(flat, NormalProjectionParams, {&flat, &lifted, &cloud});
  EXPECT_NEAR(p.number("maxdist"), 0.05 * flat.bbox.Diag(), 1e-12);
  p.set("surfacemesh", 1).set("maxdist", 1.0);
  const FilterDef& f = Filters().at(4);
  EXPECT_EQ(f.pythonName(), "get_normal_projection_deviation");
  EXPECT_EQ(f.output, Output::Values);
  const LodRun run = f.run(flat, p, nullptr);
  // Only the flat half (z = 0) lies exactly 0.3 below; the bumps are closer.
  EXPECT_NEAR(run.values.at("max").toDouble(), 0.3, 1e-9);
  EXPECT_LT(run.values.at("min").toDouble(), 0.3);
  EXPECT_EQ(run.values.at("miss_fraction").toDouble(), 0.0);
  EXPECT_EQ(run.values.at("point_num").toInt(), 144);
  MapSource self(flat, NormalProjectionParams, {&flat});
  self.set("maxdist", 1.0);
  EXPECT_LT(f.run(flat, self, nullptr).values.at("max").toDouble(), 1e-9);
  auto error = [&](MapSource& q) {
    try {
      f.run(flat, q, nullptr);
    } catch (const MLException& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  MapSource noSurface(flat, NormalProjectionParams, {&flat, &lifted, &cloud});
  noSurface.set("surfacemesh", 2);
  EXPECT_EQ(error(noSurface), "Geodesic LOD: the surface layer holds no triangles to project onto");
  MapSource missing(flat, NormalProjectionParams, {&flat});
  missing.set("surfacemesh", 7);
  EXPECT_EQ(error(missing), "Geodesic LOD: surfacemesh: there is no such layer");
  MapSource noNormals(flat, NormalProjectionParams, {&cloud, &lifted});
  noNormals.set("surfacemesh", 1);
  EXPECT_NE(error(noNormals).find("the reference layer holds no points with valid normals"), std::string::npos);
}

TEST(LodFilters, HeightFieldMakesNestedTinLayersOfInputVertices) {
  Mesh in;
  Bumpy(in, 30);
  MapSource p(in, HeightFieldParams);
  p.set("levels", "20%,5%,30");
  const LodRun run = RunHeightField(in, p, nullptr);
  std::vector<Mesh> out(3);
  FillAll(in, run, out);
  EXPECT_EQ(out[0].vn, 180);
  EXPECT_EQ(out[1].vn, 45);
  EXPECT_EQ(out[2].vn, 30);
  for (size_t k = 0; k < 3; ++k) {
    // Each layer is a TIN over the unit square (seen from above, counter-clockwise) of input vertices
    // with their colour and quality.
    double area = 0;
    for (const auto& f : out[k].face) {
      const Point3m a = f.cP(0), b = f.cP(1), c = f.cP(2);
      const double signedArea = ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / 2;
      EXPECT_GT(signedArea, 0);
      area += signedArea;
    }
    EXPECT_NEAR(area, 1.0, 1e-6) << k;
    for (const auto& v : out[k].vert) {
      const int i = int(std::lround(v.cP()[0] * 29)), j = int(std::lround(v.cP()[1] * 29));
      EXPECT_EQ(v.cP(), in.vert[size_t(i) * 30 + j].cP());
      EXPECT_EQ(v.cC(), in.vert[size_t(i) * 30 + j].cC());
      EXPECT_EQ(v.cQ(), in.vert[size_t(i) * 30 + j].cQ());
      EXPECT_NEAR(v.cN().Norm(), 1.0, 1e-6);  // the input has none: the TIN's
    }
    if (k > 0)  // the coarser level is the finer one's first vertices
      for (int v = 0; v < out[k].vn; ++v) EXPECT_EQ(out[k].vert[size_t(v)].cP(), out[0].vert[size_t(v)].cP());
  }
  auto lod = vcg::tri::Allocator<CMeshO>::FindPerVertexAttribute<Scalarm>(out[0], "lod_level");
  ASSERT_TRUE(vcg::tri::Allocator<CMeshO>::IsValidHandle(out[0], lod));
  size_t coarsest = 0;
  for (int i = 0; i < out[0].vn; ++i) coarsest += lod[i] == 2;
  EXPECT_EQ(coarsest, 30u);
  EXPECT_EQ(run.values.at("sample_num").toInt(), 180);
  // Points only: no faces.
  p.set("output", 1);
  EXPECT_TRUE(OutputLevels(RunHeightField(in, p, nullptr)).front().faces.empty());
}

TEST(LodFilters, LevelMessagesGroupCountsByThousands) {
  // As the command words them: "3,595", not "3595".
  Mesh in;
  Bumpy(in, 60);  // 3600 vertices
  auto error = [&](auto params, auto run, const char* levels) {
    MapSource p(in, params);
    p.set("levels", levels);
    try {
      run(in, p, nullptr);
    } catch (const MLException& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  for (auto [params, run] : {std::pair{PyramidParams, RunPyramid}, std::pair{HeightFieldParams, RunHeightField}}) {
    const std::string coarser = error(params, run, "2000,3000"), above = error(params, run, "4000");
    EXPECT_NE(coarser.find("levels must get strictly coarser: level 2 has 3,000 samples, level 1 2,000"),
              std::string::npos) << coarser;
    EXPECT_NE(above.find("levels: 4000 gives more than 3,600 samples; a level needs 1 to 3,600 (the layer's vertices)"),
              std::string::npos) << above;
  }
  MapSource fps(in, FpsLodParams);
  fps.set("samplenum", 5000);
  try {
    RunFpsLod(in, fps, nullptr);
    ADD_FAILURE() << "no error";
  } catch (const MLException& e) {
    EXPECT_NE(std::string(e.what()).find("samplenum must be between 1 and the number of points (3,600), got 5000"),
              std::string::npos) << e.what();
  }
  fps.set("samplenum", 1);  // and the log's counts, a singular where one
  const QString log = RunFpsLod(in, fps, nullptr).summary;
  EXPECT_TRUE(log.contains(": 1 sample of 3,600 points (0.03%)")) << log.toStdString();
  EXPECT_TRUE(log.contains("; 1 connected part;")) << log.toStdString();
}

TEST(LodFilters, TheLogNamesVerticesGivenAgainAndTheCountIsOfDistinctPositions) {
  Mesh in;
  Bumpy(in, 30);  // 900 vertices, then 300 of them again
  vcg::tri::Allocator<CMeshO>::AddVertices(in, 300);
  for (size_t v = 900; v < 1200; ++v) in.vert[v].P() = in.vert[v - 900].P();
  MapSource p(in);
  p.set("samplenum", 90);
  const QString log = RunPoissonLod(in, p, nullptr).summary;
  EXPECT_TRUE(log.contains(": 90 samples of 900 points (10.00%)")) << log.toStdString();
  EXPECT_TRUE(log.contains("; 300 vertices at an earlier vertex's position, one point with it")) << log.toStdString();
  p.set("samplenum", 901);
  EXPECT_NE(ErrorOf(in, p).find("samplenum must be at most the 900 distinct positions of the 1,200 points (300 "
                                "repeat one and are not sampled), got 901"),
            std::string::npos) << ErrorOf(in, p);
  MapSource rate(in);  // a percentage is named as given, with the count it came to
  rate.set("samplerate", 100);
  EXPECT_NE(ErrorOf(in, rate).find("samplerate 100%: its count must be at most the 900 distinct positions of the "
                                   "1,200 points (300 repeat one and are not sampled), got 1200"),
            std::string::npos) << ErrorOf(in, rate);
}

TEST(LodFilters, HeightFieldTellsWhenTheLayerIsNoHeightField) {
  Mesh grid;
  Bumpy(grid, 30, true);
  MapSource p(grid, HeightFieldParams);
  const QString quiet = RunHeightField(grid, p, nullptr).summary;
  EXPECT_FALSE(quiet.contains("face down")) << quiet.toStdString();
  Mesh ball;  // a closed surface: half of it, seen from above, faces down
  vcg::tri::Sphere(ball, 3);
  vcg::tri::UpdateBounding<CMeshO>::Box(ball);
  MapSource q(ball, HeightFieldParams);
  const QString told = RunHeightField(ball, q, nullptr).summary;
  EXPECT_TRUE(told.contains("; 50% of the layer's triangles, seen from above, face down (an object's far side"))
      << told.toStdString();
}

TEST(LodFilters, HeightFieldNamesBadParameters) {
  Mesh in;
  Bumpy(in, 10);
  auto error = [&](const char* name, double x, const QString& levels = "10%") {
    MapSource p(in, HeightFieldParams);
    p.set("levels", levels);
    if (name) p.set(name, x);
    try {
      RunHeightField(in, p, nullptr);
    } catch (const MLException& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error("separation", -1).find("separation must be a number at least 0"), std::string::npos);
  EXPECT_NE(error(nullptr, 0, "3").find("levels (the finest) must be between the 4 points on the hull"),
            std::string::npos) << error(nullptr, 0, "3");
  EXPECT_NE(error(nullptr, 0, "10,20").find("levels must get strictly coarser"), std::string::npos);
  EXPECT_NE(error("separationspace", 5).find("separationspace must be one of"), std::string::npos);
}

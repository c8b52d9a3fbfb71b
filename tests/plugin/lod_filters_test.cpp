// The plugin's filter logic on CMeshO: defaults, output layer data, untouched
// input, and MLException messages for bad input.
#include <gtest/gtest.h>
#include <cmath>
#include <map>
#include <common/mlexception.h>
#include "lod_filters.h"

namespace {
using namespace geodesic_lod;

// vcglib's mesh destructor leaves named attributes allocated: free them.
struct Mesh : CMeshO {
  ~Mesh() { ClearAttributes(); }
};

// Parameter values: the specs' defaults, overridable by name.
class MapSource : public ParamSource {
 public:
  explicit MapSource(const CMeshO& m, bool fps = false) {
    for (const ParamSpec& s : fps ? FpsLodParams(m) : PoissonLodParams(m)) v_[s.name] = s.defaultValue;
  }
  MapSource& set(const QString& n, double x) {
    EXPECT_TRUE(v_.count(n)) << n.toStdString();
    v_[n] = x;
    return *this;
  }
  double number(const QString& n) const override { return v_.at(n); }
  bool flag(const QString& n) const override { return v_.at(n) != 0; }
  int choice(const QString& n) const override { return int(v_.at(n)); }

 private:
  std::map<QString, double> v_;
};

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
  EXPECT_EQ(byName.at("metric").values.size(), 4);
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
  const QStringList skipped = FillLodLayer(in, run, out);
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
  FillLodLayer(in, RunPoissonLod(in, p, nullptr), kept);
  for (const auto& v : kept.vert) EXPECT_EQ(v.cN(), Point3m(0, 0, 3));
  p.set("recomputenormals", 1);
  FillLodLayer(in, RunPoissonLod(in, p, nullptr), recomputed);
  for (const auto& v : recomputed.vert) EXPECT_NEAR(v.cN().Norm(), 1.0, 1e-6);
}

TEST(LodFilters, BadInputRaisesMLExceptionWithAMessage) {
  Mesh empty;
  EXPECT_NE(ErrorOf(empty, MapSource(empty)).find("no vertices"), std::string::npos);
  Mesh m;
  Bumpy(m, 10);
  EXPECT_NE(ErrorOf(m, MapSource(m).set("radius", 0)).find("radius must be a positive"), std::string::npos);
  EXPECT_NE(ErrorOf(m, MapSource(m).set("normalneighbors", 100)).find("normalneighbors (100)"), std::string::npos);
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
  FillLodLayer(in, run, out);
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
    FillLodLayer(in, run, out);
    ASSERT_GT(out.fn, 10);
    for (const auto& f : out.face)
      for (int c = 0; c < 3; ++c) {
        const size_t k = vcg::tri::Index(out, f.cV(c));
        ASSERT_LT(k, size_t(out.vn));
        EXPECT_EQ(f.cP(c), in.vert[run.result.vertIndex[k]].cP());
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
    EXPECT_NE(std::string(e.what()).find("needs a layer with faces"), std::string::npos);
  }
}

TEST(LodFilters, NormalVariationFilterGivesEq1ForEveryVertexInPlace) {
  const FilterDef& f = Filters().at(2);
  EXPECT_EQ(f.pythonName(), "compute_scalar_by_normal_variation");
  EXPECT_FALSE(f.newLayer);
  Mesh in;
  Bumpy(in, 30);
  struct Src : ParamSource {
    double number(const QString&) const override { return 20; }
    bool flag(const QString&) const override { return false; }
    int choice(const QString&) const override { return 0; }
  } src;
  const LodRun run = f.run(in, src, nullptr);
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
}

// The apply step on a real MeshLab 2025.07 document: a filter adds all its
// output layers or none, whatever fails while they are written.
#include <gtest/gtest.h>
#include <cmath>
#include <new>
#include <string>
#include <common/ml_document/mesh_document.h>
#include "apply_lod.h"

namespace {
using namespace geodesic_lod;

// A document whose layer creation runs out of memory at the `failAt`-th new
// layer (counting from 1 once armed), as a large level would.
struct FailingDocument : MeshDocument {
  int failAt = 0, made = 0;
  ~FailingDocument() {  // vcglib's mesh destructor leaves named attributes allocated: free them
    for (MeshModel& m : meshIterator()) m.cm.ClearAttributes();
  }
  MeshModel* addNewMesh(const QString& path, const QString& label, bool current = true) {
    if (failAt > 0 && ++made == failAt) throw std::bad_alloc();
    return MeshDocument::addNewMesh(path, label, current);
  }
};

// Parameter values: the filter's defaults, overridden by name.
class Defaults : public ParamSource {
 public:
  Defaults(const FilterDef& f, const CMeshO& m) {
    for (const ParamSpec& s : f.params(m)) v_[s.name] = s.defaultValue, t_[s.name] = s.text;
  }
  Defaults& set(const QString& n, double x) { return v_.at(n) = x, *this; }
  Defaults& set(const QString& n, const QString& x) { return t_.at(n) = x, *this; }
  double number(const QString& n) const override { return v_.at(n); }
  bool flag(const QString& n) const override { return v_.at(n) != 0; }
  int choice(const QString& n) const override { return int(v_.at(n)); }
  QString text(const QString& n) const override { return t_.at(n); }
  const CMeshO* mesh(const QString&) const override { return nullptr; }

 private:
  std::map<QString, double> v_;
  std::map<QString, QString> t_;
};

size_t FilterIndex(const char* pythonName) {
  for (size_t f = 0; f < Filters().size(); ++f)
    if (Filters()[f].pythonName() == pythonName) return f;
  ADD_FAILURE() << pythonName;
  return 0;
}

// A 30 x 30 bumpy grid with faces, as the current (only) layer.
void AddInput(FailingDocument& md) {
  MeshModel* m = md.addNewMesh("", "input", true);
  const int n = 30;
  vcg::tri::Allocator<CMeshO>::AddVertices(m->cm, n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = double(i) / (n - 1), y = double(j) / (n - 1);
      m->cm.vert[i * n + j].P() = Point3m(x, y, 0.05 * std::sin(8 * x) * std::sin(8 * y));
    }
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      auto* v = &m->cm.vert[i * n + j];
      vcg::tri::Allocator<CMeshO>::AddFace(m->cm, v, v + n, v + n + 1);
      vcg::tri::Allocator<CMeshO>::AddFace(m->cm, v, v + n + 1, v + 1);
    }
  vcg::tri::UpdateBounding<CMeshO>::Box(m->cm);
}

std::string Apply(FailingDocument& md, size_t filter, const Defaults& p) {
  try {
    ApplyLod(filter, md, p, nullptr, [](const std::string&) {});
  } catch (const MLException& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(ApplyLod, APyramidAddsEveryLevelOrNone) {
  const size_t pyramid = FilterIndex("generate_geodesic_lod_pyramid");
  for (int triangles : {0, 1}) {
    for (int failAt : {0, 1, 2, 3}) {
      FailingDocument md;
      AddInput(md);
      MeshModel* input = md.mm();
      Defaults p(Filters()[pyramid], input->cm);
      p.set("levels", "40%,10%,20").set("output", triangles);
      md.failAt = failAt;
      const std::string error = Apply(md, pyramid, p);
      if (failAt == 0) {
        EXPECT_EQ(error, "");
        EXPECT_EQ(md.meshNumber(), 4u);
        continue;
      }
      EXPECT_NE(error.find("not enough memory"), std::string::npos) << error;
      EXPECT_EQ(md.meshNumber(), 1u) << "level " << failAt << " failed; the earlier levels must be gone";
      EXPECT_EQ(md.mm(), input);
      EXPECT_EQ(input->cm.vn, 900);
    }
  }
}

TEST(ApplyLod, ATriangleMeshLodWithRegionsAddsItsLayerOrNothing) {
  const size_t poisson = FilterIndex("generate_geodesic_poisson_lod");
  FailingDocument md;
  AddInput(md);
  MeshModel* input = md.mm();
  Defaults p(Filters()[poisson], input->cm);
  p.set("output", 1).set("regions", 1).set("radius", 0.1);
  md.failAt = 1;
  EXPECT_NE(Apply(md, poisson, p).find("not enough memory"), std::string::npos);
  EXPECT_EQ(md.meshNumber(), 1u);
  EXPECT_FALSE(input->hasDataMask(MeshModel::MM_VERTCOLOR)) << "the input was coloured by region";
  md.failAt = 0;
  EXPECT_EQ(Apply(md, poisson, p), "");
  EXPECT_EQ(md.meshNumber(), 2u);
  EXPECT_GT(md.mm()->cm.fn, 0);
  EXPECT_TRUE(input->hasDataMask(MeshModel::MM_VERTCOLOR));
}

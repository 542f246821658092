// The tool's pricing of skinned collapses (LodOptions::area_exponent, area_floor) judged on Testwuson in the
// frames make_lods() holds out, the way a user sees the LODs.
#include "helpers.hh"

#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/ImportFrames.hh>
#include <OpenMeshSkinned/Lod/LodAreaExponent.hh>
#include <OpenMeshSkinned/Lod/MakeLods.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <tuple>
#include <vector>

using namespace OpenMeshSkinned;

namespace {

// Each run once per process: two tests ask for the same one.
LodReport lod(double ratio, double exponent, double floor) {
  static const SkinnedMesh wuson = [] {
    SkinnedMesh m;
    import_skinned(omsk_test::model("X/Testwuson.X"), m);
    return m;
  }();
  static std::map<std::tuple<double, double, double>, LodReport> made;
  const auto key = std::make_tuple(ratio, exponent, floor);
  if (const auto it = made.find(key); it != made.end()) return it->second;
  LodOptions o;
  o.ratios = {ratio};
  o.area_exponent = exponent;
  o.area_floor = floor;
  const LodReport r = make_lods(wuson, o).levels.at(0).report;
  std::printf("%.0f%%, exponent %.2f, floor %.1f: held-out RMS %.4f%%, Hausdorff %.4f%%\n", 100 * ratio, exponent,
              floor, r.rms, r.hausdorff);
  return made[key] = r;
}

}  // namespace

TEST(AreaPricing, AutoOnTestwusonIsTheSquareRoot) {
  const LodReport automatic = lod(0.5, kAutoAreaExponent, 2.0), balanced = lod(0.5, 0.5, 2.0);
  EXPECT_EQ(automatic.rms, balanced.rms);
  EXPECT_EQ(automatic.hausdorff, balanced.hausdorff);
}

// Per area, a broad shallow bend costs as much as a narrow one of the same depth though it moves far more of
// the surface; over the square root of the area it costs more, and the surface as a whole stays closer.
TEST(AreaPricing, TheSquareRootOfTheAreaLowersTheRmsOfPerArea) {
  const LodReport balanced = lod(0.5, 0.5, 2.0), per_area = lod(0.5, 1.0, 0.0);
  EXPECT_LT(balanced.rms, 0.9 * per_area.rms);
}

// Without the floor a horn tip (small faces, far from the rest) is cheap again at the coarse end; below two of
// the coarsest level's triangles it keeps the per-area price.
TEST(AreaPricing, TheFloorKeepsTheWorstCaseOfAFeatureTheCoarsestLevelCanStillShow) {
  const LodReport floored = lod(0.1, 0.5, 2.0), bare = lod(0.1, 0.5, 0.0);
  EXPECT_LT(floored.hausdorff, 0.95 * bare.hausdorff);
}

// Left to the input, the power is the square root up to kSmallMeshVertices and per area above (where the
// square root measured the higher RMS): the LODs are those of the power asked for explicitly.
TEST(AreaPricing, AutoIsTheSquareRootOnSmallMeshesAndPerAreaOnLargeOnes) {
  LodOptions o;
  EXPECT_EQ(o.area_exponent, kAutoAreaExponent);
  EXPECT_EQ(lod_area_exponent(o, kSmallMeshVertices), 0.5);
  EXPECT_EQ(lod_area_exponent(o, kSmallMeshVertices + 1), 1.0);
  o.area_exponent = 0.0;
  EXPECT_EQ(lod_area_exponent(o, 10), 0.0);

  const SkinnedMesh leg = make_bending_cylinder(128, 160);  // 20,480 vertices
  ASSERT_GT(leg.n_vertices(), kSmallMeshVertices);
  auto points = [&](double exponent) {
    LodOptions q;
    q.ratios = {0.02};
    q.poses = 2;
    q.evaluate = q.refit = false;
    q.area_exponent = exponent;
    const LodChain chain = make_lods(leg, q);
    const SkinnedMesh& m = chain.levels.at(0).mesh;
    std::vector<float> p;
    for (auto vh : m.vertices())
      for (int k = 0; k < 3; ++k) p.push_back(m.point(vh)[k]);
    return p;
  };
  const auto automatic = points(kAutoAreaExponent);
  EXPECT_EQ(automatic, points(1.0));
  EXPECT_NE(automatic, points(0.5));
}

// Meshes animated without a skeleton (the frames method): the energy on light levels, a quarter power when the
// coarsest level keeps half of the triangles or fewer.
TEST(AreaPricing, AutoForTheFramesMethodIsAQuarterPowerOnlyForCoarseLevels) {
  LodOptions o;
  EXPECT_EQ(lod_frames_area_exponent(o, 0.5), 0.25);
  EXPECT_EQ(lod_frames_area_exponent(o, 0.51), 0.0);
  o.area_exponent = 1.0;
  EXPECT_EQ(lod_frames_area_exponent(o, 0.9), 1.0);
}

// Judged as the user sees it, in the frames make_lods() holds out, on Quake's faerie (198 stored frames, 654
// triangles) at 25 %, where the energy alone measures the higher RMS. Its Hausdorff distance was higher too
// until the final fit drew the LOD's faces to the original; since every stored frame is fitted on its own it
// is 13 % above the energy's in these frames (3.61 against 3.19 %) and the same on the peer benchmark's (3.38
// against 3.37 %, bench/README.md): the bound guards against the quarter power losing the worst case outright.
TEST(AreaPricing, TheQuarterPowerLowersTheFramesMethodsErrorOnAnMd2) {
  SkinnedMesh faerie;
  import_frame_animation({omsk_test::model("MD2/faerie.md2")}, faerie, {}, 10.0);
  auto lod = [&](double exponent) {
    LodOptions o;
    o.ratios = {0.25};
    o.area_exponent = exponent;
    const LodChain chain = make_lods(faerie, o);
    EXPECT_EQ(chain.method, "frames");
    const LodReport r = chain.levels.at(0).report;
    std::printf("faerie 25%%, exponent %.2f: held-out RMS %.4f%%, Hausdorff %.4f%%\n", exponent, r.rms, r.hausdorff);
    return r;
  };
  const LodReport automatic = lod(kAutoAreaExponent), energy = lod(0.0), quarter = lod(0.25);
  EXPECT_EQ(automatic.rms, quarter.rms);
  EXPECT_LT(quarter.rms, energy.rms);
  EXPECT_LT(quarter.hausdorff, 1.2 * energy.hausdorff);
}

// Import -> export glTF -> re-import: every clip, posed at 20 times, must put every vertex where the
// original puts it, within 1e-5 of the bounding-box diagonal.
#include "helpers.hh"
#include "validate.hh"

#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>
#include <OpenMeshSkinned/IO/ExportGltf.hh>

#include <filesystem>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;
namespace fs = std::filesystem;

namespace {

void expect_round_trip(const std::string& rel, const std::string& ext) {
  SCOPED_TRACE(rel + " via " + ext);
  Mesh a;
  import_skinned(omsk_test::model(rel), a);
  const fs::path out = fs::temp_directory_path() / ("omsk_rt_" + std::to_string(::getpid()) + ext);
  export_gltf(a, out.string());
  omsk_test::expect_valid_gltf(out.string());
  Mesh b;
  import_skinned(out.string(), b);
  fs::remove(out);

  EXPECT_EQ(a.n_faces(), b.n_faces());
  ASSERT_EQ(clips(a).size(), clips(b).size());
  const double diag = bbox_diagonal(a);
  const double tol = 1e-5 * diag;

  // Vertex order may change through glTF; pair each vertex of a with the vertices of b at the same rest
  // position (several when unwelded copies share a position) and take the closest posed match.
  std::vector<std::vector<int>> partners(a.n_vertices());
  {
    std::vector<std::pair<Eigen::Vector3d, int>> bs;
    for (auto vh : b.vertices()) bs.push_back({to_eigen(b.point(vh)), vh.idx()});
    std::sort(bs.begin(), bs.end(), [](const auto& x, const auto& y) { return x.first.x() < y.first.x(); });
    for (auto vh : a.vertices()) {
      const Eigen::Vector3d p = to_eigen(a.point(vh));
      auto it =
          std::lower_bound(bs.begin(), bs.end(), p.x() - tol, [](const auto& e, double x) { return e.first.x() < x; });
      for (; it != bs.end() && it->first.x() <= p.x() + tol; ++it)
        if ((it->first - p).norm() <= tol) partners[vh.idx()].push_back(it->second);
      ASSERT_FALSE(partners[vh.idx()].empty()) << "vertex " << vh.idx() << " lost in the round trip";
    }
  }

  const Skeleton& sa = skeleton(a);
  const Skeleton& sb = skeleton(b);
  double worst = 0.0;
  for (size_t c = 0; c < clips(a).size(); ++c) {
    const Clip& ca = clips(a)[c];
    const Clip& cb = clips(b)[c];
    EXPECT_EQ(ca.name, cb.name);
    EXPECT_NEAR(ca.duration, cb.duration, 1e-3 * std::max(1.0, ca.duration));
    for (int i = 0; i < 20; ++i) {
      const double t = ca.duration * i / 19.0;
      const auto pa = skin_positions(a, sample_pose(sa, ca, t));
      const auto pb = skin_positions(b, sample_pose(sb, cb, t));
      for (auto vh : a.vertices()) {
        double best = HUGE_VAL;
        for (int j : partners[vh.idx()]) best = std::min(best, (pa[vh.idx()] - pb[j]).norm());
        worst = std::max(worst, best);
      }
    }
  }
  ::testing::Test::RecordProperty("worst_relative_deviation", std::to_string(worst / diag));
  EXPECT_GT(clips(a).size(), 0u);
  EXPECT_LE(worst, tol) << "worst posed deviation " << worst / diag << " of the diagonal";
}

}  // namespace

TEST(RoundTrip, TestwusonX) {
  expect_round_trip("X/Testwuson.X", ".glb");
  expect_round_trip("X/Testwuson.X", ".gltf");
}
TEST(RoundTrip, AnimationWithSkeletonFbx) { expect_round_trip("FBX/animation_with_skeleton.fbx", ".glb"); }
TEST(RoundTrip, SimpleSkinGltf) { expect_round_trip("glTF2/simple_skin/simple_skin.gltf", ".gltf"); }

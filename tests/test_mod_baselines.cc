// The other cost models and weight-update rules, against which the skinned quadric is judged.
#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/ModDeformationSensitiveT.hh>
#include <OpenMeshSkinned/Decimater/ModRestPoseQuadricT.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Solver/WeightRules.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {
Influences skin(std::initializer_list<JointWeight> l) {
  Influences inf;
  for (const auto& jw : l) inf.push(jw.joint, jw.weight);
  inf.sort();
  return inf;
}

enum class Method { Skinned, Dsd, Rest };

// Decimates with one priority module plus the shared fold-over check; returns the held-out RMS.
double heldout_rms(const Mesh& original, Method method, double ratio, const Pose& held_out) {
  Mesh mesh = original;
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModSkinnedQuadricT<Mesh>::Handle hq;
  ModDeformationSensitiveT<Mesh>::Handle hd;
  ModRestPoseQuadricT<Mesh>::Handle hr;
  ModSkinnedFoldOverT<Mesh>::Handle hf;
  if (method == Method::Skinned) dec.add(hq);
  if (method == Method::Dsd) dec.add(hd);
  if (method == Method::Rest) dec.add(hr);
  dec.add(hf);
  EXPECT_TRUE(dec.initialize());
  dec.decimate_to_faces(0, static_cast<size_t>(ratio * mesh.n_faces()));
  mesh.garbage_collection();
  EXPECT_LE(mesh.n_faces(), static_cast<size_t>(1.2 * ratio * original.n_faces()) + 2);
  return omsk_test::posed_rms(original, mesh, held_out);
}
}  // namespace

TEST(WeightRules, PowerSkinningOnTwoEquidistantVerticesAverages) {
  const Influences a = skin({{0, 1.0}}), b = skin({{1, 0.6}, {2, 0.4}});
  const Influences m = merge_weights(WeightRule::PowerSkinning, Eigen::Vector3d(0.5, 0, 0), Eigen::Vector3d(0, 0, 0), a,
                                     Eigen::Vector3d(1, 0, 0), b, 4);
  EXPECT_NEAR(m.weight_of(0), 0.5, 1e-12);
  EXPECT_NEAR(m.weight_of(1), 0.3, 1e-12);
  EXPECT_NEAR(m.weight_of(2), 0.2, 1e-12);
}

TEST(WeightRules, DistanceInterpolationFollowsThePlacement) {
  const Influences a = skin({{0, 1.0}}), b = skin({{1, 1.0}});
  const Eigen::Vector3d p0(0, 0, 0), p1(4, 0, 0);
  // At a quarter of the way from v0: t = 1/4, three quarters of v0's skin.
  const Influences m = merge_weights(WeightRule::DistanceInterpolation, Eigen::Vector3d(1, 0, 0), p0, a, p1, b, 4);
  EXPECT_NEAR(m.weight_of(0), 0.75, 1e-12);
  // For an edge, Savoye-Meyer's power skinning is the same blend.
  const Influences q = merge_weights(WeightRule::PowerSkinning, Eigen::Vector3d(1, 0, 0), p0, a, p1, b, 4);
  EXPECT_TRUE(m == q);
  // At an endpoint, that endpoint's skin.
  EXPECT_TRUE(merge_weights(WeightRule::DistanceInterpolation, p1, p0, a, p1, b, 4) == b);
}

TEST(WeightRules, NearestEndpointCopiesAndEveryRuleRespectsTheCap) {
  const Influences a = skin({{0, 0.5}, {1, 0.3}, {2, 0.2}}), b = skin({{3, 0.7}, {4, 0.3}});
  const Eigen::Vector3d p0(0, 0, 0), p1(1, 0, 0);
  EXPECT_TRUE(merge_weights(WeightRule::NearestEndpoint, Eigen::Vector3d(0.2, 0, 0), p0, a, p1, b, 4) == a);
  for (WeightRule r : {WeightRule::NearestEndpoint, WeightRule::DistanceInterpolation, WeightRule::PowerSkinning}) {
    const Influences m = merge_weights(r, Eigen::Vector3d(0.5, 0.1, 0), p0, a, p1, b, 2);
    EXPECT_LE(m.size(), 2);
    EXPECT_NEAR(m.sum(), 1.0, 1e-12);
    for (const auto& jw : m) EXPECT_GT(jw.weight, 0.0);
  }
}

TEST(Baselines, OnTheBindPoseAloneDsdPricesWhatTheRestQuadricPricesAtV1) {
  Mesh mesh = make_bending_cylinder(12, 12);
  example_poses(mesh) = {Pose::identity(skeleton(mesh).size())};
  std::vector<PoseQuadric> rest(mesh.n_vertices());
  accumulate_quadrics(
      mesh, 1, [&](Mesh::VertexHandle v, int) { return to_eigen(mesh.point(v)); },
      [&](Mesh::VertexHandle v, int) -> PoseQuadric& { return rest[v.idx()]; });
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModDeformationSensitiveT<Mesh>::Handle hd;
  dec.add(hd);
  ASSERT_TRUE(dec.initialize());
  for (auto heh : mesh.halfedges()) {
    OpenMesh::Decimater::CollapseInfoT<Mesh> ci(mesh, heh);
    PoseQuadric q = rest[ci.v0.idx()];
    q += rest[ci.v1.idx()];
    const double expect = std::max(0.0, q(to_eigen(mesh.point(ci.v1))));
    EXPECT_NEAR(dec.module(hd).collapse_priority(ci), expect, 1e-6 * (1.0 + expect));
  }
}

TEST(Baselines, RestQuadricMovesTheSurvivorAndBlendsWeights) {
  Mesh mesh = make_bending_cylinder(16, 32);
  const Mesh original = mesh;
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModRestPoseQuadricT<Mesh>::Handle hr;
  ModWeightCapT<Mesh>::Handle hc;
  dec.add(hr);
  dec.add(hc);
  dec.module(hc).set_max_influences(2);
  ASSERT_TRUE(dec.initialize());
  dec.decimate_to_faces(0, mesh.n_faces() / 10);
  mesh.garbage_collection();
  EXPECT_LE(mesh.n_faces(), original.n_faces() / 8);
  omsk_test::expect_valid_skin(mesh, 2);
}

TEST(Baselines, HeldOutErrorRanksSkinnedFirstOnTheBendingLeg) {
  // Example poses: knee at 0 and 90 degrees; held out: 45 degrees. 5% of the triangles.
  const Mesh original = make_bending_cylinder(32, 64);
  const Pose held_out = sample_pose(skeleton(original), clips(original)[0], 0.5);
  const double skinned = heldout_rms(original, Method::Skinned, 0.05, held_out);
  const double dsd = heldout_rms(original, Method::Dsd, 0.05, held_out);
  const double rest = heldout_rms(original, Method::Rest, 0.05, held_out);
  ::testing::Test::RecordProperty("skinned", std::to_string(skinned));
  ::testing::Test::RecordProperty("dsd", std::to_string(dsd));
  ::testing::Test::RecordProperty("rest", std::to_string(rest));
  std::cout << "held-out RMS (fraction of diagonal): skinned " << skinned << ", dsd " << dsd << ", rest " << rest << "\n";
  EXPECT_LE(skinned, dsd);
  EXPECT_LE(skinned, rest);
  EXPECT_LE(dsd, rest);
}

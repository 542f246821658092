// The other cost models and weight-update rules, against which the skinned quadric is judged.
#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/Baselines/ModDeformationSensitiveT.hh>
#include <OpenMeshSkinned/Decimater/Baselines/ModPoseIndependentQuadricT.hh>
#include <OpenMeshSkinned/Decimater/Baselines/ModRestPoseQuadricT.hh>
#include <OpenMeshSkinned/Decimater/LazyDecimaterT.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {
enum class Method { Skinned, Dsd, Rest, DeCoro };

// Decimates with one priority module plus the shared fold-over check; returns the held-out RMS.
double heldout_rms(const Mesh& original, Method method, double ratio, const Pose& held_out) {
  Mesh mesh = original;
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModSkinnedQuadricT<Mesh>::Handle hq;
  ModDeformationSensitiveT<Mesh>::Handle hd;
  ModRestPoseQuadricT<Mesh>::Handle hr;
  ModPoseIndependentQuadricT<Mesh>::Handle hp;
  ModSkinnedFoldOverT<Mesh>::Handle hf;
  if (method == Method::DeCoro) dec.add(hp);
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
  const double decoro = heldout_rms(original, Method::DeCoro, 0.05, held_out);
  ::testing::Test::RecordProperty("decoro", std::to_string(decoro));
  ::testing::Test::RecordProperty("skinned", std::to_string(skinned));
  ::testing::Test::RecordProperty("dsd", std::to_string(dsd));
  ::testing::Test::RecordProperty("rest", std::to_string(rest));
  std::cout << "held-out RMS (fraction of diagonal): skinned " << skinned << ", dsd " << dsd << ", rest " << rest
            << ", decoro " << decoro << "\n";
  EXPECT_LE(skinned, dsd);
  EXPECT_LE(skinned, rest);
  EXPECT_LE(dsd, rest);
  EXPECT_LE(skinned, decoro);
}

TEST(Baselines, DeCoroWithAllPosesAtBindIsTheRestPoseQuadric) {
  // A distribution that always gives the bind pose pulls every quadric back unchanged: DeCoro prices
  // and places every collapse exactly as the rest-pose quadric does.
  Mesh a = make_bending_cylinder(16, 32), b = a;
  OpenMesh::Decimater::DecimaterT<Mesh> da(a), db(b);
  ModPoseIndependentQuadricT<Mesh>::Handle hp;
  ModRestPoseQuadricT<Mesh>::Handle hr;
  da.add(hp);
  db.add(hr);
  for (int j = 0; j < skeleton(a).size(); ++j) {
    JointDistribution d;
    d.kind = JointDistribution::Box;  // degenerate: always 0 degrees
    da.module(hp).set_joint_distribution(j, d);
  }
  ASSERT_TRUE(da.initialize());
  ASSERT_TRUE(db.initialize());
  for (auto heh : a.halfedges()) {
    OpenMesh::Decimater::CollapseInfoT<Mesh> ca(a, heh), cb(b, heh);
    const double pa = da.module(hp).collapse_priority(ca), pb = db.module(hr).collapse_priority(cb);
    EXPECT_NEAR(pa, pb, 1e-6 * (1.0 + std::abs(pb)));
    // Where several placements tie (a flat strip), rounding may pick another one of equal error.
    const auto& ra = da.module(hp).solver().solve(ca);
    const auto& rb = db.module(hr).solver().solve(cb);
    if ((ra.position - rb.position).norm() < 1e-9) {
      for (const auto& jw : rb.weights) EXPECT_NEAR(ra.weights.weight_of(jw.joint), jw.weight, 1e-9);
    }
  }
}

TEST(Baselines, DeCoroSamplesItsDistributions) {
  // A Gaussian knee around 45 degrees: the pulled-back quadrics differ from the rest pose's, so the
  // decimation differs from the rest-pose quadric's.
  const Mesh original = make_bending_cylinder(16, 32);
  Mesh a = original, b = original;
  OpenMesh::Decimater::DecimaterT<Mesh> da(a);
  ModPoseIndependentQuadricT<Mesh>::Handle hp;
  da.add(hp);
  JointDistribution knee;
  knee.kind = JointDistribution::Gaussian;
  knee.preferred = 45.0;
  knee.stiffness = 10.0;
  da.module(hp).set_joint_distribution(1, knee);
  da.module(hp).set_samples(16);
  ASSERT_TRUE(da.initialize());
  EXPECT_EQ(da.module(hp).samples_used(), 16u);
  da.decimate_to_faces(0, a.n_faces() / 5);
  OpenMesh::Decimater::DecimaterT<Mesh> db(b);
  ModRestPoseQuadricT<Mesh>::Handle hr;
  db.add(hr);
  ASSERT_TRUE(db.initialize());
  db.decimate_to_faces(0, b.n_faces() / 5);
  a.garbage_collection();
  b.garbage_collection();
  double diff = 0.0;
  for (auto vh : a.vertices())
    if (vh.idx() < int(b.n_vertices())) diff += (a.point(vh) - b.point(Mesh::VertexHandle(vh.idx()))).norm();
  EXPECT_GT(diff, 1e-3);
}

TEST(Baselines, TheQuadricBaselinesTakeFallbackPlacementsPricedByTheirOwnQuadric) {
  // DeCoro's and the rest-pose quadric price a placement other than their optimum themselves, so the fold
  // check's fallback placements serve them too: at 20 degrees on Testwuson they go further, fold nothing,
  // and each fallback collapse was priced by the module's quadric at the placement it was made at.
  for (Method method : {Method::DeCoro, Method::Rest}) {
    size_t faces[2] = {0, 0}, fallbacks[2] = {0, 0};
    for (int fallback = 0; fallback < 2; ++fallback) {
      Mesh mesh = omsk_test::load_character("X/Testwuson.X", 8);
      LazyDecimaterT<Mesh> dec(mesh);
      ModRestPoseQuadricT<Mesh>::Handle hr;
      ModPoseIndependentQuadricT<Mesh>::Handle hp;
      ModSkinnedFoldOverT<Mesh>::Handle hf;
      omsk_test::FlipWatcherT<Mesh>::Handle hw;
      if (method == Method::DeCoro)
        dec.add(hp);
      else
        dec.add(hr);
      dec.add(hf);
      dec.add(hw);
      dec.module(hf).set_max_angle(20.0);
      dec.module(hf).set_fallback_placement(fallback == 1);
      dec.module(hw).max_angle_deg = 20.0;
      ASSERT_TRUE(dec.initialize());
      dec.decimate_to_faces(0, mesh.n_faces() / 100);
      EXPECT_EQ(dec.module(hw).flipped, 0u);
      fallbacks[fallback] = dec.module(hf).solver().stats().fold_fallbacks;
      mesh.garbage_collection();
      faces[fallback] = mesh.n_faces();
      omsk_test::expect_valid_skin(mesh, Influences::kCapacity);
    }
    EXPECT_EQ(fallbacks[0], 0u);
    EXPECT_GT(fallbacks[1], 0u);
    EXPECT_LT(faces[1], faces[0] * 9 / 10) << faces[0] << " -> " << faces[1];
  }
}

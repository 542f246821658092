#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Skin/Validate.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

TEST(Influences, SortedByWeightAndNormalised) {
  Influences inf;
  inf.push(3, 0.2);
  inf.push(1, 0.5);
  inf.push(2, 0.3);
  inf.sort();
  EXPECT_EQ(inf[0].joint, 1);
  EXPECT_EQ(inf[2].joint, 3);
  inf.truncate_and_normalize(2);
  EXPECT_EQ(inf.size(), 2);
  EXPECT_NEAR(inf[0].weight, 0.625, 1e-12);
  EXPECT_NEAR(inf.sum(), 1.0, 1e-12);
}

TEST(Influences, CapacityIsFixed) {
  Influences inf;
  for (int i = 0; i < Influences::kCapacity; ++i) EXPECT_TRUE(inf.push(i, 1.0));
  EXPECT_FALSE(inf.push(99, 1.0));
  EXPECT_EQ(inf.size(), Influences::kCapacity);
}

namespace {
Mesh two_triangles() {
  Mesh mesh;
  mesh.request_vertex_status();
  auto h = add_skin(mesh);
  Joint j;
  j.name = "root";
  skeleton(mesh).joints = {j, j};
  skeleton(mesh).joints[1].parent = 0;
  auto a = mesh.add_vertex({0, 0, 0}), b = mesh.add_vertex({1, 0, 0}), c = mesh.add_vertex({0, 1, 0}),
       d = mesh.add_vertex({1, 1, 0});
  mesh.add_face(a, b, c);
  mesh.add_face(b, d, c);
  for (auto v : mesh.vertices()) mesh.property(h, v) = Influences::rigid(0);
  return mesh;
}
}  // namespace

TEST(Validate, AcceptsAndRenormalisesSmallDeviation) {
  Mesh mesh = two_triangles();
  auto h = influences_handle(mesh);
  Influences inf;
  inf.push(0, 0.6);
  inf.push(1, 0.399);
  mesh.property(h, Mesh::VertexHandle(0)) = inf;
  const auto rep = validate_skin(mesh);
  EXPECT_EQ(rep.vertices_renormalized, 1u);
  EXPECT_NEAR(mesh.property(h, Mesh::VertexHandle(0)).sum(), 1.0, 1e-15);
}

TEST(Validate, RejectsEachKindOfBadSkinWithAPreciseMessage) {
  struct Case {
    std::vector<JointWeight> w;
    const char* expect;
  };
  const std::vector<Case> cases = {
      {{{0, std::nan("")}}, "non-finite"},
      {{{0, 1.5}, {1, -0.5}}, "negative"},
      {{{0, 0.5}}, "sum to 0.5"},
      {{{0, 0.0}}, "sum to 0"},
      {{{7, 1.0}}, "out of range"},
      {{}, "no bone influences"},
  };
  for (const auto& c : cases) {
    Mesh mesh = two_triangles();
    Influences inf;
    for (const auto& jw : c.w) inf.push(jw.joint, jw.weight);
    mesh.property(influences_handle(mesh), Mesh::VertexHandle(2)) = inf;
    try {
      validate_skin(mesh);
      ADD_FAILURE() << "accepted a skin that should fail with: " << c.expect;
    } catch (const SkinError& e) {
      EXPECT_NE(std::string(e.what()).find("vertex 2"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.expect), std::string::npos) << e.what();
    }
  }
}

TEST(Validate, RejectsMoreInfluencesThanAllowed) {
  Mesh mesh = two_triangles();
  Influences inf;
  for (int i = 0; i < 2; ++i) inf.push(i, 0.5);
  mesh.property(influences_handle(mesh), Mesh::VertexHandle(1)) = inf;
  ValidationOptions opt;
  opt.max_influences = 1;
  EXPECT_THROW(validate_skin(mesh, opt), SkinError);
}

TEST(LinearBlendSkinning, BlendsJointMatrices) {
  Pose pose = Pose::identity(2);
  pose.joint[1].col(3) = Eigen::Vector3d(2, 0, 0);  // joint 1 translates by +2x
  Influences inf;
  inf.push(0, 0.25);
  inf.push(1, 0.75);
  const Eigen::Vector3d p = skin_point(Eigen::Vector3d(1, 1, 1), inf, pose);
  EXPECT_TRUE(p.isApprox(Eigen::Vector3d(2.5, 1, 1)));
}

TEST(LinearBlendSkinning, BindPoseLeavesTheMeshInPlace) {
  Mesh mesh = make_bending_cylinder(8, 8);
  const auto posed = skin_positions(mesh, Pose::identity(skeleton(mesh).size()));
  for (auto vh : mesh.vertices()) EXPECT_TRUE(posed[vh.idx()].isApprox(to_eigen(mesh.point(vh))));
  const auto normals = skin_face_normals(mesh, posed);
  for (auto fh : mesh.faces()) {
    // The generated tube faces outwards.
    const auto c = mesh.calc_face_centroid(fh);
    EXPECT_GT(normals[fh.idx()].dot(Eigen::Vector3d(c[0], 0, c[2])), 0.0);
  }
}

TEST(Clip, InterpolatesTranslationLinearlyAndRotationBySlerp) {
  Skeleton skel;
  Joint j;
  j.name = "a";
  skel.joints.push_back(j);
  Clip clip;
  clip.duration = 2.0;
  Channel ch;
  ch.joint = 0;
  ch.translation_times = {0.0, 2.0};
  ch.translations = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 0, 0)};
  ch.rotation_times = {0.0, 2.0};
  ch.rotations = {Eigen::Quaterniond::Identity(), Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()))};
  clip.channels.push_back(ch);
  const auto locals = sample_locals(skel, clip, 1.0);
  EXPECT_NEAR(locals[0](0, 3), 2.0, 1e-12);
  const Eigen::Matrix3d r = locals[0].topLeftCorner<3, 3>();
  EXPECT_TRUE(r.isApprox(Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-12));
  // Outside the clip, the ends hold.
  EXPECT_NEAR(sample_locals(skel, clip, 5.0)[0](0, 3), 4.0, 1e-12);
}

TEST(Clip, EvenlySpacedPosesIncludeBothEnds) {
  Mesh mesh = make_bending_cylinder(8, 8);
  const auto poses = sample_poses_evenly(skeleton(mesh), clips(mesh)[0], 3);
  ASSERT_EQ(poses.size(), 3u);
  // Knee joint (1) at 0, 45 and 90 degrees about x.
  const double angles[3] = {0.0, 45.0, 90.0};
  for (int i = 0; i < 3; ++i) {
    const Eigen::Matrix3d r = poses[i].joint[1].leftCols<3>();
    EXPECT_NEAR(Eigen::AngleAxisd(r).angle() * 180.0 / M_PI, angles[i], 1e-9);
  }
  EXPECT_TRUE(poses[0].joint[0].isApprox(Affine3::Identity()));
}

TEST(Trs, DecomposeComposeRoundTrip) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Matrix4d m = compose_trs(Eigen::Vector3d(1, -2, 3), q, Eigen::Vector3d(2, 0.5, 1.5));
  Eigen::Vector3d t, s;
  Eigen::Quaterniond r;
  decompose_trs(m, t, r, s);
  EXPECT_TRUE(compose_trs(t, r, s).isApprox(m, 1e-12));
}

#include <OpenMeshSkinned/Skin/PoseSchedule.hh>

namespace {
std::vector<Clip> two_clips() {
  Clip a, b;
  a.name = "a";
  a.duration = 2.0;
  b.name = "b";
  b.duration = 1.0;
  return {a, b};
}
}  // namespace

TEST(PoseSchedule, EvenlySpacedOverOneClipWithMidpointsAndOtherClipsHeldOut) {
  const auto s = make_pose_schedule(two_clips(), 3, 0);
  ASSERT_EQ(s.examples.size(), 3u);
  EXPECT_DOUBLE_EQ(s.examples[1].time, 1.0);
  EXPECT_DOUBLE_EQ(s.examples[2].time, 2.0);
  // Midpoints 0.5, 1.5 of clip a, then four frames of clip b.
  ASSERT_EQ(s.held_out.size(), 6u);
  EXPECT_DOUBLE_EQ(s.held_out[0].time, 0.5);
  EXPECT_EQ(s.held_out[2].clip, 1);
  for (const auto& h : s.held_out)
    for (const auto& e : s.examples) EXPECT_FALSE(h.clip == e.clip && h.time == e.time);
}

TEST(PoseSchedule, SpreadsOverAllClipsEndToEnd) {
  const auto s = make_pose_schedule(two_clips(), 4, -1);
  ASSERT_EQ(s.examples.size(), 4u);
  // Timeline 0..3: 0 (a@0), 1 (a@1), 2 (b@0), 3 (b@1).
  EXPECT_EQ(s.examples[2].clip, 1);
  EXPECT_DOUBLE_EQ(s.examples[2].time, 0.0);
  EXPECT_EQ(s.examples[3].clip, 1);
  EXPECT_DOUBLE_EQ(s.examples[3].time, 1.0);
  EXPECT_EQ(s.held_out.size(), 3u);
}

TEST(PoseSchedule, RejectsBadRequests) {
  EXPECT_THROW(make_pose_schedule(two_clips(), 0, -1), std::invalid_argument);
  EXPECT_THROW(make_pose_schedule(two_clips(), 2, 5), std::invalid_argument);
  EXPECT_THROW(make_pose_schedule({}, 2, -1), std::invalid_argument);
}

#include <OpenMeshSkinned/Mesh/LoopSubdivision.hh>

TEST(LoopSubdivision, QuadruplesTrianglesAndRefinesWeightsLikePositions) {
  const Mesh coarse = make_bending_cylinder(8, 8);
  const Mesh fine = loop_subdivide(coarse);
  EXPECT_EQ(fine.n_faces(), 4 * coarse.n_faces());
  EXPECT_EQ(fine.n_vertices(), coarse.n_vertices() + coarse.n_edges());
  omsk_test::expect_valid_skin(fine, Influences::kCapacity);
  // Weights are blended with the position masks: along the tube the knee weight still rises with height,
  // and a new vertex's weight lies within its parents' range.
  const auto h = influences_handle(fine);
  for (auto vh : fine.vertices()) {
    const double y = fine.point(vh)[1];
    const double w = fine.property(h, vh).weight_of(1);
    if (y < 0.7) EXPECT_LT(w, 0.01) << y;
    if (y > 1.3) EXPECT_GT(w, 0.99) << y;
  }
  // The skeleton and the clips come along.
  EXPECT_EQ(clips(fine).size(), clips(coarse).size());
  EXPECT_EQ(skeleton(fine).size(), skeleton(coarse).size());
}

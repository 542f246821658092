// Clips and joint transforms (Skin/Skeleton.hh).
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/Procedural.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

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
  ch.rotations = {Eigen::Quaterniond::Identity(),
                  Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()))};
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

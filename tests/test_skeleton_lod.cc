// Skeleton LoD: energy and labels with known answers, removed joints' motion baked so kept joints move as
// before, and skins re-solved (not only reassigned) for the reduced skeleton.
#include "helpers.hh"

#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>
#include <OpenMeshSkinned/Skin/KeyReduction.hh>
#include <OpenMeshSkinned/Skin/PoseSchedule.hh>
#include <OpenMeshSkinned/Skin/SkeletonLod.hh>
#include <OpenMeshSkinned/Solver/SkeletonLodT.hh>

using namespace OpenMeshSkinned;

namespace {

Skeleton chain_of(const std::vector<int>& parents) {
  Skeleton s;
  for (size_t j = 0; j < parents.size(); ++j) {
    Joint joint;
    joint.name = "j" + std::to_string(j);
    joint.parent = parents[j];
    joint.rest_local.block<3, 1>(0, 3) = Eigen::Vector3d(0, 1, 0);
    s.joints.push_back(joint);
  }
  return s;
}

Eigen::Quaterniond about_x(double a) { return Eigen::Quaterniond(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX())); }

}  // namespace

TEST(SkeletonLod, EnergyOfASwingThatReturnsIsItsTotalVariation) {
  const Skeleton s = chain_of({-1, 0, 1, 2});  // depth 3
  Clip clip;
  clip.duration = 2.0;
  Channel ch;
  ch.joint = 1;
  ch.rotation_times = {0, 1, 2};
  ch.rotations = {about_x(0.0), about_x(0.5), about_x(0.0)};
  clip.channels = {ch};
  const auto e = joint_energy(s, {clip});
  // rho(1) = (3 - 1) / 3; variation 0.5 + 0.5 rad; / pi.
  EXPECT_NEAR(e[1], 2.0 / 3.0 * 1.0 / M_PI, 1e-9);
  EXPECT_EQ(e[0], 0.0);
  EXPECT_EQ(e[2], 0.0);
}

TEST(SkeletonLod, AnEnergyThresholdRemovesExactlyTheMinorJointsUnderIt) {
  const Skeleton s = chain_of({-1, 0, 1, 2, 3});  // root, three minor joints, an end-effector
  Clip clip;
  clip.duration = 2.0;
  for (int j : {1, 2}) {  // joint 1 swings 0.2 rad and back, joint 2 0.8 rad and back
    Channel ch;
    ch.joint = j;
    ch.rotation_times = {0, 1, 2};
    const double a = j == 1 ? 0.2 : 0.8;
    ch.rotations = {about_x(0.0), about_x(a), about_x(0.0)};
    clip.channels.push_back(ch);
  }
  const auto e = joint_energy(s, {clip});
  ASSERT_LT(e[3], e[1]);  // joint 3 never moves
  ASSERT_LT(e[1], e[2]);
  const auto r = reduce_skeleton(s, {clip}, s.size(), nullptr, 0.5 * (e[1] + e[2]));
  EXPECT_EQ(r.new_index[1], -1);
  EXPECT_GE(r.new_index[2], 0);
  EXPECT_EQ(r.new_index[3], -1);
  EXPECT_EQ(r.skeleton.size(), 3);
}

TEST(SkeletonLod, LabelsOfASmallHumanoid) {
  // root - spine - chest; chest has neck-head, left arm-hand, right arm-hand.
  const Skeleton s = chain_of({-1, 0, 1, 2, 3, 2, 5, 2, 7});
  const auto l = label_joints(s);
  EXPECT_EQ(l[0], JointLabel::Root);
  EXPECT_EQ(l[2], JointLabel::Major);  // 4 neighbours > 1.9 x 16/9, depth 2 < 24/9
  for (int j : {4, 6, 8}) EXPECT_EQ(l[j], JointLabel::EndEffector) << j;
  for (int j : {1, 3, 5, 7}) EXPECT_EQ(l[j], JointLabel::Minor) << j;
  // Only minor joints go, the least energetic first, whatever the budget.
  const auto r = reduce_skeleton(s, {}, 2);
  EXPECT_EQ(r.skeleton.size(), 5);
  for (int j : {0, 2, 4, 6, 8}) EXPECT_GE(r.new_index[j], 0) << j;
  EXPECT_EQ(r.heir[3], 2);
  EXPECT_EQ(r.skeleton.joints[r.new_index[4]].parent, r.new_index[2]);  // the head hangs from the chest now
}

TEST(SkeletonLod, KeptJointsMoveAsBeforeInEveryClip) {
  const omsk_test::Mesh mesh = omsk_test::load_character("X/Testwuson.X", 2);
  const Skeleton& skel = skeleton(mesh);
  const auto r = reduce_skeleton(skel, clips(mesh), skel.size() * 6 / 10);
  ASSERT_LT(r.skeleton.size(), skel.size());
  const double extent = bbox_diagonal(mesh);
  for (size_t c = 0; c < clips(mesh).size(); ++c) {
    const std::vector<double> keys = key_times_and_midpoints(r.clips[c]);
    for (size_t i = 0; i < keys.size(); ++i) {
      // Exactly at the baked keys (even entries); between them, as closely as interpolating the product
      // of two interpolated transforms allows.
      const double tol = i % 2 == 0 ? 1e-9 * extent : 1e-3 * extent;
      const auto before = skel.globals(sample_locals(skel, clips(mesh)[c], keys[i]));
      const auto after = r.skeleton.globals(sample_locals(r.skeleton, r.clips[c], keys[i]));
      for (int j = 0; j < skel.size(); ++j) {
        if (r.new_index[j] < 0) continue;
        ASSERT_LT((before[j] - after[r.new_index[j]]).cwiseAbs().maxCoeff(), tol)
            << skel.joints[j].name << " clip " << c << " t " << keys[i];
      }
    }
  }
}

TEST(SkeletonLod, ReSolvedSkinsFitHeldOutFramesBetterThanHandedOverOnes) {
  omsk_test::Mesh original = omsk_test::load_character("X/Testwuson.X", 8);
  const int n = skeleton(original).size();
  omsk_test::Mesh solved = original, handed = original;
  const int removed = reduce_mesh_skeleton(solved, n * 6 / 10, 4);
  ASSERT_GT(removed, 0);
  EXPECT_LE(skeleton(solved).size(), n * 6 / 10);
  omsk_test::expect_valid_skin(solved, 4);
  // The plain hand-over of the same joints, for comparison.
  ASSERT_EQ(reduce_mesh_skeleton(handed, n * 6 / 10, 4, false), removed);
  const auto sched = make_pose_schedule(clips(original), 8, -1);
  const auto frames = poses_at(skeleton(original), clips(original), sched.held_out);
  const auto reduced_frames = poses_at(skeleton(solved), clips(solved), sched.held_out);
  double e_solved = 0.0, e_handed = 0.0;
  for (size_t f = 0; f < frames.size(); ++f) {
    const auto target = posed_soup(original, frames[f]);
    e_solved += surface_distance(target, posed_soup(solved, reduced_frames[f]), 5000).rms;
    e_handed += surface_distance(target, posed_soup(handed, reduced_frames[f]), 5000).rms;
  }
  EXPECT_LE(e_solved, e_handed) << "re-solving made the skins worse than handing the weights over";
  std::cout << "held-out RMS, " << n << " -> " << skeleton(solved).size() << " joints: re-solved " << e_solved
            << ", handed over " << e_handed << "\n";
}

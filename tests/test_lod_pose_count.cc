// How many example poses a run learns from when --poses is left to the mesh: more on a small character
// whose clips would otherwise share few examples, the usual count everywhere else.
#include <OpenMeshSkinned/Lod/CheckLodOptions.hh>
#include <OpenMeshSkinned/Lod/LodPoseCount.hh>
#include <OpenMeshSkinned/Lod/LodPoses.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <gtest/gtest.h>

using namespace OpenMeshSkinned;

namespace {

// A tube bending in \p moving clips (copies of its "bend", 1 s each).
SkinnedMesh tube(int around, int along, int moving) {
  TubeOptions t;
  t.around = around;
  t.along = along;
  SkinnedMesh mesh = make_skinned_tube(t, 90.0);
  const Clip bend = clips(mesh).at(0);
  clips(mesh).clear();
  for (int i = 0; i < moving; ++i) {
    clips(mesh).push_back(bend);
    clips(mesh).back().name = "bend" + std::to_string(i);
  }
  return mesh;
}

SkinnedMesh small(int moving) { return tube(16, 32, moving); }
SkinnedMesh large(int moving) { return tube(128, 160, moving); }

}  // namespace

TEST(LodPoseCount, TheDefaultLeavesItToTheMesh) {
  EXPECT_EQ(LodOptions().poses, kAutoLodPoses);
  EXPECT_NO_THROW(check_lod_options(LodOptions()));
  ASSERT_LE(small(1).n_vertices(), kSmallMeshVertices);
  ASSERT_GT(large(1).n_vertices(), kSmallMeshVertices);
}

TEST(LodPoseCount, EachClipOfASmallCharacterAddsPosesUpToTheMost) {
  EXPECT_EQ(lod_pose_count(LodOptions(), small(1)), kLodPosesPerClip);
  EXPECT_EQ(lod_pose_count(LodOptions(), small(2)), 2 * kLodPosesPerClip);
  EXPECT_EQ(lod_pose_count(LodOptions(), small(5)), kMaxAutoLodPoses);
}

TEST(LodPoseCount, OneClipChosenIsOneClip) {
  LodOptions o;
  o.pose_clip = "bend1";
  EXPECT_EQ(lod_pose_count(o, small(2)), kLodPosesPerClip);
}

TEST(LodPoseCount, AClipThatDoesNotMoveDoesNotCount) {
  SkinnedMesh mesh = small(1);
  Clip still = clips(mesh)[0];
  still.name = "bind";
  still.duration = 0.0;
  clips(mesh).push_back(still);
  Clip empty;
  empty.name = "nothing";
  empty.duration = 2.0;
  clips(mesh).push_back(empty);
  EXPECT_EQ(lod_pose_count(LodOptions(), mesh), kLodPosesPerClip);
}

TEST(LodPoseCount, ALargeCharacterGetsTheUsualCount) {
  EXPECT_EQ(lod_pose_count(LodOptions(), large(2)), kLodPosesPerClip);
}

TEST(LodPoseCount, AnAnimationWithoutJointsGetsTheUsualCount) {
  SkinnedMesh morphed = small(1);
  Clip c;
  c.name = "blink";
  c.duration = 1.0;
  c.morph_channels.push_back({0, {0.0, 1.0}, {0.0, 1.0}});
  clips(morphed) = {c, c};
  EXPECT_EQ(lod_pose_count(LodOptions(), morphed), kLodPosesPerClip);
}

TEST(LodPoseCount, ACountGivenIsKept) {
  LodOptions o;
  o.poses = 5;
  EXPECT_EQ(lod_pose_count(o, small(2)), 5);
  EXPECT_EQ(lod_pose_count(o, large(2)), 5);
  o.poses = -1;
  EXPECT_THROW(check_lod_options(o), LodOptionsError);
}

TEST(LodPoseCount, TheScheduleHasThatManyExamplesOverTheClips) {
  std::vector<std::string> said;
  LodCallbacks cb;
  cb.message = [&](const std::string& s) { said.push_back(s); };
  const LodPoses p = select_lod_poses(small(2), LodOptions(), "tube", cb);
  ASSERT_EQ(p.schedule.examples.size(), size_t(2 * kLodPosesPerClip));
  EXPECT_EQ(p.examples.size(), p.schedule.examples.size() + 1);  // and the bind pose
  EXPECT_EQ(p.schedule.examples.front().clip, 0);
  EXPECT_EQ(p.schedule.examples.back().clip, 1);
  ASSERT_FALSE(said.empty());
  EXPECT_NE(said.back().find("example poses at"), std::string::npos);
  EXPECT_NE(lod_pose_count_rule().find(std::to_string(kMaxAutoLodPoses)), std::string::npos);
}

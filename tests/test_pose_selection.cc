// Example poses chosen among the frames that are not held out: by the key-frame GA, evenly over the motion,
// farthest first (Deform/PoseSelection.hh).
#include "helpers.hh"

#include <OpenMeshSkinned/Deform/PoseSelection.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

// The knee bends fast and then holds: frame f bends by 90 * min(1, 3 f / 40) degrees.
Mesh bend_then_hold() {
  Mesh skinned = make_bending_cylinder(8, 16);
  const Clip& bend = clips(skinned)[0];
  std::vector<FramePositions> frames;
  std::vector<double> times;
  for (int f = 0; f <= 40; ++f) {
    times.push_back(f / 40.0);
    frames.push_back(skin_positions(skinned, sample_pose(skeleton(skinned), bend, std::min(1.0, 3.0 * f / 40.0))));
  }
  Mesh mesh = skinned;
  const auto h = influences_handle(mesh);
  for (auto v : mesh.vertices()) mesh.property(h, v) = Influences::rigid(0);
  set_frame_animation(mesh, frames, times);
  return mesh;
}

}  // namespace

TEST(PoseSelection, CandidatesAreStoredFramesThatAreNotHeldOut) {
  const Mesh mesh = bend_then_hold();
  const auto c = candidate_frames(mesh, {{0, 0.5}, {0, 0.75}});
  EXPECT_EQ(c.size(), 39u);
  for (const auto& t : c) EXPECT_TRUE(std::abs(t.time - 0.5) > 1e-9 && std::abs(t.time - 0.75) > 1e-9);
  // A skinned clip is sampled: the leg's one-second bend at 30 frames a second.
  const Mesh leg = make_bending_cylinder(8, 16);
  EXPECT_EQ(candidate_frames(leg, {}).size(), 31u);
}

TEST(PoseSelection, CandidatesOfOneClipAreThatClipsFramesOnly) {
  Mesh leg = make_bending_cylinder(8, 16);
  Clip half = clips(leg).at(0);
  half.name = "half";
  half.duration = 0.5;
  clips(leg).push_back(half);
  EXPECT_EQ(candidate_frames(leg, {}).size(), 31u + 16u);
  const auto first = candidate_frames(leg, {{1, 0.5 * 7.0 / 15.0}}, 0);
  EXPECT_EQ(first.size(), 31u) << "a held-out frame of another clip takes none of this one's";
  for (const auto& t : first) EXPECT_EQ(t.clip, 0);
  const auto second = candidate_frames(leg, {{1, 0.5 * 7.0 / 15.0}}, 1);
  EXPECT_EQ(second.size(), 15u);
  for (const auto& t : second) EXPECT_EQ(t.clip, 1);
  // A frame animation's stored frames are its one clip's.
  EXPECT_EQ(candidate_frames(bend_then_hold(), {}, 0).size(), candidate_frames(bend_then_hold(), {}).size());
  EXPECT_TRUE(candidate_frames(bend_then_hold(), {}, 1).empty());
}

TEST(PoseSelection, TheGaPutsTheExamplesWhereTheMotionIs) {
  const Mesh mesh = bend_then_hold();
  const auto candidates = candidate_frames(mesh, {});
  const auto chosen = select_poses_ga(mesh, candidates, 4);
  ASSERT_EQ(chosen.size(), 4u);
  EXPECT_DOUBLE_EQ(chosen.front().time, 0.0);
  EXPECT_DOUBLE_EQ(chosen.back().time, 1.0);
  // The bend ends at frame 13.3: a key there rebuilds the hold exactly; even spacing (0, 1/3, 2/3, 1) cannot.
  bool at_end_of_bend = false;
  for (const auto& t : chosen) at_end_of_bend |= std::abs(t.time * 40.0 - 13.3) < 1.0;
  EXPECT_TRUE(at_end_of_bend);
  EXPECT_THROW(select_poses_ga(mesh, {candidates[0]}, 2), std::invalid_argument);
}

TEST(PoseSelection, SpreadTakesTheDeepestBendFirstThenTheLargestGap) {
  // The leg's knee bends from 0 to 90 degrees over its one-second clip.
  const Mesh leg = make_bending_cylinder(8, 16);
  const auto candidates = candidate_frames(leg, {});
  const auto one = select_poses_spread(leg, candidates, 1);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_NEAR(one[0].time, 1.0, 1e-9) << "the frame farthest from the bind pose is the deepest bend";
  const auto two = select_poses_spread(leg, candidates, 2);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_NEAR(two[1].time, 1.0, 1e-9);
  EXPECT_NEAR(two[0].time, 0.5, 0.1) << "halfway between the bind pose and the deepest bend";
  EXPECT_EQ(select_poses_spread(leg, candidates, 100).size(), candidates.size());
  // Without the bind pose among the examples, the first candidate (the straight leg) is taken first.
  const auto unbound = select_poses_spread(leg, candidates, 2, false);
  ASSERT_EQ(unbound.size(), 2u);
  EXPECT_NEAR(unbound[0].time, 0.0, 1e-9);
  EXPECT_NEAR(unbound[1].time, 1.0, 1e-9);
  EXPECT_THROW(select_poses_spread(leg, {}, 2), std::invalid_argument);
}

TEST(PoseSelection, EvenOverTheMotionPutsTheExamplesWhereTheMeshMoves) {
  // The knee bends over the first third of the frames and then holds: even times would put three of four
  // examples in the hold, where every frame is the same.
  const Mesh mesh = bend_then_hold();
  const auto chosen = select_poses_by_motion(mesh, candidate_frames(mesh, {}), 4);
  ASSERT_EQ(chosen.size(), 4u);
  EXPECT_DOUBLE_EQ(chosen.front().time, 0.0);
  for (size_t i = 0; i < chosen.size(); ++i) {
    EXPECT_LE(chosen[i].time * 40.0, 14.0 + 1e-9) << "example " << i << " is in the hold";
    if (i > 0) {
      EXPECT_GT(chosen[i].time, chosen[i - 1].time);
    }
  }
  // About a third of the bend apart (frames 0, 4.4, 8.9, 13.3 of a linear bend).
  EXPECT_NEAR(chosen[1].time * 40.0, 4.4, 1.0);
  EXPECT_NEAR(chosen[2].time * 40.0, 8.9, 1.0);
  EXPECT_THROW(select_poses_by_motion(mesh, {}, 2), std::invalid_argument);
}

TEST(PoseSelection, AClipWithoutLengthIsOneCandidate) {
  Mesh leg = make_bending_cylinder(8, 16);
  Clip still = clips(leg)[0];
  still.name = "still";
  still.duration = 0.0;
  clips(leg).push_back(still);
  const auto c = candidate_frames(leg, {});
  EXPECT_EQ(c.size(), 32u) << "31 frames of the bend and one of the still clip";
  EXPECT_EQ(std::count_if(c.begin(), c.end(), [](const PoseTime& t) { return t.clip == 1; }), 1);
}

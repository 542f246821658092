// Which frames become example poses and which are held out (Skin/PoseSchedule.hh).
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Skin/PoseSchedule.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

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

TEST(PoseSchedule, FrameAnimationsLearnFromAndAreJudgedOnStoredFramesOnly) {
  std::vector<double> frames;
  for (int f = 0; f < 11; ++f) frames.push_back(0.1 * f);
  Clip clip;
  clip.duration = 1.0;
  PoseSchedule s = make_pose_schedule({clip}, 4, 0);  // examples 0, 1/3, 2/3, 1; held out at 1/6, 1/2, 5/6
  snap_to_frames(s, frames);
  std::vector<double> ex, held;
  for (const auto& t : s.examples) ex.push_back(t.time);
  for (const auto& t : s.held_out) held.push_back(t.time);
  ASSERT_EQ(ex.size(), 4u);
  EXPECT_NEAR(ex[1], 0.3, 1e-12);
  EXPECT_NEAR(ex[2], 0.7, 1e-12);
  ASSERT_EQ(held.size(), 3u);
  for (double h : held) {
    EXPECT_NEAR(std::fmod(h * 10.0 + 1e-9, 1.0), 0.0, 1e-6) << h << " is not a stored frame";
    for (double e : ex) EXPECT_GT(std::abs(h - e), 1e-9) << h << " is also an example";
  }
  // More examples than frames: each frame once, none left to hold out.
  PoseSchedule dense = make_pose_schedule({clip}, 40, 0);
  snap_to_frames(dense, {0.0, 0.5, 1.0});
  EXPECT_EQ(dense.examples.size(), 3u);
  EXPECT_TRUE(dense.held_out.empty());
}

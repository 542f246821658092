// Motion LoD: dropping key frames that interpolation reproduces, and choosing how many by the skinned surface.
#include "helpers.hh"

#include <OpenMeshSkinned/Skin/KeyReduction.hh>

#include <random>

using namespace OpenMeshSkinned;

namespace {

Eigen::Quaterniond about_x(double a) { return Eigen::Quaterniond(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX())); }

double max_local_difference(const Skeleton& skel, const Clip& a, const Clip& b) {
  double worst = 0.0;
  for (double t = 0.0; t <= a.duration + 1e-9; t += a.duration / 97) {
    const auto la = sample_locals(skel, a, t), lb = sample_locals(skel, b, t);
    for (size_t j = 0; j < la.size(); ++j) worst = std::max(worst, (la[j] - lb[j]).cwiseAbs().maxCoeff());
  }
  return worst;
}

}  // namespace

TEST(KeyReduction, DuplicatedAndInterpolatedKeysDisappearWithZeroError) {
  Skeleton skel;
  skel.joints.resize(1);
  Clip clip;
  clip.duration = 4.0;
  Channel ch;
  ch.joint = 0;
  // Rotation held for three keys, then a turn held for two: the middle duplicate goes.
  ch.rotation_times = {0, 1, 2, 3, 4};
  ch.rotations = {about_x(0), about_x(0), about_x(0), about_x(1), about_x(1)};
  // A straight, uniform translation: only its ends stay.
  ch.translation_times = {0, 1, 2, 3, 4};
  for (int i = 0; i <= 4; ++i) ch.translations.push_back(Eigen::Vector3d(i, 0, 0));
  clip.channels = {ch};
  const Clip r = reduce_keys(clip, KeyTolerance{});
  EXPECT_EQ(r.channels[0].rotation_times, (std::vector<double>{0, 2, 3, 4}));
  EXPECT_EQ(r.channels[0].translation_times, (std::vector<double>{0, 4}));
  EXPECT_LT(max_local_difference(skel, clip, r), 1e-12);
  EXPECT_EQ(count_keys({clip}), 10u);
  EXPECT_EQ(count_keys({r}), 6u);
}

TEST(KeyReduction, ThePapersFrameMergeDropsDuplicatedFramesWithZeroError) {
  Skeleton skel;
  skel.joints.resize(2);
  skel.joints[1].parent = 0;
  Clip clip;
  clip.duration = 5.0;
  // Frames 0-2 identical (a hold), 3 a pose, 4-5 that pose held: frames 1 and 4 are duplicates inside holds.
  const double angle[] = {0.0, 0.0, 0.0, 0.7, 0.7, 0.7};
  for (int j : {0, 1}) {
    Channel ch;
    ch.joint = j;
    for (int f = 0; f < 6; ++f) {
      ch.rotation_times.push_back(f);
      ch.rotations.push_back(about_x(j == 0 ? angle[f] : 0.5 * angle[f]));
    }
    clip.channels.push_back(ch);
  }
  const Clip r = merge_key_frames(clip, skel, 1e-9);
  EXPECT_EQ(r.channels[0].rotation_times, (std::vector<double>{0, 2, 3, 5}));
  EXPECT_EQ(r.channels[1].rotation_times, (std::vector<double>{0, 2, 3, 5}));
  EXPECT_EQ(r.duration, clip.duration);
  EXPECT_LT(max_local_difference(skel, clip, r), 1e-12);
  // A threshold above the pose change merges the move too: the motion changes (the surface bound decides).
  EXPECT_LT(merge_key_frames(clip, skel, 10.0).channels[0].rotation_times.size(), 4u);
}

TEST(KeyReduction, ATolerancedReductionStaysWithinItsTolerance) {
  Skeleton skel;
  skel.joints.resize(1);
  Clip clip;
  clip.duration = 10.0;
  Channel ch;
  ch.joint = 0;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(-0.002, 0.002);
  for (int i = 0; i <= 100; ++i) {
    ch.rotation_times.push_back(0.1 * i);
    ch.rotations.push_back(about_x(std::sin(0.1 * i) + noise(rng)));
  }
  clip.channels = {ch};
  const Clip r = reduce_keys(clip, KeyTolerance{0.01, 0.0, 0.0});
  EXPECT_LT(r.channels[0].rotation_times.size(), 40u);
  // Every original key is within 0.01 rad of the reduced channel.
  for (size_t i = 0; i < ch.rotation_times.size(); ++i) {
    const auto l = sample_locals(skel, r, ch.rotation_times[i]);
    const Eigen::Quaterniond q(Eigen::Matrix3d(l[0].block<3, 3>(0, 0)));
    EXPECT_LE(q.angularDistance(ch.rotations[i]), 0.01 + 1e-9) << i;
  }
}

class SurfaceBound : public testing::TestWithParam<KeyReductionMethod> {};

TEST_P(SurfaceBound, HoldsAndDropsKeysOnARealCharacter) {
  const omsk_test::Mesh mesh = omsk_test::load_character("X/Testwuson.X", 2);
  const double bound = 0.002 * bbox_diagonal(mesh);
  const std::vector<Clip> reduced = reduce_clips_to_error(mesh, bound, GetParam());
  EXPECT_LT(count_keys(reduced), count_keys(clips(mesh)) * 3 / 4);
  // Checked independently at every key time of the original clips.
  const Skeleton& skel = skeleton(mesh);
  for (size_t c = 0; c < reduced.size(); ++c)
    for (double t : key_times_and_midpoints(clips(mesh)[c])) {
      const auto a = skin_positions(mesh, sample_pose(skel, clips(mesh)[c], t));
      const auto b = skin_positions(mesh, sample_pose(skel, reduced[c], t));
      for (size_t v = 0; v < a.size(); ++v) ASSERT_LE((a[v] - b[v]).norm(), bound) << "clip " << c << " t " << t;
    }
}

INSTANTIATE_TEST_SUITE_P(KeyReduction, SurfaceBound,
                         testing::Values(KeyReductionMethod::Channels, KeyReductionMethod::Frames));

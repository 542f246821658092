// The final fit of a frame animation: every stored frame's LOD shape fitted to the original's on its own.
#include "helpers.hh"

#include <OpenMeshSkinned/IO/ImportFrames.hh>
#include <OpenMeshSkinned/Lod/Evaluate.hh>
#include <OpenMeshSkinned/Lod/MakeLods.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>
#include <OpenMeshSkinned/Solver/RefitFrames.hh>

using namespace OpenMeshSkinned;

namespace {

SkinnedMesh faerie() {
  SkinnedMesh m;
  import_frame_animation({omsk_test::model("MD2/faerie.md2")}, m, {}, 10.0);
  return m;
}

// The frames method's LOD at \p ratio with the example poses' fit only (the frame fit is what is tested).
SkinnedMesh lod_of(const SkinnedMesh& mesh, double ratio) {
  LodOptions o;
  o.ratios = {ratio};
  o.refit = false;
  o.evaluate = false;
  LodChain chain = make_lods(mesh, o);
  EXPECT_EQ(chain.method, "frames");
  SkinnedMesh lod = chain.levels.at(0).mesh;
  refit_positions(lod, mesh, chain.poses.examples);
  return lod;
}

// Times halfway between stored frames: what the clip plays there is a blend neither fit saw alone.
std::vector<Pose> between_frames(const SkinnedMesh& mesh) {
  const std::vector<double>& t = frame_times(mesh);
  std::vector<double> times;
  for (size_t f = 0; f + 1 < t.size(); f += 9) times.push_back(0.5 * (t[f] + t[f + 1]));
  return sample_poses_at(skeleton(mesh), clips(mesh)[frame_clip(mesh)], times);
}

}  // namespace

// Faerie (198 stored frames) at 25 %: fitting every frame on its own brings the LOD closer to the original in
// every stored frame on average and in times between them, and keeps the animation (rest shape, targets, clip).
TEST(RefitFrames, EveryFrameFittedBringsTheLodCloserBetweenFramesToo) {
  const SkinnedMesh original = faerie();
  ASSERT_EQ(frame_times(original).size(), 198u);
  const SkinnedMesh lod = lod_of(original, 0.25);
  SkinnedMesh fitted = lod;
  RefitSettings s;
  s.threads = 2;
  const RefitFramesReport r = refit_frames(fitted, original, s);
  EXPECT_EQ(r.frames, 198u);
  EXPECT_EQ(fitted.n_faces(), lod.n_faces());
  EXPECT_EQ(morph_targets(fitted).size(), morph_targets(lod).size());
  EXPECT_EQ(frame_times(fitted), frame_times(lod));
  const auto between = between_frames(original);
  EvaluateOptions eo;
  eo.threads = 1;
  const HeldOutError before = evaluate(original, lod, between, eo), after = evaluate(original, fitted, between, eo);
  std::printf("faerie 25%%, between stored frames: RMS %.4f%% -> %.4f%%, Hausdorff %.4f%% -> %.4f%%\n", before.rms,
              after.rms, before.hausdorff, after.hausdorff);
  EXPECT_LT(after.rms, 0.95 * before.rms);
  // Each stored frame's shape is its own fit: the same as the one-pose fit would give.
  for (size_t f : {size_t(0), size_t(57), size_t(197)}) {
    SkinnedMesh one = lod;
    const auto poses =
        sample_poses_at(skeleton(original), clips(original)[frame_clip(original)], {frame_times(original)[f]});
    RefitSettings single;
    single.fit_weights = false;
    refit_positions(one, original, poses, single);
    const auto a = frame_positions(fitted, f), b = skin_positions(one, poses[0]);
    for (size_t v = 0; v < a.size(); v += 7) EXPECT_LT((a[v] - b[v]).norm(), 1e-5 * bbox_diagonal(original)) << f;
  }
}

// The answer does not depend on how many threads share the frames.
TEST(RefitFrames, TheAnswerDoesNotDependOnTheThreadCount) {
  const SkinnedMesh original = faerie();
  const SkinnedMesh lod = lod_of(original, 0.5);
  SkinnedMesh one = lod, two = lod;
  RefitSettings s;
  s.threads = 1;
  refit_frames(one, original, s);
  s.threads = 2;
  refit_frames(two, original, s);
  for (auto vh : one.vertices()) EXPECT_EQ(one.point(vh), two.point(vh));
  OpenMesh::VPropHandleT<MorphDeltas> hd;
  ASSERT_TRUE(morph_deltas_handle(one, hd));
  for (auto vh : one.vertices()) EXPECT_EQ(one.property(hd, vh), two.property(hd, vh));
}

// Clips that mix targets otherwise (here a weight of 2, which would extrapolate the frames' separate fits)
// are not a frame animation: nothing is fitted and nothing moves. A skinned character has no frames either.
TEST(RefitFrames, OnlyAFrameAnimationIsFittedFrameByFrame) {
  const SkinnedMesh original = faerie();
  SkinnedMesh lod = lod_of(original, 0.5);
  Clip& clip = clips(lod)[frame_clip(lod)];
  ASSERT_FALSE(clip.morph_channels.empty());
  for (double& w : clip.morph_channels[5].weights) w *= 2.0;
  const SkinnedMesh before = lod;
  EXPECT_EQ(refit_frames(lod, original).frames, 0u);
  for (auto vh : lod.vertices()) EXPECT_EQ(lod.point(vh), before.point(vh));
  OpenMesh::VPropHandleT<MorphDeltas> hd;
  ASSERT_TRUE(morph_deltas_handle(lod, hd));
  for (auto vh : lod.vertices()) EXPECT_EQ(lod.property(hd, vh), before.property(hd, vh));
  // The same LOD with its clip as it was is fitted.
  clips(lod) = clips(lod_of(original, 0.5));
  EXPECT_EQ(refit_frames(lod, original).frames, 198u);

  const omsk_test::Mesh wuson = omsk_test::load_character("X/Testwuson.X", 4);
  omsk_test::Mesh wlod = wuson;
  omsk_test::decimate(wlod, 0.3);
  EXPECT_EQ(refit_frames(wlod, wuson).frames, 0u);
}

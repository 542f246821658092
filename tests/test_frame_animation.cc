// Meshes animated without a skeleton, kept as morph-target frames: what goes in plays back, in the
// library and in the glTF file (posed by the spec), and key-frame thinning keeps the kept frames exact.
#include "helpers.hh"

#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>

#include <gltf_spec.hh>
#include <validate.hh>

#include <filesystem>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

// The knee bending 0..90 degrees over one second, baked into 11 frames.
Mesh baked_leg() { return bake_frame_animation(make_bending_cylinder(12, 16), 0, 11); }

double max_difference(const FramePositions& a, const std::vector<Eigen::Vector3d>& b) {
  double worst = 0.0;
  for (size_t v = 0; v < a.size(); ++v) worst = std::max(worst, (a[v] - b[v]).norm());
  return worst;
}

}  // namespace

TEST(FrameAnimation, EveryFramePlaysBackAtItsTimeAndInBetweenIsTheLinearBlend) {
  const Mesh skinned = make_bending_cylinder(12, 16);
  const Mesh mesh = baked_leg();
  ASSERT_EQ(frame_times(mesh).size(), 11u);
  ASSERT_EQ(morph_targets(mesh).size(), 10u);
  ASSERT_EQ(frame_clip(mesh), 0);
  const Clip& clip = clips(mesh)[0];
  for (size_t f = 0; f < 11; ++f) {
    const double t = frame_times(mesh)[f];
    const auto expected = skin_positions(skinned, sample_pose(skeleton(skinned), clips(skinned)[0], t));
    EXPECT_LT(max_difference(frame_positions(mesh, f), expected), 1e-5) << f;
    EXPECT_LT(max_difference(frame_positions(mesh, f), skin_positions(mesh, sample_pose(skeleton(mesh), clip, t))),
              1e-6);
  }
  // Halfway between frames 3 and 4: the average of the two.
  const double t = 0.5 * (frame_times(mesh)[3] + frame_times(mesh)[4]);
  const auto mid = skin_positions(mesh, sample_pose(skeleton(mesh), clip, t));
  const auto a = frame_positions(mesh, 3), b = frame_positions(mesh, 4);
  for (size_t v = 0; v < a.size(); ++v) EXPECT_LT((mid[v] - 0.5 * (a[v] + b[v])).norm(), 1e-6);
}

TEST(FrameAnimation, KeepFramesKeepsTheKeptFramesExactAndBlendsTheOthers) {
  Mesh mesh = baked_leg();
  const Mesh full = mesh;
  keep_frames(mesh, {0, 5, 10});
  ASSERT_EQ(frame_times(mesh).size(), 3u);
  EXPECT_EQ(morph_targets(mesh).size(), 2u);
  EXPECT_LT(max_difference(frame_positions(mesh, 1), frame_positions(full, 5)), 1e-6);
  EXPECT_LT(max_difference(frame_positions(mesh, 2), frame_positions(full, 10)), 1e-6);
  // Frame 2 of the original is now 2/5 of the way from frame 0 to frame 5.
  const auto p = skin_positions(mesh, sample_pose(skeleton(mesh), clips(mesh)[0], frame_times(full)[2]));
  const auto a = frame_positions(full, 0), b = frame_positions(full, 5);
  for (size_t v = 0; v < a.size(); ++v) EXPECT_LT((p[v] - (0.6 * a[v] + 0.4 * b[v])).norm(), 1e-6);
  EXPECT_THROW(keep_frames(mesh, {1, 2}), std::invalid_argument);
}

TEST(FrameAnimation, BadFramesAreRefused) {
  Mesh mesh = make_bending_cylinder(8, 8);
  const FramePositions f0 = frame_positions(mesh, 0);
  EXPECT_THROW(set_frame_animation(mesh, {f0}, {0.0}), std::invalid_argument);
  EXPECT_THROW(set_frame_animation(mesh, {f0, FramePositions(3)}, {0.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(set_frame_animation(mesh, {f0, f0}, {1.0, 1.0}), std::invalid_argument);
}

TEST(FrameAnimation, TheGltfFilePlaysTheFramesAsTheSpecPosesIt) {
  const Mesh mesh = baked_leg();
  const std::string path = ::testing::TempDir() + "frames_leg.glb";
  export_gltf(mesh, path);
  omsk_test::expect_valid_gltf(path);
  const auto model = omsk_spec::load(path);
  ASSERT_EQ(model.animations.size(), 1u);
  for (size_t f : {0, 3, 7, 10}) {
    const omsk_spec::Soup s = omsk_spec::pose(model, 0, frame_times(mesh)[f]);
    const FramePositions expected = frame_positions(mesh, f);
    omsk_spec::Soup e;
    e.points.assign(expected.begin(), expected.end());
    for (auto fh : mesh.faces()) {
      auto fv = mesh.cfv_iter(fh);
      e.triangles.push_back({(fv++)->idx(), (fv++)->idx(), fv->idx()});
    }
    EXPECT_LT(omsk_spec::max_nearest_distance(s, e), 1e-4) << "frame " << f;
    EXPECT_LT(omsk_spec::max_nearest_distance(e, s), 1e-4) << "frame " << f;
  }
}

TEST(FrameAnimation, SeveralMaterialsKeepOneSetOfTargetsThroughGltf) {
  // Two materials: the file has two primitives, each with every target, moved by the node's one set of
  // weights; read back, they are one set again (not 2 x 10 targets).
  Mesh mesh = baked_leg();
  materials(mesh).push_back(materials(mesh)[0]);
  materials(mesh)[1].name = "upper";
  const auto hm = face_material_handle(mesh);
  for (auto fh : mesh.faces()) mesh.property(hm, fh) = mesh.point(*mesh.cfv_iter(fh))[1] > 1.0 ? 1 : 0;
  const std::string path = ::testing::TempDir() + "frames_two_materials.glb";
  export_gltf(mesh, path);
  Mesh back;
  import_skinned(path, back);
  EXPECT_EQ(morph_targets(back).size(), 10u);
  ASSERT_EQ(clips(back).size(), 1u);
  EXPECT_EQ(clips(back)[0].morph_channels.size(), 10u);
  const double t = frame_times(mesh)[7];
  const auto a = skin_positions(mesh, sample_pose(skeleton(mesh), clips(mesh)[0], t));
  const auto b = skin_positions(back, sample_pose(skeleton(back), clips(back)[0], t));
  // Vertices are renumbered by the file: compare the posed point sets.
  double worst = 0.0;
  for (auto vb : back.vertices()) {
    double nearest = HUGE_VAL;
    for (auto va : mesh.vertices()) nearest = std::min(nearest, (a[va.idx()] - b[vb.idx()]).norm());
    worst = std::max(worst, nearest);
  }
  EXPECT_LT(worst, 1e-4);
}

// ModFrameQuadricT: per-frame quadrics of the vertices' own trajectories, for meshes without a skeleton.
#include "frame_modules.hh"

#include <OpenMeshSkinned/Decimater/ModDeformationWeightedQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModFrameQuadricT.hh>

using namespace OpenMeshSkinned;
using namespace omsk_test;

TEST(ModFrameQuadric, BeatsTheRestShapeQuadricsInFramesItNeverSaw) {
  const Mesh mesh = frame_leg();
  for (size_t faces : {800, 200}) {
    const Mesh frames = decimate_frames<ModFrameQuadricT>(mesh, faces, [](auto&) {});
    const Mesh rest =
        decimate_frames<ModDeformationWeightedQuadricT>(mesh, faces, [](auto& m) { m.set_importance_scale(0.0); });
    const Mesh weighted = decimate_frames<ModDeformationWeightedQuadricT>(mesh, faces, [](auto&) {});
    EXPECT_EQ(frames.n_faces(), faces);
    EXPECT_EQ(rest.n_faces(), faces);
    const double e_frames = heldout_rms(mesh, frames), e_rest = heldout_rms(mesh, rest);
    const double e_weighted = heldout_rms(mesh, weighted);
    std::printf("%zu faces: frame quadric %.5f, rest quadric %.5f, deformation-weighted %.5f\n", faces, e_frames,
                e_rest, e_weighted);
    // The rest shape's quadric cannot see the knee's rings (straight lines until the knee bends).
    EXPECT_LT(e_frames, 0.2 * e_rest);
    EXPECT_LT(e_frames, 0.2 * e_weighted);
  }
}

TEST(ModFrameQuadric, WithoutPlacementSurvivorsKeepTheirTrajectories) {
  const Mesh mesh = frame_leg();
  const Mesh lod = decimate_frames<ModFrameQuadricT>(mesh, 300, [](auto& m) { m.set_placement(false); });
  // Every LOD vertex is an input vertex, with its own position in every stored frame.
  const size_t F = frame_times(mesh).size();
  std::vector<FramePositions> in, out;
  for (size_t f = 0; f < F; ++f) in.push_back(frame_positions(mesh, f)), out.push_back(frame_positions(lod, f));
  for (auto v : lod.vertices()) {
    size_t match = mesh.n_vertices();
    for (auto u : mesh.vertices())
      if ((in[0][u.idx()] - out[0][v.idx()]).norm() < 1e-12) match = u.idx();
    ASSERT_LT(match, mesh.n_vertices());
    for (size_t f = 0; f < F; ++f) EXPECT_LT((in[f][match] - out[f][v.idx()]).norm(), 1e-6);
  }
}

TEST(ModFrameQuadric, PlacedVerticesMoveWithTheSurfaceInEveryStoredFrame) {
  const Mesh mesh = frame_leg();
  const Mesh lod = decimate_frames<ModFrameQuadricT>(mesh, 600, [](auto&) {});
  size_t moved = 0;
  for (auto v : lod.vertices()) {
    bool is_input = false;
    for (auto u : mesh.vertices()) is_input |= (mesh.point(u) - lod.point(v)).norm() < 1e-12;
    moved += !is_input;
  }
  EXPECT_GT(moved, 20u);
  // In the frames it learnt from and in the others, every LOD vertex stays on the posed input's surface.
  const double diag = bbox_diagonal(mesh);
  for (size_t f = 0; f < frame_times(mesh).size(); ++f) {
    const Pose pose = sample_pose(skeleton(mesh), clips(mesh)[0], frame_times(mesh)[f]);
    const MeasuredSurface surface(posed_soup(mesh, pose), 1000, 1);
    double worst = 0.0;
    for (const auto& p : posed_soup(lod, pose).points) worst = std::max(worst, surface.distance(p));
    EXPECT_LT(worst / diag, 2e-3) << "frame " << f;
  }
}

TEST(ModFrameQuadric, MaxErrorStopsIt) {
  const Mesh mesh = frame_leg();
  const Mesh lod = decimate_frames<ModFrameQuadricT>(mesh, 10, [](auto& m) { m.set_max_err(1e-9); });
  // Only collapses of no error in any frame: along the straight generators of the parts that stay rigid.
  EXPECT_GT(lod.n_faces(), 500u);
  EXPECT_LT(lod.n_faces(), mesh.n_faces());
}

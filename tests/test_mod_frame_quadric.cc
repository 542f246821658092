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

TEST(ModFrameQuadric, AreaExponentAndFloorAreChecked) {
  Mesh mesh = frame_leg();
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModFrameQuadricT<Mesh>::Handle hq;
  dec.add(hq);
  auto& m = dec.module(hq);
  EXPECT_EQ(m.area_exponent(), 0.0);
  for (double bad : {-0.01, 1.01, std::nan("")}) EXPECT_THROW(m.set_area_exponent(bad), std::invalid_argument);
  for (double bad : {-1.0, HUGE_VAL, std::nan("")}) EXPECT_THROW(m.set_area_floor(bad), std::invalid_argument);
  m.set_area_exponent(0.5);
  m.set_area_floor(4.0);
  EXPECT_EQ(m.area_exponent(), 0.5);
  EXPECT_EQ(m.area_floor(), 4.0);
}

// The area a collapse stands for is that of the endpoints' faces in the example frames, averaged: per area
// the energy is divided by it, over the square root by its root.
TEST(ModFrameQuadric, AreaExponentDividesTheEnergyByTheFramesMeanArea) {
  Mesh mesh = frame_leg();
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModFrameQuadricT<Mesh>::Handle hq;
  dec.add(hq);
  ASSERT_TRUE(dec.initialize());
  auto& m = dec.module(hq);
  const std::vector<FramePoints> frames = example_frame_points(mesh);
  size_t checked = 0;
  for (auto heh : mesh.halfedges()) {
    const auto v0 = mesh.from_vertex_handle(heh), v1 = mesh.to_vertex_handle(heh);
    bool inner = true;
    for (auto v : {v0, v1})
      for (auto u : mesh.vv_range(v)) inner &= !mesh.is_boundary(u);
    if (!inner || checked == 20) continue;
    OpenMesh::Decimater::CollapseInfoT<Mesh> ci(mesh, heh);
    m.set_area_exponent(0.0);
    const double energy = m.collapse_priority(ci);
    if (!(energy > 0.0)) continue;
    m.set_area_exponent(1.0);
    const double per_area = m.collapse_priority(ci);
    m.set_area_exponent(0.5);
    const double balanced = m.collapse_priority(ci);
    double area = 0.0;
    for (const FramePoints& p : frames)
      for (auto v : {v0, v1})
        for (auto fh : mesh.vf_range(v)) {
          auto fv = mesh.fv_iter(fh);
          const Eigen::Vector3d a = p[(*fv++).idx()], b = p[(*fv++).idx()], c = p[(*fv).idx()];
          area += 0.5 * (b - a).cross(c - a).norm();
        }
    area /= double(frames.size());
    EXPECT_NEAR(per_area, energy / area, 1e-5 * per_area);
    EXPECT_NEAR(balanced, energy / std::sqrt(area), 1e-5 * balanced);
    ++checked;
  }
  EXPECT_EQ(checked, 20u);
}

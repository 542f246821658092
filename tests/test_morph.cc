// Morph targets: offsets that survive import, decimation and export; weights sampled from clips.
#include "fixtures.hh"
#include "gltf_spec.hh"

#include <OpenMeshSkinned/Collapse/MorphTransferT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedQuadricT.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Skin/LinearBlendSkinning.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>

#include <gtest/gtest.h>

using namespace OpenMeshSkinned;

TEST(Morph, ClipWeightsAreInterpolatedLinearly) {
  Clip c;
  c.duration = 2.0;
  c.morph_channels.push_back({1, {0.0, 1.0, 2.0}, {0.0, 1.0, 0.5}});
  EXPECT_TRUE(sample_morph_weights(Clip{}, 0.3).empty());
  const auto w = sample_morph_weights(c, 1.5);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_DOUBLE_EQ(w[0], 0.0);
  EXPECT_DOUBLE_EQ(w[1], 0.75);
  EXPECT_DOUBLE_EQ(sample_morph_weights(c, 9.0)[1], 0.5);  // clamped into the clip
}

TEST(Morph, OffsetsAreAddedBeforeSkinning) {
  SkinnedMesh mesh = make_skinned_tube({}, 90.0);
  const auto hd = add_morph_targets(mesh);
  morph_targets(mesh).push_back({"up"});
  for (auto vh : mesh.vertices()) mesh.property(hd, vh) = {Eigen::Vector3f(0, 0, 1)};
  Pose p = Pose::identity(skeleton(mesh).size());
  const auto before = skin_positions(mesh, p);
  p.morph_weights = {0.5};
  const auto after = skin_positions(mesh, p);
  for (auto vh : mesh.vertices()) EXPECT_NEAR((after[vh.idx()] - before[vh.idx()]).z(), 0.5, 1e-12);
}

// A vertex that lands midway along a collapsed edge gets the average of its endpoints' offsets, and a
// field that is linear over the surface is reproduced exactly wherever the vertex lands on it.
TEST(Morph, TransferInterpolatesOnTheOldSurface) {
  SkinnedMesh mesh;
  request_skinned_attributes(mesh);
  add_skin(mesh);
  const auto hd = add_morph_targets(mesh);
  morph_targets(mesh).push_back({"x"});
  SkinnedMesh::VertexHandle v[4];
  const double pts[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  for (int i = 0; i < 4; ++i) {
    v[i] = mesh.add_vertex(SkinnedMesh::Point(pts[i][0], pts[i][1], pts[i][2]));
    mesh.property(hd, v[i]) = {Eigen::Vector3f(float(2 * pts[i][0] + pts[i][1]), 0, 0)};  // linear field
  }
  mesh.add_face(v[0], v[1], v[3]);
  mesh.add_face(v[0], v[3], v[2]);
  MorphTransferT<SkinnedMesh> transfer(mesh);
  ASSERT_TRUE(transfer.active());
  transfer.record(v[0], v[3]);
  mesh.set_point(v[3], SkinnedMesh::Point(0.25, 0.5, 0.0));
  transfer.apply(v[3]);
  EXPECT_NEAR(mesh.property(hd, v[3])[0].x(), 2 * 0.25 + 0.5, 1e-6);
}

TEST(Morph, DecimationKeepsOneOffsetPerTargetOnEveryVertex) {
  const std::string dir = testing::TempDir();
  tinygltf::Model m = omsk_fixtures::testwuson(dir);
  omsk_fixtures::add_morph_target(m);
  omsk_spec::save_glb(m, dir + "/morph_wuson.glb");
  SkinnedMesh mesh;
  import_skinned(dir + "/morph_wuson.glb", mesh);
  OpenMesh::VPropHandleT<MorphDeltas> hd;
  ASSERT_TRUE(morph_deltas_handle(mesh, hd));
  float before = 0.0f;
  for (auto vh : mesh.vertices()) before = std::max(before, mesh.property(hd, vh)[0].norm());
  example_poses(mesh) = sample_poses_evenly(skeleton(mesh), clips(mesh)[0], 4);
  OpenMesh::Decimater::DecimaterT<SkinnedMesh> dec(mesh);
  ModSkinnedQuadricT<SkinnedMesh>::Handle hq;
  dec.add(hq);
  ASSERT_TRUE(dec.initialize());
  dec.decimate_to_faces(0, mesh.n_faces() / 5);
  mesh.garbage_collection();
  float after = 0.0f;
  for (auto vh : mesh.vertices()) {
    ASSERT_EQ(mesh.property(hd, vh).size(), 1u);
    ASSERT_TRUE(mesh.property(hd, vh)[0].allFinite());
    after = std::max(after, mesh.property(hd, vh)[0].norm());
  }
  EXPECT_GT(after, 0.5f * before);     // the bulge is still there
  EXPECT_LE(after, 1.0001f * before);  // and interpolation never exaggerates it
}

// Linear blend skinning (Skin/LinearBlendSkinning.hh).
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/Procedural.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

TEST(LinearBlendSkinning, BlendsJointMatrices) {
  Pose pose = Pose::identity(2);
  pose.joint[1].col(3) = Eigen::Vector3d(2, 0, 0);  // joint 1 translates by +2x
  Influences inf;
  inf.push(0, 0.25);
  inf.push(1, 0.75);
  const Eigen::Vector3d p = skin_point(Eigen::Vector3d(1, 1, 1), inf, pose);
  EXPECT_TRUE(p.isApprox(Eigen::Vector3d(2.5, 1, 1)));
}

TEST(LinearBlendSkinning, BindPoseLeavesTheMeshInPlace) {
  Mesh mesh = make_bending_cylinder(8, 8);
  const auto posed = skin_positions(mesh, Pose::identity(skeleton(mesh).size()));
  for (auto vh : mesh.vertices()) EXPECT_TRUE(posed[vh.idx()].isApprox(to_eigen(mesh.point(vh))));
  const auto normals = skin_face_normals(mesh, posed);
  for (auto fh : mesh.faces()) {
    // The generated tube faces outwards.
    const auto c = mesh.calc_face_centroid(fh);
    EXPECT_GT(normals[fh.idx()].dot(Eigen::Vector3d(c[0], 0, c[2])), 0.0);
  }
}

TEST(LinearBlendSkinning, APosedVertexIsItsSkinnedPointAndADeletedOneStaysAtRest) {
  Mesh mesh = make_bending_cylinder(8, 8);
  Pose pose = Pose::identity(skeleton(mesh).size());
  pose.joint.back().col(3) = Eigen::Vector3d(0.5, -1, 2);
  const auto h = influences_handle(mesh);
  const VertexPoser<Mesh> posed(mesh, pose);
  size_t moved = 0;
  for (auto vh : mesh.vertices()) {
    const Eigen::Vector3d p = posed(vh);
    EXPECT_TRUE(p.isApprox(skin_point(to_eigen(mesh.point(vh)), mesh.property(h, vh), pose)));
    moved += !p.isApprox(to_eigen(mesh.point(vh)));
  }
  EXPECT_GT(moved, 0u);  // the pose moves part of the tube: the check above is not of the rest pose
  const auto vh = *mesh.vertices().begin();
  mesh.delete_vertex(vh, false);
  EXPECT_TRUE(posed(vh).isApprox(to_eigen(mesh.point(vh))));
  EXPECT_TRUE(skin_positions(mesh, pose)[vh.idx()].isApprox(to_eigen(mesh.point(vh))));
}

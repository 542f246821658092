// Deformation gradients (Lee eq. 1-3), deformation distances (eq. 4) and face importance (report eq. 8).
#include "helpers.hh"

#include <OpenMeshSkinned/Deform/DeformationAnalysis.hh>
#include <OpenMeshSkinned/Deform/ExampleFrames.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>
#include <OpenMeshSkinned/Skin/PoseSchedule.hh>

#include <Eigen/Geometry>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

using Tri = std::array<Eigen::Vector3d, 3>;

Tri apply(const Eigen::Matrix3d& A, const Eigen::Vector3d& b, const Tri& t) {
  return {A * t[0] + b, A * t[1] + b, A * t[2] + b};
}

// A three-bone tube whose vertices each follow one bone (no blending), bent at both joints, as frames.
Mesh articulated_tube(double bend_degrees, size_t n_frames) {
  TubeOptions o;
  o.around = 12;
  o.along = 30;
  o.bones = 3;
  o.blend = 1e-4;  // each vertex follows one bone; the joint rings themselves halfway
  return bake_frame_animation(make_skinned_tube(o, bend_degrees), 0, n_frames);
}

std::vector<FramePoints> frames_of(const Mesh& m) {
  std::vector<FramePoints> out;
  for (size_t f = 0; f < frame_times(m).size(); ++f) out.push_back(frame_positions(m, f));
  return out;
}

}  // namespace

TEST(DeformationAnalysis, TheGradientOfAnAffineMapIsItsLinearPart) {
  const Tri ref = {Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(1.3, -0.2, 0.5), Eigen::Vector3d(0.4, 0.9, -0.7)};
  Eigen::Matrix3d A;
  A << 1.2, 0.3, -0.1, 0.0, 0.8, 0.4, 0.2, -0.5, 1.1;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::Matrix3d M;
  // A rotation (and a uniform scale) moves the fourth vertex exactly as the map does: the gradient is the map.
  ASSERT_TRUE(deformation_gradient(ref, apply(2.0 * R, Eigen::Vector3d(3, 4, 5), ref), M));
  EXPECT_LT((M - 2.0 * R).norm(), 1e-9);
  // A general map agrees on the triangle's plane (the two edge directions).
  ASSERT_TRUE(deformation_gradient(ref, apply(A, Eigen::Vector3d::Zero(), ref), M));
  EXPECT_LT((M * (ref[1] - ref[0]) - A * (ref[1] - ref[0])).norm(), 1e-9);
  EXPECT_LT((M * (ref[2] - ref[0]) - A * (ref[2] - ref[0])).norm(), 1e-9);
  EXPECT_FALSE(deformation_gradient({ref[0], ref[0], ref[1]}, ref, M));
}

TEST(DeformationAnalysis, DistanceIsZeroInsideARigidPartAndLargeAcrossABend) {
  const Mesh mesh = articulated_tube(90.0, 5);
  const FramePoints ref = frame_positions(mesh, 0);
  const FaceGradients<Mesh> g(mesh, ref, frames_of(mesh));
  const std::vector<double> D = deformation_distances(mesh, ref, g, true);
  // Bones along +y in thirds of the length: an edge with both faces well inside one third is rigid.
  double inside = 0.0, across = 0.0;
  for (auto eh : mesh.edges()) {
    if (mesh.is_boundary(eh)) continue;
    const double y = 0.5 * (mesh.point(mesh.from_vertex_handle(mesh.halfedge_handle(eh, 0)))[1] +
                            mesh.point(mesh.to_vertex_handle(mesh.halfedge_handle(eh, 0)))[1]);
    const double third = std::fmod(y / (2.0 / 3.0), 1.0);
    if (third > 0.2 && third < 0.8)
      inside = std::max(inside, D[eh.idx()]);
    else
      across = std::max(across, D[eh.idx()]);
  }
  EXPECT_LT(inside, 1e-8);  // morph offsets are stored as floats
  EXPECT_GT(across, 1.0);
}

TEST(DeformationAnalysis, ImportanceIsHighExactlyAtTheJoints) {
  Mesh mesh = articulated_tube(60.0, 4);
  const std::vector<double> w = face_importance(mesh, frame_positions(mesh, 0), frames_of(mesh));
  const double joints[] = {2.0 / 3.0, 4.0 / 3.0};
  for (auto fh : mesh.faces()) {
    double near = HUGE_VAL;
    for (auto vh : mesh.fv_range(fh))
      for (double j : joints) near = std::min(near, std::abs(mesh.point(vh)[1] - j));
    if (near > 0.15) {
      EXPECT_LT(w[fh.idx()], 1e-8) << "face " << near << " from a joint";
    } else if (near < 1e-6) {
      EXPECT_GT(w[fh.idx()], 0.05) << "face on a joint ring";
    }
  }
}

TEST(DeformationAnalysis, ExampleFramesArePosedWithMorphOffsets) {
  Mesh mesh = articulated_tube(90.0, 5);
  example_poses(mesh) = poses_at(skeleton(mesh), clips(mesh), {{0, frame_times(mesh)[2]}, {0, frame_times(mesh)[4]}});
  const auto frames = example_frame_points(mesh);
  ASSERT_EQ(frames.size(), 2u);
  const FramePoints f4 = frame_positions(mesh, 4);
  for (size_t v = 0; v < f4.size(); ++v) EXPECT_LT((frames[1][v] - f4[v]).norm(), 1e-6);
}

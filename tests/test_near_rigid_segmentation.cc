// Lee et al.'s near-rigid segmentation: an articulated mesh comes back as its rigid parts.
#include "helpers.hh"

#include <OpenMeshSkinned/Deform/NearRigidSegmentation.hh>
#include <OpenMeshSkinned/IO/ImportFrames.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>

#include <map>
#include <set>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

// \p bones rigid parts along +y (each vertex follows one bone; the joint rings themselves blend), every
// joint bending by up to \p degrees, as frames.
Mesh articulated_tube(int bones, double degrees, size_t n_frames) {
  TubeOptions o;
  o.around = 16;
  o.along = 12 * bones;
  o.bones = bones;
  o.blend = 1e-4;
  return bake_frame_animation(make_skinned_tube(o, degrees), 0, n_frames);
}

std::vector<FramePoints> frames_of(const Mesh& m) {
  std::vector<FramePoints> out;
  for (size_t f = 0; f < frame_times(m).size(); ++f) out.push_back(frame_positions(m, f));
  return out;
}

// The bone a face lies on, or -1 when it touches a joint ring (those may go either way).
int bone_of(const Mesh& mesh, Mesh::FaceHandle fh, int bones) {
  const double len = 2.0 / bones;
  std::set<int> b;
  for (auto vh : mesh.fv_range(fh)) {
    const double y = mesh.point(vh)[1];
    const double k = std::round(y / len);
    if (k > 0 && k < bones && std::abs(y - k * len) < 1e-9) return -1;
    b.insert(std::min(bones - 1, int(y / len)));
  }
  return b.size() == 1 ? *b.begin() : -1;
}

void expect_parts_are_bones(const Mesh& mesh, const Segmentation& s, int bones) {
  ASSERT_EQ(s.parts, bones);
  std::map<int, std::set<int>> parts_of_bone, bones_of_part;
  for (auto fh : mesh.faces()) {
    const int b = bone_of(mesh, fh, bones);
    if (b < 0) continue;
    parts_of_bone[b].insert(s.part[fh.idx()]);
    bones_of_part[s.part[fh.idx()]].insert(b);
  }
  for (auto& [b, p] : parts_of_bone) EXPECT_EQ(p.size(), 1u) << "bone " << b << " is split";
  for (auto& [p, b] : bones_of_part) EXPECT_EQ(b.size(), 1u) << "part " << p << " spans bones";
}

}  // namespace

TEST(NearRigidSegmentation, AnArticulatedTubeComesBackAsItsBones) {
  const Mesh mesh = articulated_tube(3, 90.0, 6);
  const auto frames = frames_of(mesh);
  const Segmentation s = segment_near_rigid(mesh, frames[0], frames);
  expect_parts_are_bones(mesh, s, 3);
}

TEST(NearRigidSegmentation, FiveBonesToo) {
  const Mesh mesh = articulated_tube(5, 70.0, 5);
  const auto frames = frames_of(mesh);
  expect_parts_are_bones(mesh, segment_near_rigid(mesh, frames[0], frames), 5);
}

TEST(NearRigidSegmentation, AMeshMovingRigidlyIsOnePart) {
  Mesh mesh = articulated_tube(3, 0.0, 4);
  auto frames = frames_of(mesh);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (size_t f = 1; f < frames.size(); ++f)
    for (auto& p : frames[f]) p = R * p + Eigen::Vector3d(f, 0, 0);
  const Segmentation s = segment_near_rigid(mesh, frames[0], frames);
  EXPECT_EQ(s.parts, 1);
}

TEST(NearRigidSegmentation, TheMinimumCutShortensTheBoundariesAndKeepsThePartsWhole) {
  Mesh mesh;
  import_frame_animation({omsk_test::model("MD2/sydney.md2")}, mesh, {}, 10.0);
  std::vector<FramePoints> frames;
  for (size_t f = 0; f < frame_times(mesh).size(); f += 6) frames.push_back(frame_positions(mesh, f));
  auto boundary = [&](const Segmentation& s) {
    double len = 0.0;
    for (auto eh : mesh.edges())
      if (!mesh.is_boundary(eh) && s.part[mesh.face_handle(mesh.halfedge_handle(eh, 0)).idx()] !=
                                       s.part[mesh.face_handle(mesh.halfedge_handle(eh, 1)).idx()])
        len += mesh.calc_edge_length(eh);
    return len;
  };
  SegmentationSettings rough;
  rough.smoothing_hops = 0;
  const Segmentation a = segment_near_rigid(mesh, frames[0], frames, rough);
  const Segmentation b = segment_near_rigid(mesh, frames[0], frames);
  EXPECT_EQ(a.parts, b.parts);
  EXPECT_GT(b.parts, 8);
  EXPECT_LT(boundary(b), 0.8 * boundary(a));
  // Every part is one connected piece of faces.
  for (int p = 0; p < b.parts; ++p) {
    std::vector<char> seen(mesh.n_faces(), 0);
    std::vector<Mesh::FaceHandle> stack;
    for (auto fh : mesh.faces())
      if (b.part[fh.idx()] == p) {
        stack.push_back(fh);
        seen[fh.idx()] = 1;
        break;
      }
    size_t reached = 0;
    while (!stack.empty()) {
      const auto fh = stack.back();
      stack.pop_back();
      ++reached;
      for (auto g : mesh.ff_range(fh))
        if (b.part[g.idx()] == p && !seen[g.idx()]) seen[g.idx()] = 1, stack.push_back(g);
    }
    EXPECT_EQ(reached, size_t(std::count(b.part.begin(), b.part.end(), p))) << "part " << p;
  }
}

#pragma once
// Shared by the tests of the deformation modules: an animated mesh as frames, decimated with a chosen
// priority module (and the frame fold-over check), judged in frames it never saw.
#include "helpers.hh"

#include <OpenMeshSkinned/Decimater/ModFrameFoldOverT.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>
#include <OpenMeshSkinned/Skin/PoseSchedule.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>

namespace omsk_test {

/// The knee bending 0..90 degrees over one second, baked into 21 frames; the even frames are its example
/// poses.
inline Mesh frame_leg() {
  using namespace OpenMeshSkinned;
  Mesh mesh = bake_frame_animation(make_bending_cylinder(32, 64), 0, 21);
  std::vector<PoseTime> even;
  for (size_t f = 0; f < 21; f += 4) even.push_back({0, frame_times(mesh)[f]});
  example_poses(mesh) = poses_at(skeleton(mesh), clips(mesh), even);
  return mesh;
}

/// Mean RMS surface distance (fraction of the diagonal) over the odd frames.
inline double heldout_rms(const Mesh& original, const Mesh& lod) {
  using namespace OpenMeshSkinned;
  double sum = 0.0;
  int n = 0;
  for (size_t f = 1; f < frame_times(original).size(); f += 2, ++n)
    sum += posed_rms(original, lod, sample_pose(skeleton(original), clips(original)[0], frame_times(original)[f]));
  return sum / n;
}

/// Decimates a copy of \p mesh to \p faces with priority module \p Priority and the frame fold-over
/// check; \p setup configures the priority module.
template <template <typename> class Priority, typename Setup>
Mesh decimate_frames(const Mesh& mesh, size_t faces, Setup setup) {
  Mesh out = mesh;
  OpenMesh::Decimater::DecimaterT<Mesh> dec(out);
  typename Priority<Mesh>::Handle hp;
  typename OpenMeshSkinned::ModFrameFoldOverT<Mesh>::Handle hf;
  dec.add(hp);
  dec.add(hf);
  setup(dec.module(hp));
  EXPECT_TRUE(dec.initialize());
  dec.decimate_to_faces(0, faces);
  out.garbage_collection();
  return out;
}

}  // namespace omsk_test

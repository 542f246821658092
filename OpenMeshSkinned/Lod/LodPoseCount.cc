#include "LodPoseCount.hh"

#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <algorithm>

namespace OpenMeshSkinned {

static_assert(kAutoLodPoses == 0, "LodOptions::poses defaults to 0, which leaves the count to lod_pose_count()");

int lod_pose_count(const LodOptions& options, const SkinnedMesh& mesh) {
  if (options.poses != kAutoLodPoses) return options.poses;
  const auto& all = clips(mesh);
  const auto moving =
      std::count_if(all.begin(), all.end(), [](const Clip& c) { return c.duration > 0.0 && !c.channels.empty(); });
  if (moving == 0 || mesh.n_vertices() > kSmallMeshVertices) return kLodPosesPerClip;
  const int clips_sampled = options.pose_clip.empty() ? int(moving) : 1;
  return std::min(kLodPosesPerClip * clips_sampled, kMaxAutoLodPoses);
}

std::string lod_pose_count_rule() {
  return std::to_string(kLodPosesPerClip) + " per clip that moves joints, at most " + std::to_string(kMaxAutoLodPoses) +
         ", on a mesh of up to " + std::to_string(kSmallMeshVertices) + " vertices; else " +
         std::to_string(kLodPosesPerClip);
}

}  // namespace OpenMeshSkinned

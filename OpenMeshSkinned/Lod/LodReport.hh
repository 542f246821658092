#pragma once
// One level of a LOD chain as made and measured, and the chain: the levels with the poses they were made in
// and judged in.

#include <OpenMeshSkinned/Lod/SwitchHints.hh>
#include <OpenMeshSkinned/Skin/PoseSchedule.hh>
#include <OpenMeshSkinned/Skin/Skeleton.hh>
#include <OpenMeshSkinned/Skin/SkinnedMesh.hh>

#include <cstddef>
#include <string>
#include <vector>

namespace OpenMeshSkinned {

struct LodReport {
  double ratio = 0.0;
  size_t target = 0;  ///< triangles asked for
  size_t faces = 0, vertices = 0;
  double seconds = 0.0;  ///< from the start of the decimation to this level's snapshot
  int max_influences = 0;
  size_t keys = 0;                    ///< key frames over its clips' channels (fewer with anim_error)
  int joints = 0;                     ///< its skeleton's joints (fewer with max_joints)
  double fold_limit = 90.0;           ///< the largest face turn allowed to reach the target (degrees)
  bool at_floor = false;              ///< stopped above the target where no collapse keeps the mesh manifold
  size_t pieces = 0;                  ///< then: its connected pieces
  size_t fold_fallbacks = 0;          ///< collapses made off their solved placement, which folded, to reach it
  size_t non_finite_weights = 0;      ///< weight problems the solver refused as non-finite, this level and before
  double deviation_bound = -1.0;      ///< max_error: bound on the input's vertices' distance, % (< 0: none)
  bool evaluated = false;             ///< false when not evaluated
  double rms = 0.0, hausdorff = 0.0;  ///< held-out, % of the input's rest-pose bounding-box diagonal
  LodSwitchHint switch_hint;          ///< when an engine may switch to it (from the held-out Hausdorff error)
  std::vector<float> vertex_error;    ///< per vertex, max over held-out frames, % (per_vertex_error only)
};

struct LodLevel {
  LodReport report;
  SkinnedMesh mesh;
};

/// The example poses the decimater sees and the held-out frames the result is judged in.
struct LodPoses {
  PoseSchedule schedule;
  std::vector<Pose> examples, heldout;
};

struct LodChain {
  std::string method;  ///< the method that made it (LodOptions::method, or the mesh's default)
  LodPoses poses;
  std::vector<LodLevel> levels;  ///< largest first
  double decimate_seconds = 0.0, evaluate_seconds = 0.0;
};

}  // namespace OpenMeshSkinned

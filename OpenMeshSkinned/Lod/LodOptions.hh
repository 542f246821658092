#pragma once
// What make_lods() is asked for, with the command line's defaults, and the checks that refuse a bad request
// with the command line's one-line messages (the CLI, the Python package and a C++ caller all see the same).

#include <OpenMeshSkinned/Skin/SkinnedMesh.hh>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace OpenMeshSkinned {

/// A request make_lods() cannot carry out as given (a value out of range, a combination that cannot hold).
struct LodOptionsError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

struct LodOptions {
  /// The priority module: one of lod_methods() ("skinned" and the papers' baselines). Empty: "skinned", or
  /// "frames" for a mesh animated without a skeleton (only that method sees its morph-target frames).
  std::string method;
  /// One LOD per ratio of the input's triangles, in (0, 1] (made largest first). Ignored when \a faces is set.
  std::vector<double> ratios = {0.5};
  /// One LOD per triangle count (made largest first; empty: \a ratios).
  std::vector<size_t> faces;
  int max_influences = 4;  ///< bones per vertex at every level, 1..Influences::kCapacity
  /// Example poses: at the times pose_select chooses, plus the bind pose; 0: as many as lod_pose_count()
  /// chooses for the mesh.
  int poses = 0;
  std::string pose_clip;  ///< the clip (name or index) the example poses come from; empty: all, end to end
  bool bind_pose = true;  ///< the bind pose among the example poses
  /// How the example poses are chosen: "even" (evenly spaced times), or among the frames not held out: "motion"
  /// (evenly spaced over the motion: select_poses_by_motion), "spread" (farthest first: select_poses_spread) or
  /// "ga" (the key-frame GA).
  std::string pose_select = "even";
  int threads = 0;                ///< 0: the hardware's
  bool evaluate = true;           ///< measure every LOD in held-out frames
  bool per_vertex_error = false;  ///< and keep each LOD vertex's worst held-out error (LodReport::vertex_error)
  /// final fit of the LODs' rest positions in the example poses (on small inputs also their skin weights, and a
  /// frame animation's every stored frame: Refit.hh, RefitFrames.hh)
  bool refit = true;
  bool strict_fold = false;  ///< never relax the 90-degree fold-over limit to reach a target
  /// The skinned and frames priorities are energy / area^area_exponent (ModSkinnedQuadricT::set_area_exponent,
  /// ModFrameQuadricT::set_area_exponent): 0 is the energy, 1 a mean squared distance; -1 (kAutoAreaExponent):
  /// by the input, lod_area_exponent() and lod_frames_area_exponent().
  double area_exponent = -1.0;
  /// Below this many of the coarsest level's mean triangles a collapse is priced per area
  /// (ModSkinnedQuadricT::set_area_floor, ModFrameQuadricT::set_area_floor; 0: no floor).
  double area_floor = 2.0;
  double joint_guard = 0.0;  ///< Savoye-Meyer joint-region guard TAU (0: off)
  /// weight of the rest-pose normal quadrics against the geometry (ModSkinnedQuadricT::set_normal_weight; 0: off)
  double normal_weight = 0.03;
  double max_error = 0.0;       ///< bound on the input's vertices' distance to the LOD, % of the diagonal (0: none)
  std::vector<int> max_joints;  ///< skeleton LoD: joints kept, one per LOD, the last repeating (empty: all)
  double joint_energy = 0.0;    ///< skeleton LoD: minor joints under this joint energy go (0: none by energy)
  double anim_error = 0.0;      ///< motion LoD: keys dropped while no vertex moves further, % of the diagonal
  bool anim_frames = false;     ///< motion LoD by merging whole key frames (the paper's) instead of channels
  size_t keyframes = 0;         ///< frame animations: keep this many stored frames, chosen by the GA (0: all)
  size_t max_memory_mb = 8192;  ///< refuse a number of poses whose poses would need more (0: no limit)
};

/// Past this many example poses the schedule stops being a sample of the clips and becomes the clips.
constexpr int kMaxLodPoses = 1000;
/// What one example or held-out pose costs per vertex: posed position and pose quadric in the solver, posed
/// copies in the evaluation (measured: about 120 bytes per vertex and pose; rounded up here).
constexpr size_t kBytesPerVertexPose = 128;

/// The method make_lods() runs on \p mesh: options.method, or the default for this mesh.
std::string lod_method_for(const LodOptions& options, const SkinnedMesh& mesh);
/// Whether \p mesh is animated by morph targets alone (stored frames, or clips that move no joint).
bool morph_animated_only(const SkinnedMesh& mesh);
/// The clip options.pose_clip names in \p mesh (a name or an index); -1 when none is named.
int lod_pose_clip(const LodOptions& options, const SkinnedMesh& mesh, const std::string& name = "the mesh");

/// The triangle count of each LOD \p options asks of \p mesh, and the ratio each stands for.
void lod_targets(const LodOptions& options, const SkinnedMesh& mesh, std::vector<double>& ratios,
                 std::vector<size_t>& targets);

}  // namespace OpenMeshSkinned

#pragma once
// What the command line asked for, and the one error type that means "the command line is wrong" (exit 2).

#include <OpenMeshSkinned/Lod/LodOptions.hh>
#include <OpenMeshSkinned/Skin/SkinnedMesh.hh>

#include <stdexcept>
#include <string>
#include <vector>

namespace skinned_decimate {

using Mesh = OpenMeshSkinned::SkinnedMesh;

struct Options {
  std::string input, output, report, pose_clip, method = "skinned";
  double ratio = 0.0;
  size_t faces = 0;
  std::vector<double> lods;  // sorted, largest first
  int max_influences = 4;
  int poses = OpenMeshSkinned::LodOptions().poses;  // 0: lod_pose_count() chooses
  bool quiet = false;
  bool verbose = false;  // --verbose: the isolated reader's own output too
  bool poses_given = false;
  bool ratio_given = false;
  bool compare = false;
  bool bind_pose = true;
  bool faces_given = false;
  bool isolate = true;
  size_t max_memory_mb = 8192;
  double time_limit = 300.0;
  int threads = 0;  // 0: the hardware's
  bool evaluate = true;
  std::string html, preview;  // --html page, --preview PNG
  bool html_beside = false;   // --html-assets beside: the GLBs in a script next to the page
  double joint_guard = 0.0;   // --joint-guard TAU (0: off)
  double normal_weight = OpenMeshSkinned::LodOptions{}.normal_weight;  // --normal-weight W (0: geometry only)
  double anim_error = 0.0;      // --anim-error E, % of the diagonal (0: clips kept whole)
  bool anim_frames = false;     // --anim-method frames: the paper's whole-frame merge instead of channels
  std::vector<int> max_joints;  // --max-joints N or N1,N2,... one per LOD (empty: skeleton kept whole)
  double joint_energy = 0.0;    // --joint-energy E: minor joints under it go (0: none by energy)
  bool strict_fold = false;     // --strict-fold: never relax the 90-degree fold-over limit
  double max_error = 0.0;       // --max-error E, % of the diagonal: bound on the original's vertices (0: none)
  bool method_given = false;
  bool sequences = true;             // --no-sequence: a numbered file is one mesh, not a frame of a sequence
  double fps = 0.0;                  // --fps: frame rate of a frame animation (0: 10 for MD2/MD3/MDL, 24 otherwise)
  size_t keyframes = 0;              // --keyframes K: keep K frames of a frame animation, chosen by the GA (0: all)
  std::string pose_select = "even";  // --pose-select even|motion|spread|ga
  std::string segment;               // --segment OUT.glb: near-rigid parts, coloured, and OUT.json
  bool refit = true;                 // final fit of the LOD's rest positions in the example poses (--no-refit: off)
  double area_exponent = -1.0;       // --error: skinned and frames price energy / area^this (per-area 1; auto -1)
  double area_floor = 2.0;           // --area-floor N: per area below N of the coarsest level's mean triangles
};

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace skinned_decimate

#include "CheckLodOptions.hh"

#include "LodAreaExponent.hh"
#include "LodMethods.hh"
#include "LodPoseCount.hh"
#include "LodPoses.hh"

#include <OpenMeshSkinned/Skin/FrameAnimation.hh>
#include <OpenMeshSkinned/Skin/Influences.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <algorithm>
#include <cmath>

namespace OpenMeshSkinned {

// The messages name the command line's options: the CLI shows them as they are, and the Python package
// raises them (its keywords are the options' names).
void check_lod_options(const LodOptions& o) {
  if (o.faces.empty() && o.ratios.empty()) throw LodOptionsError("no LOD asked for: give --ratio, --faces or --lods");
  if (o.faces.empty())
    for (double r : o.ratios)
      if (!(r > 0.0 && r <= 1.0))
        throw LodOptionsError("--lods: every ratio must be in (0, 1], got " + fixed_number(r, 4));
  for (size_t f : o.faces)
    if (f == 0) throw LodOptionsError("--faces must be at least 1");
  if (o.max_influences < 1 || o.max_influences > Influences::kCapacity)
    throw LodOptionsError("--max-influences must be 1 to " + std::to_string(Influences::kCapacity));
  if (o.poses < 0 || o.poses > kMaxLodPoses)
    throw LodOptionsError("--poses must be 1 to " + std::to_string(kMaxLodPoses) + ", or 0 to leave it to the mesh");
  const auto& selections = pose_selections();
  if (std::find(selections.begin(), selections.end(), o.pose_select) == selections.end())
    throw LodOptionsError("--pose-select must be " + pose_selection_names() + ", got \"" + o.pose_select + "\"");
  if (!o.method.empty() && !is_lod_method(o.method)) throw LodOptionsError("--method must be " + lod_method_names());
  if (o.threads < 0) throw LodOptionsError("--threads must be 0 (the hardware's) or more");
  for (double v : {o.joint_guard, o.max_error, o.joint_energy, o.anim_error, o.normal_weight})
    if (!(v >= 0.0) || !std::isfinite(v))
      throw LodOptionsError(
          "--joint-guard, --max-error, --joint-energy, --anim-error and --normal-weight must be finite and >= 0");
  if (!(o.area_exponent >= 0.0 && o.area_exponent <= 1.0) && o.area_exponent != kAutoAreaExponent)
    throw LodOptionsError("--error: the area exponent must be in [0, 1] (or -1: by the input's size), got " +
                          fixed_number(o.area_exponent, 4));
  if (!(o.area_floor >= 0.0) || !std::isfinite(o.area_floor))
    throw LodOptionsError("--area-floor must be finite and >= 0");
  for (int j : o.max_joints)
    if (j < 1) throw LodOptionsError("--max-joints: every value must be at least 1");
  if (o.max_error > 0.0 && (!o.max_joints.empty() || o.joint_energy > 0.0))
    throw LodOptionsError(
        "--max-error cannot be combined with --max-joints or --joint-energy: the skeleton LoD re-solves the skins "
        "after the decimation, and the bound would no longer hold");
}

void check_lod_options(const LodOptions& o, const SkinnedMesh& mesh, const std::string& name) {
  check_lod_options(o);
  for (size_t f : o.faces)
    if (f > mesh.n_faces())
      throw LodOptionsError("--faces " + std::to_string(f) + " is more than the input's " +
                            std::to_string(mesh.n_faces()) + " triangles");
  lod_pose_clip(o, mesh, name);
  const int k = lod_pose_count(o, mesh);
  const size_t poses = 2 * size_t(k) + 2;  // examples + bind, held-out frames in between
  const size_t need_mb = (poses * mesh.n_vertices() * kBytesPerVertexPose >> 20) + 1;
  if (o.max_memory_mb > 0 && need_mb > o.max_memory_mb)
    throw LodOptionsError("--poses " + std::to_string(k) + ": needs about " + std::to_string(need_mb) +
                          " MB for this mesh (" + std::to_string(mesh.n_vertices()) + " vertices), over --max-memory " +
                          std::to_string(o.max_memory_mb) + " MB");
  const size_t stored = frame_times(mesh).size();
  if (o.keyframes > 0 && stored == 0)
    throw LodOptionsError("--keyframes: " + name + " reads as a still mesh (its stored frames all have one shape)");
  if (o.keyframes > stored)
    throw LodOptionsError("--keyframes " + std::to_string(o.keyframes) + " is more than the " + std::to_string(stored) +
                          " frames");
  const std::string method = lod_method_for(o, mesh);
  if (o.max_error > 0.0 && (method == "frames" || method == "deform"))
    throw LodOptionsError(
        "--max-error bounds the methods whose vertices the skinned solver places (skinned, decoro, "
        "dsd, rest, compact, static); --method " +
        method + " places them itself");
}

}  // namespace OpenMeshSkinned

#pragma once
/** \file Skeleton.hh
 *  The skeleton, animation clips and example poses that travel with a skinned mesh.
 *
 *  Convention: mesh vertices are stored in the scene's root space, and a joint's inverse bind matrix maps
 *  that space to the joint's space at bind time. A pose is one skinning matrix per joint,
 *  M_k = global_k(pose) * inverse_bind_k, so the bind pose is the identity for every joint and the posed
 *  position of a vertex is sum_k w_k M_k v (linear blend skinning).
 */

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace OpenMeshSkinned {

using Affine3 = Eigen::Matrix<double, 3, 4>;  ///< affine map [R | t], rows x, y, z

/// A joint (a node of the scene hierarchy that deforms or carries joints).
struct Joint {
  std::string name;
  int parent = -1;                                           ///< index into Skeleton::joints, -1 for a root
  Eigen::Matrix4d rest_local = Eigen::Matrix4d::Identity();  ///< transform relative to the parent when not animated
  Eigen::Matrix4d inverse_bind = Eigen::Matrix4d::Identity();
};

/// Joints ordered so that every parent comes before its children.
struct Skeleton {
  std::vector<Joint> joints;

  int size() const { return static_cast<int>(joints.size()); }
  int find(const std::string& name) const;
  /// Global transforms of all joints from their local transforms (parents first).
  std::vector<Eigen::Matrix4d> globals(const std::vector<Eigen::Matrix4d>& locals) const;
  /// Skinning matrices global_k * inverse_bind_k.
  std::vector<Affine3> skinning(const std::vector<Eigen::Matrix4d>& locals) const;
};

/// Keyframes of one joint. Times are in seconds.
struct Channel {
  int joint = -1;
  std::vector<double> translation_times;
  std::vector<Eigen::Vector3d> translations;
  std::vector<double> rotation_times;
  std::vector<Eigen::Quaterniond> rotations;
  std::vector<double> scale_times;
  std::vector<Eigen::Vector3d> scales;
};

/// Keyframes of one morph target's weight (linear interpolation, as glTF's LINEAR). Times in seconds.
struct MorphChannel {
  int target = -1;  ///< index into the mesh's "m:morph_targets"
  std::vector<double> times;
  std::vector<double> weights;
};

/// An animation clip: keyframed channels; joints without a channel keep their rest transform, morph
/// targets without a channel keep weight 0.
struct Clip {
  std::string name;
  double duration = 0.0;  ///< seconds; channels' keys lie in [0, duration]
  std::vector<Channel> channels;
  std::vector<MorphChannel> morph_channels;
};

/// Adds every key time of \p ch (translation, rotation and scale keys) to \p times, then sorts \p times and
/// drops repeats.
void add_key_times(const Channel& ch, std::vector<double>& times);

/// One example pose: a skinning matrix per joint, relative to the bind pose, and the morph targets'
/// weights (empty: all 0). Morph offsets are added to the rest position before skinning, as in glTF.
struct Pose {
  std::string label;  ///< e.g. "walk@0.25s"
  std::vector<Affine3> joint;
  std::vector<double> morph_weights;

  /// The bind pose of a skeleton with \p n joints (all identities).
  static Pose identity(int n, std::string label = "bind");
  /// Every matrix entry and morph weight finite (keys of huge values can overflow when composed).
  bool finite() const;
};

/// A morph target (blend shape): its per-vertex offsets live in "v:morph_deltas".
struct MorphTarget {
  std::string name;
  bool normals = false;  ///< the input gave it normal offsets: the export writes them (Morph.hh says how)
};

/// Local transforms of every joint of \p skel for \p clip at \p time (seconds, clamped into the clip):
/// translations and scales are interpolated linearly, rotations by slerp.
std::vector<Eigen::Matrix4d> sample_locals(const Skeleton& skel, const Clip& clip, double time);

/// Weights of the morph targets \p clip animates at \p time (clamped into the clip), indexed by target
/// (targets without a channel: 0). Empty when the clip animates no morph target.
std::vector<double> sample_morph_weights(const Clip& clip, double time);

/// The example pose of \p clip at \p time.
Pose sample_pose(const Skeleton& skel, const Clip& clip, double time);

/// \p k poses at evenly spaced times over \p clip, both ends included (one pose at time 0 when k == 1).
std::vector<Pose> sample_poses_evenly(const Skeleton& skel, const Clip& clip, int k);

/// Poses of \p clip at the given times.
std::vector<Pose> sample_poses_at(const Skeleton& skel, const Clip& clip, const std::vector<double>& times);

/// Splits an affine 4x4 into translation, rotation and (positive or mirrored) scale; shear is dropped.
void decompose_trs(const Eigen::Matrix4d& m, Eigen::Vector3d& t, Eigen::Quaterniond& r, Eigen::Vector3d& s);
Eigen::Matrix4d compose_trs(const Eigen::Vector3d& t, const Eigen::Quaterniond& r, const Eigen::Vector3d& s);

}  // namespace OpenMeshSkinned

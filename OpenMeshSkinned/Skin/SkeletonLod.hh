#pragma once
/** \file SkeletonLod.hh
 *  Skeleton LoD after Savoye & Meyer (2008, 4.1): joint energy from the clips, the labelling of joints into
 *  root, end-effector, major, extreme and minor ones, and the removal of the least energetic minor joints
 *  (only minor joints go, so every kinematic sub-chain keeps its ends: the skeleton's homotopy is kept).
 *  A removed joint's motion is baked into its children's local transforms, so every kept joint moves
 *  exactly as before; the mesh side (SkeletonLodT.hh) hands the removed joints' weights over and re-solves
 *  the skins.
 */

#include "OpenMeshSkinned/Skin/Skeleton.hh"

#include <functional>
#include <vector>

namespace OpenMeshSkinned {

enum class JointLabel { Root, EndEffector, Major, Extreme, Minor };

/// Depth of every joint in its tree (roots 0).
std::vector<int> joint_depths(const Skeleton& skel);

/// The change between two rotations in the paper's terms: over the three Euler angles, each the short way
/// round, summed and divided by pi (joint_energy() and merge_key_frames() both measure motion so).
double euler_change(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);

/** The paper's labelling rules, in order: depth 0 -> root; no child -> end-effector; more than 1.9 x the
 *  average number of neighbours (parent and children) and shallower than the average depth -> major,
 *  deeper -> extreme; otherwise minor (the only removable kind). */
std::vector<JointLabel> label_joints(const Skeleton& skel);

/** Joint energy over all clips: rho(j) * sum over the three Euler angles of the total variation of the
 *  angle over the joint's rotation keys, divided by pi. rho(j) = (h - d(j)) / h, d the joint's depth and h
 *  the skeleton's. (The extracted formula sums R(b+1) - R(b) inside the absolute value, which telescopes
 *  to the last-minus-first angle and would call a joint that swings and returns still: the sum of
 *  |R(b+1) - R(b)| is what the text describes. Max(R^a), the joint's range about an axis, is not in the
 *  files: pi, the largest an Euler angle can be.) */
std::vector<double> joint_energy(const Skeleton& skel, const std::vector<Clip>& clips);

struct SkeletonReduction {
  Skeleton skeleton;           ///< the kept joints, parents first
  std::vector<int> new_index;  ///< per original joint: its index in skeleton, -1 when removed
  std::vector<int> heir;       ///< per original joint: itself when kept, else its nearest kept ancestor
  std::vector<Clip> clips;     ///< the clips for the kept joints, removed joints' motion baked in
};

/** What removing joint \p j costs when \p heir (its nearest kept ancestor) takes over its motion. */
using JointRemovalCost = std::function<double(int j, int heir)>;

/** Removes every minor joint whose energy is under \p energy_threshold (the paper's threshold), then more
 *  minor joints until at most \p max_joints remain (or no minor joint is left): the least energetic first
 *  (the paper), or, given \p cost, the cheapest first, re-costed after every removal (heirs change as
 *  ancestors go). Kept joints keep their inverse binds and move as before in every clip (exactly at
 *  every key). */
SkeletonReduction reduce_skeleton(const Skeleton& skel, const std::vector<Clip>& clips, int max_joints,
                                  const JointRemovalCost& cost = nullptr, double energy_threshold = 0.0);

}  // namespace OpenMeshSkinned

#pragma once
// An independent glTF 2.0 poser for the tests: it reads a file with tinygltf and poses it exactly as the
// specification says, sharing no code with the library's skinning, so it can judge what the library
// writes and how the library poses what it reads.
//   skinned vertex: sum_k w_k * world(joint_k) * IBM_k * (v + sum_i m_i * delta_i)  (mesh node ignored)
//   unskinned:      world(node) * (v + sum_i m_i * delta_i)

#include <tiny_gltf.h>

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace omsk_spec {

struct Soup {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
  /// TEXCOORD_0 per point ((0, 0) where a primitive has none); has_uv: some primitive had it.
  std::vector<Eigen::Vector2d> uvs;
  bool has_uv = false;
};

/// Loads a .gltf or .glb; throws std::runtime_error with tinygltf's message.
tinygltf::Model load(const std::string& path);
/// Writes a model as .glb (buffers and images embedded).
void save_glb(tinygltf::Model& model, const std::string& path);

/// An accessor's elements as doubles (normalised integers mapped to [0, 1]), count * components values.
std::vector<double> read(const tinygltf::Model& model, int accessor);
int components(const tinygltf::Accessor& acc);

/// Largest input time of animation \p anim.
double duration(const tinygltf::Model& model, int anim);

/// The scene posed at \p time of animation \p anim (anim < 0: no animation). Every triangle of every
/// mesh instance of the default scene; points are all vertices of those primitives.
Soup pose(const tinygltf::Model& model, int anim, double time);

/// Bounding-box diagonal of the points that triangles use.
double diagonal(const Soup& s);

/// For each point used by a triangle of \p a, the distance to the nearest point used by a triangle of
/// \p b; returns the largest. O(n log n) in practice (sorted sweep).
double max_nearest_distance(const Soup& a, const Soup& b);

}  // namespace omsk_spec

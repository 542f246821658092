#pragma once
// Messy characters built from Debian's assimp test models, the way real exports are messy: a rotated and
// scaled root with the skinned mesh node below it (Mixamo / FBX -> glTF), a rigid mesh under a joint,
// a second skin with its own joint order and bind space, a morph target with a weight channel, and
// degenerate faces. Each builder edits a tinygltf model in place; the spec poser in gltf_spec.hh judges
// the results.

#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace omsk_fixtures {

/// Testwuson.X read by the library and written as a tidy GLB into \p dir; returns that file's model.
tinygltf::Model testwuson(const std::string& dir);

/// Puts every scene root under a new node "Armature" rotated by \p degrees_x about X and scaled by
/// \p scale, and the skinned mesh nodes under a child "Body" with a transform the spec ignores.
void wrap_under_rotated_root(tinygltf::Model& m, double degrees_x = -90.0, double scale = 0.01);

/// Adds an unskinned box (a helmet) as a child of the joint named \p joint, offset along its local Y.
void attach_rigid_box(tinygltf::Model& m, const std::string& joint, double size);

/// Moves the second half of the first skinned primitive's triangles into a new mesh with a skin of its
/// own: joints listed in reverse order, vertices stored in another frame (rotated and moved) with inverse
/// bind matrices to match, so it poses exactly like before.
void split_into_second_skin(tinygltf::Model& m);

/// Adds a morph target "Bulge" to every primitive of the first skinned mesh (vertices in the top third
/// move outwards by 5% of the height) and a weights channel 0 -> 1 -> 0 to the first animation.
void add_morph_target(tinygltf::Model& m);

/// Appends triangles with a repeated index and a duplicate of an existing triangle to the first primitive.
void add_degenerate_faces(tinygltf::Model& m);

/// Appends data to buffer 0 and returns a new accessor over it.
int add_accessor(tinygltf::Model& m, const std::vector<float>& data, int type, size_t count);
int add_index_accessor(tinygltf::Model& m, const std::vector<uint32_t>& data);

}  // namespace omsk_fixtures

#pragma once
/** \file Procedural.hh
 *  The papers' own test characters, generated: DeCoro & Rusinkiewicz's tapered leg bending at the knee,
 *  and Landreneau & Schaefer's square column bent in several example poses.
 */

#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

namespace OpenMeshSkinned {

struct TubeOptions {
  int around = 32;  ///< segments around the tube
  int along = 64;   ///< segments along the tube
  double length = 2.0;
  double radius_base = 0.25;
  double radius_tip = 0.15;  ///< < radius_base tapers
  bool square = false;       ///< square cross-section instead of a circle
  int bones = 2;             ///< a chain of equal bones along +y
  double blend = 0.1;        ///< half-width (fraction of length) of the weight blend at each joint
};

/** A tube along +y, skinned to a chain of bones, with one clip "bend" in which every joint but the root
 *  rotates about +x from 0 to \p bend_degrees over one second. The example poses are left at the bind
 *  pose only. Vertices blend linearly (smoothstep) between neighbouring bones near each joint. */
SkinnedMesh make_skinned_tube(const TubeOptions& opt, double bend_degrees);

/// DeCoro's leg: tapered cylinder, two bones, knee bending 0..90 degrees; example poses at 0 and 90.
SkinnedMesh make_bending_cylinder(int around = 32, int along = 64);

/** Landreneau & Schaefer's square column: 4 bones; \p around x \p along x 2 triangles (default 128 x 448
 *  x 2 = 114,688 as in their Table 1); four example poses bending it forward, back, left and right, and
 *  one clip "sway" (3 s) that passes through them at 0, 1, 2 and 3 s. */
SkinnedMesh make_square_column(int around = 128, int along = 448);

/** Spreads a character's skin over more bones, to make many-influence test characters out of real ones
 *  (e.g. Testwuson, 4 bones a vertex, into an 8-bone one): \p steps rounds of Laplacian smoothing of the
 *  weight field, each vertex's weights becoming half its own and half its neighbours' average; after each
 *  round the heaviest \p max_influences (<= Influences::kCapacity) are kept and renormalised. */
void diffuse_skin_weights(SkinnedMesh& mesh, int steps, int max_influences);

}  // namespace OpenMeshSkinned

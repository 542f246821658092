#pragma once
/** \file MakeLods.hh
 *  The whole job in one call: the LOD chain of a skinned (or frame-animated) character from one pass of the
 *  decimater with a snapshot per level, the fold-limit ladder and fallback placements, the final fit, the
 *  skeleton and motion LoD, and the held-out evaluation — what the skinned-decimate tool does between reading
 *  the input and writing the LODs.
 *
 *      SkinnedMesh hero;
 *      import_skinned("hero.fbx", hero);
 *      LodOptions options;
 *      options.ratios = {0.5, 0.25, 0.1};
 *      LodChain chain = make_lods(hero, options);
 *      save_lods(chain, "hero.glb");  // hero_lod1.glb, hero_lod2.glb, hero_lod3.glb
 */

#include <OpenMeshSkinned/Lod/CheckLodOptions.hh>
#include <OpenMeshSkinned/Lod/Evaluate.hh>
#include <OpenMeshSkinned/Lod/LodMethods.hh>
#include <OpenMeshSkinned/Lod/LodOptions.hh>
#include <OpenMeshSkinned/Lod/LodPoses.hh>
#include <OpenMeshSkinned/Lod/LodProgress.hh>
#include <OpenMeshSkinned/Lod/LodReport.hh>

#include <string>

namespace OpenMeshSkinned {

/** The LODs \p options asks of \p mesh, largest first, each with its report. \p name names the mesh in
 *  messages. Throws LodOptionsError for a request that cannot be carried out (the CLI's one-line messages),
 *  LodCancelled when \p callbacks cancels, IOError when the clips' poses do not compose. \p mesh is not
 *  changed. */
LodChain make_lods(const SkinnedMesh& mesh, const LodOptions& options, const LodCallbacks& callbacks = {},
                   const std::string& name = "the mesh");

/// A frame animation's options.keyframes stored frames that rebuild all its frames best by interpolation
/// (the key-frame GA), with a message comparing it to even spacing.
std::vector<size_t> choose_lod_keyframes(const SkinnedMesh& mesh, size_t keyframes, const LodCallbacks& callbacks);

}  // namespace OpenMeshSkinned

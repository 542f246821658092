#pragma once
// Meshes animated without a skeleton in the tool (MD2/MD3/MDL, numbered sequences): which files make one,
// and the near-rigid segmentation mode (--segment).

#include "Options.hh"

#include <OpenMeshSkinned/IO/FrameFiles.hh>
#include <OpenMeshSkinned/IO/OutputSet.hh>

#include <string>
#include <vector>

namespace skinned_decimate {

using OpenMeshSkinned::frame_files;  // the rule the Python package shares
using OpenMeshSkinned::frame_rate;

/** --segment OUT.glb: \p mesh cut into near-rigid parts (Lee et al.) over its frames (a frame animation's
 *  stored frames, or its clips sampled), written as OUT.glb with one coloured material per part (the
 *  animation kept) and OUT.json with each face's part; both staged in \p outputs. */
void write_segmentation(const Mesh& mesh, const std::string& out, OpenMeshSkinned::OutputSet& outputs);

/// OUT.json beside OUT.glb.
std::string segmentation_json_path(const std::string& glb);

}  // namespace skinned_decimate

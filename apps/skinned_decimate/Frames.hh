#pragma once
// Meshes animated without a skeleton in the tool (MD2/MD3/MDL, numbered sequences): which files make one,
// and the near-rigid segmentation mode (--segment).

#include "Options.hh"

#include <OpenMeshSkinned/IO/OutputSet.hh>

#include <string>
#include <vector>

namespace skinned_decimate {

/// The files of the frame animation \p input stands for: itself when it stores frames (MD2/MD3/MDL), its
/// numbered siblings when \p sequences, it is an OBJ, PLY, STL or OFF file and there are two or more;
/// empty when it is one mesh.
std::vector<std::string> frame_files(const std::string& input, bool sequences);

/// The frame rate to play \p files at: \p fps when given, else 10 for Quake's formats (their animations
/// run at the server's 10 Hz) and 24 for sequences.
double frame_rate(const std::vector<std::string>& files, double fps);

/** --segment OUT.glb: \p mesh cut into near-rigid parts (Lee et al.) over its frames (a frame animation's
 *  stored frames, or its clips sampled), written as OUT.glb with one coloured material per part (the
 *  animation kept) and OUT.json with each face's part; both staged in \p outputs. */
void write_segmentation(const Mesh& mesh, const std::string& out, OpenMeshSkinned::OutputSet& outputs);

/// OUT.json beside OUT.glb.
std::string segmentation_json_path(const std::string& glb);

}  // namespace skinned_decimate

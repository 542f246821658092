#pragma once
/** \file FrameFiles.hh
 *  Which files make one mesh animated without a skeleton, and the rate it plays at: the rule the command
 *  line and the Python package's load() share.
 */

#include <string>
#include <vector>

namespace OpenMeshSkinned {

/// The files of the frame animation \p input stands for: itself when it stores frames (MD2/MD3/MDL), its
/// numbered siblings when \p sequences, it is an OBJ, PLY, STL or OFF file and there are two or more;
/// empty when it is one mesh.
std::vector<std::string> frame_files(const std::string& input, bool sequences = true);

/// The frame rate to play \p files at: \p fps when given (> 0), else 10 for Quake's formats (their
/// animations run at the server's 10 Hz) and 24 for sequences.
double frame_rate(const std::vector<std::string>& files, double fps = 0.0);

}  // namespace OpenMeshSkinned

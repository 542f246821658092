#pragma once
/** \file StoredFrames.hh
 *  Which frames make one vertex animation: the frames a Quake-family file stores, and the numbered files of
 *  a sequence. Read from file names and headers alone, before (and without) the reader.
 */

#include <cstddef>
#include <string>
#include <vector>

namespace OpenMeshSkinned {

/// Frames stored in a vertex-animated file, from its header (MD2, MD3, MDL); 1 for any other file.
size_t stored_frame_count(const std::string& path);

/** The numbered files \p path belongs to: for "dir/walk_0007.obj", every "dir/walk_<digits>.obj", in the
 *  order of their numbers. Just {path} when its name does not end in a number. */
std::vector<std::string> numbered_sequence(const std::string& path);

}  // namespace OpenMeshSkinned

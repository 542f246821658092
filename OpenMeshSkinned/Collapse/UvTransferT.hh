#pragma once
/** \file UvTransferT.hh
 *  The name the decimater modules have always used for the re-interpolation of a moved vertex's corners.
 *  It carries every per-corner set now (UV0, further UV sets, colours): see CornerTransferT.hh.
 */

#include "OpenMeshSkinned/Collapse/CornerTransferT.hh"

namespace OpenMeshSkinned {

template <typename Mesh>
using UvTransferT = CornerTransferT<Mesh>;

}  // namespace OpenMeshSkinned

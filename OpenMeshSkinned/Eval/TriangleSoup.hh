#pragma once
/** \file TriangleSoup.hh
 *  Positions and index triples: a surface as the distance measures see it.
 */

#include <Eigen/Core>

#include <array>
#include <vector>

namespace OpenMeshSkinned {

/// A triangle soup: positions and index triples.
struct TriangleSoup {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
};

}  // namespace OpenMeshSkinned

#pragma once
/** \file DualGraph.hh
 *  The graph Lee et al.'s near-rigid segmentation works on (NearRigidSegmentation.hh): a node per face, an
 *  arc across each interior edge carrying the deformation distance of its two faces (eq. 5), and the
 *  searches the segmentation runs on it. Internal to the segmentation.
 */

#include "OpenMeshSkinned/Deform/DeformationAnalysis.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <vector>

namespace OpenMeshSkinned::detail {

struct Arc {
  int to;
  double dis;     // eq. 5
  double d_norm;  // D / avg(D)
  double edge;    // length of the shared edge, rest shape
};

struct DualGraph {
  std::vector<std::vector<Arc>> arcs;  // by face index
  std::vector<double> area;
};

/// The dual graph of \p mesh in its rest shape \p ref, with the deformation gradients \p g; \p delta
/// weights the frames as eq. 5 does.
DualGraph dual_graph(const SkinnedMesh& mesh, const FramePoints& ref, const FaceGradients<SkinnedMesh>& g,
                     double delta);
/// Shortest distances from \p sources; \p origin[f] = the source that reaches f first (-1: unreachable).
std::vector<double> shortest_paths(const DualGraph& G, const std::vector<int>& sources,
                                   std::vector<int>* origin = nullptr);
/// The influence region of feature face \p p: the faces of B around it where the harmonic field that is 1 at
/// p and 0 on A reaches 0.01 (conductance 1 / Dis, so that a bending edge holds the field back).
std::vector<int> influence_region(const DualGraph& G, const std::vector<char>& in_a, int p);
/// Connected pieces of the faces labelled \p label (neighbours across edges).
std::vector<std::vector<int>> pieces(const DualGraph& G, const std::vector<int>& part, int label);

}  // namespace OpenMeshSkinned::detail

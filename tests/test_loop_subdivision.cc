// Loop subdivision of a skinned mesh (Mesh/LoopSubdivision.hh).
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/LoopSubdivision.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

TEST(LoopSubdivision, QuadruplesTrianglesAndRefinesWeightsLikePositions) {
  const Mesh coarse = make_bending_cylinder(8, 8);
  const Mesh fine = loop_subdivide(coarse);
  EXPECT_EQ(fine.n_faces(), 4 * coarse.n_faces());
  EXPECT_EQ(fine.n_vertices(), coarse.n_vertices() + coarse.n_edges());
  omsk_test::expect_valid_skin(fine, Influences::kCapacity);
  // Weights are blended with the position masks: along the tube the knee weight still rises with height,
  // and a new vertex's weight lies within its parents' range.
  const auto h = influences_handle(fine);
  for (auto vh : fine.vertices()) {
    const double y = fine.point(vh)[1];
    const double w = fine.property(h, vh).weight_of(1);
    if (y < 0.7) {
      EXPECT_LT(w, 0.01) << y;
    }
    if (y > 1.3) {
      EXPECT_GT(w, 0.99) << y;
    }
  }
  // The skeleton and the clips come along.
  EXPECT_EQ(clips(fine).size(), clips(coarse).size());
  EXPECT_EQ(skeleton(fine).size(), skeleton(coarse).size());
}

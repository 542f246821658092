// The procedural characters' helpers: spreading a real character's skin over more bones.
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/Procedural.hh>

using namespace OpenMeshSkinned;

TEST(Procedural, DiffusingTestwusonsSkinGivesEightValidInfluencesThatKeepTheDominantBone) {
  const omsk_test::Mesh original = omsk_test::load_character("X/Testwuson.X", 2);
  omsk_test::Mesh mesh = original;
  ASSERT_LE(omsk_test::max_influences(original), 4);
  diffuse_skin_weights(mesh, 3, 8);
  EXPECT_EQ(omsk_test::max_influences(mesh), 8);
  omsk_test::expect_valid_skin(mesh, 8);
  // Smoothing spreads, it does not move the skin: most vertices keep their heaviest bone.
  const auto h = influences_handle(mesh);
  size_t kept = 0, more = 0;
  for (auto vh : mesh.vertices()) {
    kept += mesh.property(h, vh)[0].joint == original.property(h, vh)[0].joint;
    more += mesh.property(h, vh).size() > original.property(h, vh).size();
  }
  EXPECT_GT(kept, 0.9 * mesh.n_vertices());
  EXPECT_GT(more, 0.5 * mesh.n_vertices());
}

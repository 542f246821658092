// Skin validation (Skin/Validate.hh).
#include "helpers.hh"

#include <OpenMeshSkinned/Skin/Validate.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {
Mesh two_triangles() {
  Mesh mesh;
  mesh.request_vertex_status();
  auto h = add_skin(mesh);
  Joint j;
  j.name = "root";
  skeleton(mesh).joints = {j, j};
  skeleton(mesh).joints[1].parent = 0;
  auto a = mesh.add_vertex({0, 0, 0}), b = mesh.add_vertex({1, 0, 0}), c = mesh.add_vertex({0, 1, 0}),
       d = mesh.add_vertex({1, 1, 0});
  mesh.add_face(a, b, c);
  mesh.add_face(b, d, c);
  for (auto v : mesh.vertices()) mesh.property(h, v) = Influences::rigid(0);
  return mesh;
}
}  // namespace

TEST(Validate, AcceptsAndRenormalisesSmallDeviation) {
  Mesh mesh = two_triangles();
  auto h = influences_handle(mesh);
  Influences inf;
  inf.push(0, 0.6);
  inf.push(1, 0.399);
  mesh.property(h, Mesh::VertexHandle(0)) = inf;
  const auto rep = validate_skin(mesh);
  EXPECT_EQ(rep.vertices_renormalized, 1u);
  EXPECT_NEAR(mesh.property(h, Mesh::VertexHandle(0)).sum(), 1.0, 1e-15);
}

TEST(Validate, RejectsEachKindOfBadSkinWithAPreciseMessage) {
  struct Case {
    std::vector<JointWeight> w;
    const char* expect;
  };
  const std::vector<Case> cases = {
      {{{0, std::nan("")}}, "non-finite"}, {{{0, 1.5}, {1, -0.5}}, "negative"},
      {{{0, 0.5}}, "sum to 0.5"},          {{{0, 0.0}}, "sum to 0"},
      {{{7, 1.0}}, "out of range"},        {{}, "no bone influences"},
  };
  for (const auto& c : cases) {
    Mesh mesh = two_triangles();
    Influences inf;
    for (const auto& jw : c.w) inf.push(jw.joint, jw.weight);
    mesh.property(influences_handle(mesh), Mesh::VertexHandle(2)) = inf;
    try {
      validate_skin(mesh);
      ADD_FAILURE() << "accepted a skin that should fail with: " << c.expect;
    } catch (const SkinError& e) {
      EXPECT_NE(std::string(e.what()).find("vertex 2"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(c.expect), std::string::npos) << e.what();
    }
  }
}

TEST(Validate, RejectsMoreInfluencesThanAllowed) {
  Mesh mesh = two_triangles();
  Influences inf;
  for (int i = 0; i < 2; ++i) inf.push(i, 0.5);
  mesh.property(influences_handle(mesh), Mesh::VertexHandle(1)) = inf;
  ValidationOptions opt;
  opt.max_influences = 1;
  EXPECT_THROW(validate_skin(mesh, opt), SkinError);
}

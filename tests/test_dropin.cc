// The modules are ordinary OpenMesh decimater modules: they mix with OpenMesh's own, work in every
// decimater, and with float as well as double meshes.
#include "helpers.hh"

#include <OpenMeshSkinned/Mesh/Procedural.hh>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/McDecimaterT.hh>
#include <OpenMesh/Tools/Decimater/MixedDecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

struct FloatTraits : OpenMesh::DefaultTraits {
  VertexAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Normal | OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::Status);
};
using FloatMesh = OpenMesh::TriMesh_ArrayKernelT<FloatTraits>;

// The same character on a float mesh: copy points, faces and the skin properties.
FloatMesh to_float(const Mesh& src) {
  FloatMesh dst;
  const auto hs = influences_handle(src);
  const auto hd = add_skin(dst);
  for (auto vh : src.vertices()) {
    const auto p = src.point(vh);
    const auto v = dst.add_vertex(FloatMesh::Point(float(p[0]), float(p[1]), float(p[2])));
    dst.property(hd, v) = src.property(hs, vh);
  }
  for (auto fh : src.faces()) {
    std::vector<FloatMesh::VertexHandle> vs;
    for (auto v : src.fv_range(fh)) vs.emplace_back(v.idx());
    dst.add_face(vs);
  }
  skeleton(dst) = skeleton(src);
  example_poses(dst) = example_poses(src);
  dst.update_face_normals();
  return dst;
}

template <typename M>
void expect_skin_ok(const M& mesh, int cap) {
  const auto h = influences_handle(mesh);
  for (auto vh : mesh.vertices()) {
    const auto& inf = mesh.property(h, vh);
    ASSERT_LE(inf.size(), cap);
    ASSERT_NEAR(inf.sum(), 1.0, 1e-6);
  }
}

}  // namespace

TEST(DropIn, TogetherWithOpenMeshsOwnModules) {
  Mesh mesh = omsk_test::load_character("X/Testwuson.X", 6);
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModSkinnedQuadricT<Mesh>::Handle hq;
  ModWeightCapT<Mesh>::Handle hc;
  ModSkinnedFoldOverT<Mesh>::Handle hf;
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle hn;
  OpenMesh::Decimater::ModAspectRatioT<Mesh>::Handle ha;
  dec.add(hn);
  dec.add(hq);
  dec.add(ha);
  dec.add(hc);
  dec.add(hf);
  dec.module(hc).set_max_influences(3);
  dec.module(ha).set_aspect_ratio(10.0);
  ASSERT_TRUE(dec.initialize());
  const size_t before = mesh.n_faces();
  EXPECT_GT(dec.decimate_to_faces(0, before / 4), 0u);
  mesh.garbage_collection();
  EXPECT_LT(mesh.n_faces(), before / 2);
  omsk_test::expect_valid_skin(mesh, 3);
}

TEST(DropIn, ModulesInAnyOrderAndSubset) {
  // Binary modules first, the priority module last: the shared solver must not care.
  Mesh mesh = make_bending_cylinder(16, 32);
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModSkinnedFoldOverT<Mesh>::Handle hf;
  ModWeightCapT<Mesh>::Handle hc;
  ModSkinnedQuadricT<Mesh>::Handle hq;
  dec.add(hf);
  dec.add(hc);
  dec.add(hq);
  dec.module(hc).set_max_influences(1);
  ASSERT_TRUE(dec.initialize());
  dec.decimate_to_faces(0, mesh.n_faces() / 10);
  mesh.garbage_collection();
  expect_skin_ok(mesh, 1);
  EXPECT_LE(mesh.n_faces(), 1024u / 10 * 12 / 10 + 2);
}

TEST(DropIn, FloatMeshTraits) {
  FloatMesh mesh = to_float(make_bending_cylinder(16, 32));
  OpenMesh::Decimater::DecimaterT<FloatMesh> dec(mesh);
  ModSkinnedQuadricT<FloatMesh>::Handle hq;
  ModWeightCapT<FloatMesh>::Handle hc;
  ModSkinnedFoldOverT<FloatMesh>::Handle hf;
  dec.add(hq);
  dec.add(hc);
  dec.add(hf);
  ASSERT_TRUE(dec.initialize());
  const size_t before = mesh.n_faces();
  dec.decimate_to_faces(0, before / 10);
  mesh.garbage_collection();
  EXPECT_LE(mesh.n_faces(), before / 8);
  expect_skin_ok(mesh, 4);
}

TEST(DropIn, MultipleChoiceDecimater) {
  Mesh mesh = make_bending_cylinder(16, 32);
  OpenMesh::Decimater::McDecimaterT<Mesh> dec(mesh);
  ModSkinnedQuadricT<Mesh>::Handle hq;
  ModWeightCapT<Mesh>::Handle hc;
  ModSkinnedFoldOverT<Mesh>::Handle hf;
  dec.add(hq);
  dec.add(hc);
  dec.add(hf);
  dec.module(hc).set_max_influences(2);
  ASSERT_TRUE(dec.initialize());
  const size_t before = mesh.n_faces();
  dec.decimate_to_faces(0, before / 5);
  mesh.garbage_collection();
  EXPECT_LE(mesh.n_faces(), before / 4);
  expect_skin_ok(mesh, 2);
}

TEST(DropIn, MixedDecimater) {
  Mesh mesh = make_bending_cylinder(16, 32);
  OpenMesh::Decimater::MixedDecimaterT<Mesh> dec(mesh);
  ModSkinnedQuadricT<Mesh>::Handle hq;
  ModWeightCapT<Mesh>::Handle hc;
  dec.add(hq);
  dec.add(hc);
  ASSERT_TRUE(dec.initialize());
  const size_t before = mesh.n_faces();
  dec.decimate_to_faces(0, before / 5, 0.5f);
  mesh.garbage_collection();
  EXPECT_LE(mesh.n_faces(), before / 4);
  expect_skin_ok(mesh, 4);
}

TEST(DropIn, ModulesLeaveNoPropertiesOrLocksBehind) {
  Mesh mesh = make_bending_cylinder(16, 32);
  {
    OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
    ModSkinnedQuadricT<Mesh>::Handle hq;
    ModSkinnedFoldOverT<Mesh>::Handle hf;
    dec.add(hq);
    dec.add(hf);
    ASSERT_TRUE(dec.initialize());
    dec.decimate_to_faces(0, mesh.n_faces() / 10);
  }
  OpenMesh::MPropHandleT<std::shared_ptr<CollapseSolverT<Mesh>>> hs;
  EXPECT_FALSE(mesh.get_property_handle(hs, kSolverProperty));
  for (auto vh : mesh.vertices()) EXPECT_FALSE(mesh.status(vh).locked());
  EXPECT_TRUE(has_skin(mesh));
}

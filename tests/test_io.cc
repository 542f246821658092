#include "helpers.hh"
#include "validate.hh"

#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;
using omsk_test::model;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("omsk_test_io_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d / name;
}

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  f << text;
}

std::string import_error(const std::string& path) {
  Mesh mesh;
  try {
    import_skinned(path, mesh);
  } catch (const IOError& e) {
    return e.what();
  }
  return "";
}

// A 2-joint skinned quad as glTF, with the given weights for vertex 0 (the others are rigid on joint 0).
std::string skinned_quad_gltf(const std::array<float, 4>& w0, const fs::path& out) {
  tinygltf::Model m;
  m.asset.version = "2.0";
  std::vector<unsigned char> bytes;
  auto view = [&](const void* data, size_t n, int target) {
    while (bytes.size() % 4) bytes.push_back(0);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = bytes.size();
    v.byteLength = n;
    v.target = target;
    bytes.insert(bytes.end(), static_cast<const unsigned char*>(data), static_cast<const unsigned char*>(data) + n);
    m.bufferViews.push_back(v);
    return int(m.bufferViews.size()) - 1;
  };
  auto accessor = [&](int v, int ctype, int type, size_t count, std::vector<double> mn = {},
                      std::vector<double> mx = {}) {
    tinygltf::Accessor a;
    a.bufferView = v;
    a.componentType = ctype;
    a.type = type;
    a.count = count;
    a.minValues = mn;
    a.maxValues = mx;
    m.accessors.push_back(a);
    return int(m.accessors.size()) - 1;
  };
  const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  const uint16_t joints[] = {0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const float weights[] = {w0[0], w0[1], w0[2], w0[3], 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  const uint16_t idx[] = {0, 1, 2, 1, 3, 2};
  const float ibm[] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] =
      accessor(view(pos, sizeof pos, 34962), 5126, TINYGLTF_TYPE_VEC3, 4, {0, 0, 0}, {1, 1, 0});
  prim.attributes["JOINTS_0"] = accessor(view(joints, sizeof joints, 34962), 5123, TINYGLTF_TYPE_VEC4, 4);
  prim.attributes["WEIGHTS_0"] = accessor(view(weights, sizeof weights, 34962), 5126, TINYGLTF_TYPE_VEC4, 4);
  prim.indices = accessor(view(idx, sizeof idx, 34963), 5123, TINYGLTF_TYPE_SCALAR, 6);
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(prim);
  m.meshes.push_back(mesh);
  tinygltf::Skin skin;
  skin.joints = {0, 1};
  skin.inverseBindMatrices = accessor(view(ibm, sizeof ibm, 0), 5126, TINYGLTF_TYPE_MAT4, 2);
  m.skins.push_back(skin);
  tinygltf::Node root, child, mnode;
  root.name = "root";
  root.children = {1};
  child.name = "child";
  child.translation = {0, 1, 0};
  mnode.name = "quad";
  mnode.mesh = 0;
  mnode.skin = 0;
  m.nodes = {root, child, mnode};
  tinygltf::Scene sc;
  sc.nodes = {0, 2};
  m.scenes.push_back(sc);
  m.defaultScene = 0;
  tinygltf::Buffer b;
  b.data = bytes;
  m.buffers.push_back(b);
  tinygltf::TinyGLTF t;
  EXPECT_TRUE(t.WriteGltfSceneToFile(&m, out.string(), false, true, true, false));
  return out.string();
}

}  // namespace

TEST(Import, RealCharactersCarrySkeletonSkinAndClips) {
  struct Expect {
    const char* file;
    size_t min_clips;
  };
  for (const auto& e : {Expect{"X/Testwuson.X", 3}, Expect{"FBX/animation_with_skeleton.fbx", 1},
                        Expect{"glTF2/simple_skin/simple_skin.gltf", 1}}) {
    SCOPED_TRACE(e.file);
    Mesh mesh;
    const auto rep = import_skinned(model(e.file), mesh);
    EXPECT_FALSE(rep.rigid);
    EXPECT_GT(mesh.n_faces(), 0u);
    EXPECT_EQ(rep.faces, mesh.n_faces());
    EXPECT_GE(clips(mesh).size(), e.min_clips);
    EXPECT_GE(skeleton(mesh).size(), 2);
    // Welding: fewer OpenMesh vertices than split file vertices, or equal when nothing was split.
    EXPECT_LE(rep.welded_vertices, rep.source_vertices + rep.nonmanifold_vertices_added);
    omsk_test::expect_valid_skin(mesh, Influences::kCapacity);
    // Parents before children.
    const auto& sk = skeleton(mesh);
    for (int i = 0; i < sk.size(); ++i) EXPECT_LT(sk.joints[i].parent, i);
  }
}

TEST(Import, ReadingOurOwnGlbKeepsItsSkeleton) {
  // The writer puts the mesh's node beside the joints (and a root above several top joints); reading that
  // back must not add them as joints: every LOD of a LOD, and every re-run, has the input's skeleton.
  for (bool two_roots : {false, true}) {
    SCOPED_TRACE(two_roots ? "two top-level joints" : "one root joint");
    Mesh mesh = make_bending_cylinder(8, 8);
    Skeleton& skel = skeleton(mesh);
    if (two_roots) {
      skel.joints[1].rest_local = skel.joints[0].rest_local * skel.joints[1].rest_local;
      skel.joints[1].parent = -1;
      clips(mesh).clear();
    }
    const auto out = scratch(two_roots ? "own_two_roots.glb" : "own_one_root.glb");
    export_gltf(mesh, out.string());
    Mesh back;
    const auto rep = import_skinned(out.string(), back);
    const Skeleton& sb = skeleton(back);
    ASSERT_EQ(sb.size(), skel.size());
    for (int j = 0; j < sb.size(); ++j) {
      EXPECT_EQ(sb.joints[j].name, skel.joints[j].name);
      EXPECT_EQ(sb.joints[j].parent, skel.joints[j].parent);
      EXPECT_TRUE(sb.joints[j].rest_local.isApprox(skel.joints[j].rest_local, 1e-6));
    }
    EXPECT_EQ(rep.unweighted_vertices, 0u);
  }
}

TEST(Import, AMeshUsedBeforeIsReplacedNotAppendedTo) {
  // Into the same mesh, in and out of process: what comes back is the second file alone.
  for (bool isolate : {false, true}) {
    SCOPED_TRACE(isolate ? "isolated" : "in process");
    ImportOptions opt;
    opt.isolate = isolate;
    Mesh fresh, reused;
    import_skinned(model("glTF2/simple_skin/simple_skin.gltf"), fresh, opt);
    import_skinned(model("X/Testwuson.X"), reused, opt);
    OpenMesh::MPropHandleT<int> own;
    reused.add_property(own, "m:users_own");
    import_skinned(model("glTF2/simple_skin/simple_skin.gltf"), reused, opt);
    EXPECT_EQ(reused.n_vertices(), fresh.n_vertices());
    EXPECT_EQ(skeleton(reused).size(), skeleton(fresh).size());
    EXPECT_EQ(clips(reused).size(), clips(fresh).size());
    EXPECT_EQ(materials(reused).size(), materials(fresh).size());
    OpenMesh::MPropHandleT<int> h;
    EXPECT_FALSE(reused.get_property_handle(h, "m:users_own")) << "the mesh is cleared first, properties too";
  }
}

TEST(Import, WeldsSeamsIntoConnectedTopologyAndKeepsWedgeAttributes) {
  Mesh mesh;
  const auto rep = import_skinned(model("X/Testwuson.X"), mesh);
  EXPECT_LT(rep.welded_vertices, rep.source_vertices);  // the file splits at UV seams
  // A connected surface: almost all edges are interior after welding.
  size_t boundary = 0;
  for (auto eh : mesh.edges()) boundary += mesh.is_boundary(eh);
  EXPECT_LT(boundary, mesh.n_edges() / 10);
  // Seams survive as differing halfedge texcoords around one vertex.
  size_t seam_vertices = 0;
  for (auto vh : mesh.vertices()) {
    std::vector<Mesh::TexCoord2D> uvs;
    for (auto heh : mesh.vih_range(vh))
      if (!mesh.is_boundary(heh)) uvs.push_back(mesh.texcoord2D(heh));
    for (const auto& uv : uvs)
      if ((uv - uvs[0]).norm() > 1e-6) {
        ++seam_vertices;
        break;
      }
  }
  EXPECT_GT(seam_vertices, 0u);
}

TEST(Import, NonManifoldInputKeepsEveryFaceAndSaysSo) {
  // Three triangles on one edge: OpenMesh cannot hold the third without copies.
  const auto p = scratch("fin.obj");
  write_file(p, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  Mesh mesh;
  const auto rep = import_skinned(p.string(), mesh);
  EXPECT_EQ(mesh.n_faces(), 3u);
  EXPECT_GT(rep.nonmanifold_vertices_added, 0u);
  EXPECT_TRUE(rep.rigid);
  bool said = false;
  for (const auto& w : rep.warnings) said |= w.find("non-manifold") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(Import, UnskinnedMeshBecomesOneRigidJointAndSaysSo) {
  const auto p = scratch("tri.obj");
  write_file(p, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Mesh mesh;
  const auto rep = import_skinned(p.string(), mesh);
  EXPECT_TRUE(rep.rigid);
  ASSERT_FALSE(rep.warnings.empty());
  EXPECT_NE(rep.warnings[0].find("no skin"), std::string::npos);
  const auto h = influences_handle(mesh);
  for (auto vh : mesh.vertices()) EXPECT_EQ(mesh.property(h, vh).size(), 1);
}

TEST(Import, BadFilesGiveOneLineErrorsNamingTheFile) {
  const auto missing = scratch("missing.gltf").string();
  const auto empty = scratch("empty.glb");
  write_file(empty, "");
  const auto garbage = scratch("garbage.fbx");
  write_file(garbage, "this is not an FBX file at all\n");
  // A real file cut in half.
  const auto truncated = scratch("truncated.X");
  {
    std::ifstream in(model("X/Testwuson.X"), std::ios::binary);
    std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    write_file(truncated, all.substr(0, all.size() / 2));
  }
  for (const auto& [path, what] :
       std::vector<std::pair<std::string, std::string>>{{missing, "does not exist"},
                                                        {empty.string(), "empty"},
                                                        {garbage.string(), "cannot be read"},
                                                        {truncated.string(), ""},
                                                        {scratch("").string(), "directory"}}) {
    SCOPED_TRACE(path);
    const std::string err = import_error(path);
    ASSERT_FALSE(err.empty()) << "no error for " << path;
    EXPECT_EQ(err.rfind(path, 0), 0u) << err;  // starts with the file name
    EXPECT_EQ(err.find('\n'), std::string::npos) << err;
    EXPECT_NE(err.find(what), std::string::npos) << err;
  }
}

TEST(Import, BadWeightsInAFileAreRefused) {
  EXPECT_EQ(import_error(skinned_quad_gltf({0.5f, 0.5f, 0, 0}, scratch("ok.gltf"))), "");
  // Weights that sum to zero can never be rescaled.
  const std::string zero = import_error(skinned_quad_gltf({0, 0, 0, 0}, scratch("zero.gltf")));
  EXPECT_NE(zero.find("zero.gltf"), std::string::npos) << "all-zero weights accepted";
  EXPECT_NE(zero.find("sum to 0"), std::string::npos) << zero;

  // assimp's glTF reader would drop NaN weights and zero negative ones before we see them: refused first.
  const auto neg = skinned_quad_gltf({1.5f, -0.5f, 0, 0}, scratch("neg.gltf"));
  const auto nan = skinned_quad_gltf({std::nanf(""), 0.5f, 0, 0}, scratch("nan.gltf"));
  EXPECT_NE(import_error(neg).find("has a negative weight in WEIGHTS_0"), std::string::npos) << import_error(neg);
  EXPECT_NE(import_error(nan).find("has a non-finite weight in WEIGHTS_0"), std::string::npos) << import_error(nan);

  // Sums off 1 (raw FBX deformers): strict mode refuses them, the default rescales them and says so.
  const auto off = skinned_quad_gltf({0.5f, 0.3f, 0, 0}, scratch("off.gltf"));
  ImportOptions strict;
  strict.normalize_weights = false;
  Mesh mesh;
  try {
    import_skinned(off, mesh, strict);
    ADD_FAILURE() << "strict import accepted weights that do not sum to 1";
  } catch (const IOError& e) {
    EXPECT_NE(std::string(e.what()).find("sum to"), std::string::npos) << e.what();
  }
  const auto rep = import_skinned(off, mesh);
  EXPECT_EQ(rep.renormalized_vertices, 1u);
  ASSERT_FALSE(rep.warnings.empty());
  EXPECT_NE(rep.warnings.back().find("rescaled"), std::string::npos);
}

TEST(Export, RefusesBadTargetsAndLeavesNothingBehind) {
  Mesh mesh = make_bending_cylinder(8, 8);
  EXPECT_THROW(export_gltf(mesh, scratch("x.obj").string()), IOError);
  const fs::path nodir = scratch("no/such/dir/out.glb");
  EXPECT_THROW(export_gltf(mesh, nodir.string()), IOError);
  EXPECT_FALSE(fs::exists(nodir));
  // A folder we cannot write into (root bypasses permissions, so use a path under a regular file).
  const auto file = scratch("plainfile");
  write_file(file, "x");
  EXPECT_THROW(export_gltf(mesh, (file / "out.glb").string()), IOError);
  // A good write leaves exactly the target, no temporary.
  const fs::path good = scratch("good.glb");
  export_gltf(mesh, good.string());
  omsk_test::expect_valid_gltf(good.string());
  EXPECT_GT(fs::file_size(good), 0u);
  for (const auto& e : fs::directory_iterator(good.parent_path()))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

TEST(Export, InputFileIsNeverModified) {
  const auto src = model("glTF2/simple_skin/simple_skin.gltf");
  const auto before = fs::last_write_time(src);
  const auto size = fs::file_size(src);
  Mesh mesh;
  import_skinned(src, mesh);
  export_gltf(mesh, scratch("simple.gltf").string());
  omsk_test::expect_valid_gltf(scratch("simple.gltf").string());
  EXPECT_EQ(fs::last_write_time(src), before);
  EXPECT_EQ(fs::file_size(src), size);
}

TEST(Export, LodNormalsFollowTheMovedGeometry) {
  // Decimate the leg (vertices move), export, read back: every corner normal is unit and points out of
  // the tube, as the surface now is.
  Mesh mesh = make_bending_cylinder(24, 48);
  omsk_test::decimate(mesh, 0.1);
  const auto out = scratch("lod_normals.glb");
  export_gltf(mesh, out.string());
  omsk_test::expect_valid_gltf(out.string());
  Mesh back;
  import_skinned(out.string(), back);
  size_t checked = 0;
  for (auto heh : back.halfedges()) {
    if (back.is_boundary(heh)) continue;
    const auto n = back.normal(heh);
    const auto p = back.point(back.to_vertex_handle(heh));
    EXPECT_NEAR(n.norm(), 1.0, 1e-5);
    if (p[1] > 0.05 && p[1] < 1.95) {  // away from the open ends
      EXPECT_GT(n[0] * p[0] + n[2] * p[2], 0.0);
      ++checked;
    }
  }
  EXPECT_GT(checked, 100u);
}

TEST(Export, MoreThanFourInfluencesUseASecondJointSet) {
  // Six bones blending over wide zones: vertices with five or six influences need JOINTS_1/WEIGHTS_1.
  Mesh mesh = omsk_test::many_influence_tube(8, 24);
  const auto h = influences_handle(mesh);
  const int most = omsk_test::max_influences(mesh);
  ASSERT_GT(most, 4);
  const auto out = scratch("six.gltf");
  export_gltf(mesh, out.string());
  omsk_test::expect_valid_gltf(out.string());
  Mesh back;
  import_skinned(out.string(), back);
  ASSERT_EQ(back.n_vertices(), mesh.n_vertices());
  const auto hb = influences_handle(back);
  EXPECT_EQ(omsk_test::max_influences(back), most);
  // Same skin at the same place; joints are matched by name (the re-read scene numbers them anew).
  const Skeleton& sm = skeleton(mesh);
  const Skeleton& sb = skeleton(back);
  for (auto vb : back.vertices()) {
    for (auto vm : mesh.vertices())
      if ((back.point(vb) - mesh.point(vm)).norm() < 1e-6) {
        for (const auto& jw : mesh.property(h, vm)) {
          const int jb = sb.find(sm.joints[jw.joint].name);
          ASSERT_GE(jb, 0);
          EXPECT_NEAR(back.property(hb, vb).weight_of(jb), jw.weight, 1e-6);
        }
        break;
      }
  }
}

TEST(Export, JointsOfSeveralHierarchiesShareARootThatIsNoJoint) {
  // Two top-level joints (a corrupt or unusual hierarchy): glTF's skins need a common root, so the writer
  // adds a node above them, and the skin still lists exactly the mesh's joints.
  Mesh mesh = make_bending_cylinder(8, 8);
  Skeleton& skel = skeleton(mesh);
  ASSERT_EQ(skel.size(), 2);
  ASSERT_EQ(skel.joints[1].parent, 0);
  skel.joints[1].rest_local = skel.joints[0].rest_local * skel.joints[1].rest_local;
  skel.joints[1].parent = -1;
  clips(mesh).clear();
  const auto out = scratch("two_roots.glb");
  export_gltf(mesh, out.string());
  omsk_test::expect_valid_gltf(out.string());
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, out.string())) << err;
  ASSERT_EQ(m.skins.size(), 1u);
  EXPECT_EQ(m.skins[0].joints, (std::vector<int>{0, 1}));
  const auto root = std::find_if(m.nodes.begin(), m.nodes.end(), [](const auto& n) { return n.name == "joints_root"; });
  ASSERT_NE(root, m.nodes.end());
  EXPECT_EQ(root->children, (std::vector<int>{0, 1}));
}

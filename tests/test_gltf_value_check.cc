// GltfValueCheck: a NaN skin weight is refused, not silently dropped by the reader.
#include "gltf_spec.hh"

#include <OpenMeshSkinned/IO/GltfValueCheck.hh>
#include <OpenMeshSkinned/IO/Import.hh>

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

namespace fs = std::filesystem;
using namespace OpenMeshSkinned;

namespace {
const std::string simple_skin = std::string(OMSK_TEST_MODELS) + "/glTF2/simple_skin/simple_skin.gltf";

// simple_skin changed by \p edit, as .gltf with inline buffers.
template <typename Edit>
fs::path edited(Edit edit) {
  const fs::path d = fs::temp_directory_path() / ("omsk_valuecheck_" + std::to_string(::getpid()));
  fs::create_directories(d);
  tinygltf::Model m = omsk_spec::load(simple_skin);
  edit(m);
  const fs::path out = d / "w.gltf";
  tinygltf::TinyGLTF w;
  EXPECT_TRUE(w.WriteGltfSceneToFile(&m, out.string(), true, true, true, false));
  return out;
}

// Component \p c of vertex \p v of attribute \p name (T: its component type) set to \p value.
template <typename T>
fs::path with_value(const char* name, T value, size_t v, size_t c) {
  return edited([&](tinygltf::Model& m) {
    const auto& acc = m.accessors[m.meshes[0].primitives[0].attributes.at(name)];
    const auto& view = m.bufferViews[acc.bufferView];
    const size_t stride = view.byteStride ? view.byteStride : 4 * sizeof(T);
    std::memcpy(m.buffers[view.buffer].data.data() + view.byteOffset + acc.byteOffset + v * stride + c * sizeof(T),
                &value, sizeof(T));
  });
}

fs::path with_weight(float value, size_t v, size_t c) { return with_value("WEIGHTS_0", value, v, c); }

// Attribute \p name of simple_skin made sparse: its element \p index replaced by \p values (T: the component
// type), the index stored as an unsigned short.
template <typename T>
fs::path with_sparse(const char* name, std::vector<T> values, uint32_t index) {
  return edited([&](tinygltf::Model& m) {
    auto& acc = m.accessors[m.meshes[0].primitives[0].attributes.at(name)];
    auto& bytes = m.buffers[0].data;
    auto add_view = [&](const void* data, size_t n) {
      while (bytes.size() % 4) bytes.push_back(0);
      tinygltf::BufferView view;
      view.buffer = 0;
      view.byteOffset = bytes.size();
      view.byteLength = n;
      bytes.insert(bytes.end(), static_cast<const unsigned char*>(data), static_cast<const unsigned char*>(data) + n);
      m.bufferViews.push_back(view);
      return int(m.bufferViews.size()) - 1;
    };
    const uint16_t i16 = uint16_t(index);
    acc.sparse.isSparse = true;
    acc.sparse.count = 1;
    acc.sparse.indices.bufferView = add_view(&i16, sizeof i16);
    acc.sparse.indices.byteOffset = 0;
    acc.sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    acc.sparse.values.bufferView = add_view(values.data(), values.size() * sizeof(T));
    acc.sparse.values.byteOffset = 0;
  });
}

std::string message(const fs::path& f) {
  try {
    check_gltf_values(f.string(), "shown.gltf");
  } catch (const IOError& e) {
    return e.what();
  }
  return "accepted";
}
}  // namespace

TEST(GltfValueCheck, NonFiniteWeightIsAnErrorNamingTheVertex) {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    const auto f = with_weight(bad, 2, 0);
    try {
      check_gltf_values(f.string(), "shown.gltf");
      FAIL() << "accepted a non-finite weight";
    } catch (const IOError& e) {
      EXPECT_STREQ(e.what(), "shown.gltf: vertex 2 of mesh 0 (\"\") has a non-finite weight in WEIGHTS_0");
    }
    SkinnedMesh mesh;
    EXPECT_THROW(import_skinned(f.string(), mesh), IOError);
  }
}

TEST(GltfValueCheck, FiniteWeightsAndOtherFormatsPass) {
  EXPECT_NO_THROW(check_gltf_values(with_weight(0.5f, 2, 0).string(), "x"));
  EXPECT_NO_THROW(check_gltf_values(simple_skin, "x"));
  EXPECT_NO_THROW(check_gltf_values(std::string(OMSK_TEST_MODELS) + "/X/Testwuson.X", "x"));
}

TEST(GltfValueCheck, AWeightedJointOutsideTheSkinIsAnErrorNamingIt) {
  // simple_skin's skin has 2 joints; vertex 4 weighs its second joint by 0.5.
  for (uint16_t bad : {uint16_t(7), uint16_t(60000)}) {
    const auto f = with_value<uint16_t>("JOINTS_0", bad, 4, 1);
    EXPECT_EQ(message(f), "shown.gltf: vertex 4 of mesh 0 (\"\") names joint " + std::to_string(bad) +
                              " in JOINTS_0, but skin 0 (\"\") has 2 joints");
    SkinnedMesh mesh;
    EXPECT_THROW(import_skinned(f.string(), mesh), IOError);
  }
  // Vertex 0 gives its second joint no weight: what that index says does not matter to any reader.
  EXPECT_EQ(message(with_value<uint16_t>("JOINTS_0", 7, 0, 1)), "accepted");
}

TEST(GltfValueCheck, AnAccessorClaimingMoreThanItsViewHoldsIsAnError) {
  // A count of 2^31 once made the weight check read the rest of the buffer and blame "vertex 160".
  const auto f = edited([](tinygltf::Model& m) { m.accessors[3].count = size_t(1) << 31; });
  EXPECT_EQ(message(f),
            "shown.gltf: accessor 3 (WEIGHTS_0 of mesh 0 (\"\")) claims 2147483648 elements of 16 bytes from byte 160, "
            "more than its buffer view's 320 bytes hold");
  SkinnedMesh mesh;
  try {
    import_skinned(f.string(), mesh);
    FAIL() << "accepted";
  } catch (const IOError& e) {
    EXPECT_EQ(std::string(e.what()).find(f.string() + ": accessor 3 (WEIGHTS_0"), 0u) << e.what();
  }
}

TEST(GltfValueCheck, SparseSkinAccessorsAreCheckedAsTheReaderPatchesThem) {
  // A NaN weight or a joint outside the skin in a sparse substitute is refused as in the base data.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto w = with_sparse<float>("WEIGHTS_0", {nan, 0.0f, 0.0f, 0.0f}, 2);
  EXPECT_EQ(message(w), "shown.gltf: vertex 2 of mesh 0 (\"\") has a non-finite weight in WEIGHTS_0");
  SkinnedMesh mesh;
  EXPECT_THROW(import_skinned(w.string(), mesh), IOError);
  // Vertex 4 weighs its second joint by 0.5 in the base data.
  const auto j = with_sparse<uint16_t>("JOINTS_0", {0, 7, 0, 0}, 4);
  EXPECT_EQ(message(j),
            "shown.gltf: vertex 4 of mesh 0 (\"\") names joint 7 in JOINTS_0, but skin 0 (\"\") has 2 joints");
  // Valid substitutes pass.
  EXPECT_EQ(message(with_sparse<float>("WEIGHTS_0", {0.25f, 0.75f, 0.0f, 0.0f}, 2)), "accepted");
  EXPECT_EQ(message(with_sparse<uint16_t>("JOINTS_0", {1, 0, 0, 0}, 4)), "accepted");
}

TEST(GltfValueCheck, ASparseIndexOutsideItsAccessorIsRefusedForPositionsToo) {
  const tinygltf::Model m = omsk_spec::load(simple_skin);
  const int pos = m.meshes[0].primitives[0].attributes.at("POSITION");
  const size_t n = m.accessors[pos].count;
  const auto f = with_sparse<float>("POSITION", {0.0f, 1.0f, 0.0f}, uint32_t(n));
  EXPECT_EQ(message(f), "shown.gltf: accessor " + std::to_string(pos) +
                            " (POSITION of mesh 0 (\"\")) substitutes element " + std::to_string(n) +
                            " (sparse entry 0) of its " + std::to_string(n));
  SkinnedMesh mesh;
  EXPECT_THROW(import_skinned(f.string(), mesh), IOError);
  EXPECT_EQ(message(with_sparse<float>("POSITION", {0.0f, 1.0f, 0.0f}, 0)), "accepted");
  // Substitutes that reach past their buffer view are refused before anything reads them.
  const auto w = with_sparse<float>("WEIGHTS_0", {0.5f, 0.5f}, 2);  // half a VEC4
  EXPECT_NE(message(w).find("claims 1 sparse values of 16 bytes"), std::string::npos) << message(w);
}

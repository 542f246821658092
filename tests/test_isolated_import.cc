// The isolated reader: a reader crash, a runaway allocation or an endless read is an IOError, and a
// good file comes back exactly as the in-process import reads it.
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/IO/ImportArchive.hh>

#include <gtest/gtest.h>

#include <string>

using namespace OpenMeshSkinned;

namespace {
std::string model(const std::string& rel) { return std::string(OMSK_TEST_MODELS) + "/" + rel; }
std::string crasher(int i) {
  return std::string(OMSK_TEST_DATA) + "/crashers/md5_mutant_segv_" + std::to_string(i) + ".md5mesh";
}
ImportOptions isolated() {
  ImportOptions o;
  o.isolate = true;
  return o;
}
std::string error_of(const std::string& path, const ImportOptions& o) {
  SkinnedMesh m;
  try {
    import_skinned(path, m, o);
  } catch (const IOError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(IsolatedImport, GivesTheSameCharacterAsTheInProcessReader) {
  for (const char* rel : {"X/Testwuson.X", "glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf"}) {
    SkinnedMesh a, b;
    const ImportReport ra = import_skinned(model(rel), a);
    const ImportReport rb = import_skinned(model(rel), b, isolated());
    EXPECT_EQ(save_import(b, rb), save_import(a, ra)) << rel;
  }
}

TEST(IsolatedImport, AReaderCrashIsAnErrorNamingFileAndFormat) {
  // Mutants of SimpleCube.md5mesh that make assimp 5.2.5's MD5 reader write out of bounds (SIGSEGV).
  for (int i : {1, 2}) {
    const std::string e = error_of(crasher(i), isolated());
    EXPECT_NE(e.find(crasher(i) + ": the reader crashed (SIG"), std::string::npos) << e;
    EXPECT_NE(e.find("MD5"), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos);
  }
}

TEST(IsolatedImport, TheReadersOwnErrorsComeThroughUnchanged) {
  const std::string missing = error_of("/nonexistent/omsk.glb", isolated());
  EXPECT_EQ(missing, "/nonexistent/omsk.glb: file does not exist");
  const std::string bvh = model("BVH/01_01.bvh");
  EXPECT_EQ(error_of(bvh, isolated()), error_of(bvh, {}));
}

TEST(IsolatedImport, TimeLimit) {
  ImportOptions o = isolated();
  o.time_limit_seconds = 0.001;
  const std::string e = error_of(model("X/Testwuson.X"), o);
  EXPECT_NE(e.find("the reader took longer than"), std::string::npos) << e;
}

#if !defined(__SANITIZE_ADDRESS__)
TEST(IsolatedImport, MemoryLimit) {
  ImportOptions o = isolated();
  o.memory_limit_mb = 1;  // less than the process already maps: the first allocation of the read fails
  const std::string e = error_of(model("X/Testwuson.X"), o);
  EXPECT_NE(e.find("the reader ran out of memory (limit 1 MB)"), std::string::npos) << e;
}
#endif

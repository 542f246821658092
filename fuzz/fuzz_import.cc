// libFuzzer target over the import path: the first byte picks the format (the file extension assimp
// dispatches on), the rest is the file. Runs the in-process importer, so that a crash here is a crash a
// library user without ImportOptions::isolate would see. Build and run with bench/fuzz.sh.
#include <OpenMeshSkinned/IO/Import.hh>

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

namespace {
constexpr const char* kExtensions[] = {".x",   ".md5mesh", ".fbx", ".gltf", ".glb",
                                       ".obj", ".dae",     ".ply", ".smd",  ".b3d"};
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  const size_t n_ext = sizeof kExtensions / sizeof kExtensions[0];
  static const std::string dir = [] {
    char tmpl[] = "/tmp/omsk-fuzz-XXXXXX";
    return std::string(mkdtemp(tmpl));
  }();
  const std::string path = dir + "/input" + kExtensions[data[0] % n_ext];
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data + 1, 1, size - 1, f);
    std::fclose(f);
  } else {
    return 0;
  }
  try {
    OpenMeshSkinned::SkinnedMesh mesh;
    OpenMeshSkinned::import_skinned(path, mesh);
  } catch (const OpenMeshSkinned::IOError&) {
    // A clean refusal is the expected outcome for most inputs.
  }
  return 0;
}

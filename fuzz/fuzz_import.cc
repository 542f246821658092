// libFuzzer target over the import path: the first byte picks the format (the file extension assimp
// dispatches on), the rest is the file. Runs the in-process importer, so that a crash here is a crash a
// library user without ImportOptions::isolate would see. Build and run with bench/fuzz.sh.
#include <OpenMeshSkinned/IO/Import.hh>

#include "FuzzInput.hh"

#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = omsk_fuzz::write_input(data, size);
  if (path.empty()) return 0;
  try {
    OpenMeshSkinned::SkinnedMesh mesh;
    OpenMeshSkinned::import_skinned(path, mesh);
  } catch (const OpenMeshSkinned::IOError&) {
    // A clean refusal is the expected outcome for most inputs.
  }
  return 0;
}

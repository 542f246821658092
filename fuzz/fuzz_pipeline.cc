// libFuzzer target over the whole pipeline on small inputs: import (in process), example poses from the
// first clip, one decimation level with the skinned modules under LazyDecimaterT, export. The first byte
// picks the format as in fuzz_import.cc. What the fuzzer looks for past the reader: a crash, a hang (a
// solve that does not end on a strange number) or an exception other than the documented ones. Build and
// run with bench/fuzz.sh --pipeline.
#include <OpenMeshSkinned/Decimater/LazyDecimaterT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedFoldOverT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModWeightCapT.hh>
#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include "FuzzInput.hh"

#include <cstdint>
#include <stdexcept>
#include <string>

namespace {
// Larger meshes would make each execution slow without reaching new code.
constexpr size_t kMaxFaces = 4000;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using Mesh = OpenMeshSkinned::SkinnedMesh;
  const std::string path = omsk_fuzz::write_input(data, size);
  if (path.empty()) return 0;
  Mesh mesh;
  try {
    OpenMeshSkinned::import_skinned(path, mesh);
  } catch (const OpenMeshSkinned::IOError&) {
    return 0;  // a clean refusal is the expected outcome for most inputs
  }
  if (mesh.n_faces() > kMaxFaces) return 0;
  const auto& clips = OpenMeshSkinned::clips(mesh);
  if (!clips.empty())
    OpenMeshSkinned::example_poses(mesh) =
        OpenMeshSkinned::sample_poses_evenly(OpenMeshSkinned::skeleton(mesh), clips[0], 3);
  else
    OpenMeshSkinned::use_bind_pose_only(mesh);
  try {
    OpenMeshSkinned::LazyDecimaterT<Mesh> decimater(mesh);
    OpenMeshSkinned::ModSkinnedQuadricT<Mesh>::Handle quadric;
    OpenMeshSkinned::ModWeightCapT<Mesh>::Handle cap;
    OpenMeshSkinned::ModSkinnedFoldOverT<Mesh>::Handle fold;
    decimater.add(quadric);
    decimater.add(cap);
    decimater.add(fold);
    decimater.module(cap).set_max_influences(4);
    decimater.set_threads(1);
    if (!decimater.initialize()) return 0;
    decimater.decimate_to_faces(0, mesh.n_faces() / 2);
    mesh.garbage_collection();
  } catch (const std::length_error&) {
    return 0;  // a skeleton beyond what the solver handles: refused, as documented
  } catch (const std::invalid_argument&) {
    return 0;  // example poses that overflow (huge keys composed down a chain): refused, as documented
  }
  try {
    OpenMeshSkinned::export_gltf(mesh, omsk_fuzz::scratch_dir() + "/out.glb");
  } catch (const OpenMeshSkinned::IOError&) {
  }
  return 0;
}

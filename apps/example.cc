// The drop-in example: read a skinned character, add the OpenMeshSkinned modules to OpenMesh's standard
// DecimaterT, decimate, write glTF. Copy this into your own tool.
//
//   omsk-example [INPUT [OUTPUT.glb [RATIO [POSES]]]]
//
// Without INPUT it builds DeCoro's bending leg (a tapered cylinder, knee bent 0..90 degrees) and writes
// omsk-example-out/leg.glb.
#include <OpenMeshSkinned/Decimater/ModSkinnedFoldOverT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModWeightCapT.hh>
#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <string>

using Mesh = OpenMeshSkinned::SkinnedMesh;

int main(int argc, char** argv) {
  try {
    // Arguments first, so that a typo fails at once and before any output exists.
    const std::string out = argc > 2 ? argv[2] : argc > 1 ? "out.glb" : "omsk-example-out/leg.glb";
    const double ratio = argc > 3 ? std::stod(argv[3]) : 0.1;
    const int n_poses = argc > 4 ? std::stoi(argv[4]) : 8;
    if (!(ratio > 0.0 && ratio <= 1.0)) throw std::runtime_error("RATIO must be in (0, 1]");
    if (n_poses < 1) throw std::runtime_error("POSES must be at least 1");
    const std::string ext = std::filesystem::path(out).extension().string();
    if (ext != ".glb" && ext != ".gltf") throw std::runtime_error(out + ": output must end in .glb or .gltf");

    Mesh mesh;
    if (argc > 1) {
      const auto report = OpenMeshSkinned::import_skinned(argv[1], mesh);
      for (const auto& w : report.warnings) std::cerr << argv[1] << ": warning: " << w << "\n";
    } else {
      std::cout << "No input given: generating DeCoro's bending leg (2 bones, knee 0..90 degrees).\n";
      mesh = OpenMeshSkinned::make_bending_cylinder();
      std::filesystem::create_directories("omsk-example-out");
    }

    // Example poses: evenly spaced over the first clip (the generated leg brings its own: 0 and 90 degrees).
    auto& clips = OpenMeshSkinned::clips(mesh);
    if (argc > 1 && !clips.empty())
      OpenMeshSkinned::example_poses(mesh) =
          OpenMeshSkinned::sample_poses_evenly(OpenMeshSkinned::skeleton(mesh), clips[0], n_poses);

    // The three modules, added to a plain OpenMesh decimater like any of OpenMesh's own.
    OpenMesh::Decimater::DecimaterT<Mesh> decimater(mesh);
    OpenMeshSkinned::ModSkinnedQuadricT<Mesh>::Handle quadric;
    OpenMeshSkinned::ModWeightCapT<Mesh>::Handle cap;
    OpenMeshSkinned::ModSkinnedFoldOverT<Mesh>::Handle fold;
    decimater.add(quadric);
    decimater.add(cap);
    decimater.add(fold);
    decimater.module(cap).set_max_influences(4);
    decimater.module(fold).set_max_angle(90.0);
    if (!decimater.initialize()) throw std::runtime_error("decimater did not initialize");

    const size_t faces_before = mesh.n_faces();
    const size_t target = std::max<size_t>(4, static_cast<size_t>(ratio * faces_before));
    const auto t0 = std::chrono::steady_clock::now();
    decimater.decimate_to_faces(0, target);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    mesh.garbage_collection();

    const auto& stats = decimater.module(quadric).solver().stats();
    std::cout << "faces " << faces_before << " -> " << mesh.n_faces() << " in " << secs << " s, "
              << OpenMeshSkinned::example_poses(mesh).size() << " example poses; edge solves " << stats.solves
              << ", cache hits " << stats.cache_hits << ", Ceres calls " << stats.weights.ceres_calls << "\n";

    OpenMeshSkinned::export_gltf(mesh, out);
    std::cout << "wrote " << out << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "omsk-example: " << e.what() << "\n";
    return 1;
  }
}

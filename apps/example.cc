// The drop-in example: read a skinned character, add the OpenMeshSkinned modules to a decimater, decimate,
// write glTF. Copy this into your own tool.
//
//   omsk-example [INPUT [OUTPUT.glb [RATIO [POSES]]]]
//
// Without INPUT it builds DeCoro's bending leg (a tapered cylinder, knee bent 0..90 degrees) and writes
// omsk-example-out/leg.glb.
//
// The driver is LazyDecimaterT, the one the tool uses: it has DecimaterT's interface and takes OpenMesh's own
// modules too. OpenMesh's DecimaterT works with the same three modules (swap the type below); it is slower,
// and between two decimate calls it needs decimater.module(fold).release_deferred().
#include <OpenMeshSkinned/Decimater/LazyDecimaterT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedFoldOverT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModWeightCapT.hh>
#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/Lod/LodAreaExponent.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Mesh/SurfaceArea.hh>

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

    // The example poses are what every collapse is judged in: evenly spaced over the first clip (the
    // generated leg brings its own, 0 and 90 degrees). A character without a clip can only be judged in its
    // rest pose, and that has to be asked for: the modules refuse a mesh without example poses.
    auto& clips = OpenMeshSkinned::clips(mesh);
    if (argc > 1 && !clips.empty())
      OpenMeshSkinned::example_poses(mesh) =
          OpenMeshSkinned::sample_poses_evenly(OpenMeshSkinned::skeleton(mesh), clips[0], n_poses);
    else if (argc > 1) {
      std::cout << argv[1] << " has no animation: decimating in the rest pose alone.\n";
      OpenMeshSkinned::use_bind_pose_only(mesh);
    }

    // The three modules, added like any of OpenMesh's own.
    OpenMeshSkinned::LazyDecimaterT<Mesh> decimater(mesh);
    OpenMeshSkinned::ModSkinnedQuadricT<Mesh>::Handle quadric;
    OpenMeshSkinned::ModWeightCapT<Mesh>::Handle cap;
    OpenMeshSkinned::ModSkinnedFoldOverT<Mesh>::Handle fold;
    decimater.add(quadric);
    decimater.add(cap);
    decimater.add(fold);
    const size_t faces_before = mesh.n_faces();
    const size_t target = std::max<size_t>(4, static_cast<size_t>(ratio * faces_before));
    // The tool's pricing: the energy over the square root of the area it stands for on small meshes (per area
    // on large ones), and per area below two of the target's mean triangles, where a sharp feature the LOD
    // could still show would otherwise be cheap.
    decimater.module(quadric).set_area_exponent(OpenMeshSkinned::lod_area_exponent({}, mesh.n_vertices()));
    decimater.module(quadric).set_area_floor(2.0 * OpenMeshSkinned::surface_area(mesh) / double(target));
    decimater.module(cap).set_max_influences(4);
    decimater.module(fold).set_max_angle(90.0);
    if (!decimater.initialize()) throw std::runtime_error("decimater did not initialize");

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

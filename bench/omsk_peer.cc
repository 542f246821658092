// omsk-peer: held-out error of simplified characters against their original, whichever tool made them,
// with every file posed by the glTF specification itself (tests/support/gltf_spec: tinygltf, no code shared
// with the library's import or skinning), so ours and gltfpack's outputs are judged the same way.
//
//   omsk-peer ORIGINAL.glb CANDIDATE.glb [CANDIDATE.glb ...] [--frames K]
//
// Frames: K per animation of the original at (i + 0.5) / K of its length, i = 0..K-1 (the tool's own
// example poses are K' evenly spaced times over all clips end to end, both ends included; gltfpack sees
// no pose). A candidate's animation is matched by name (by position for unnamed ones). Error: Metro-style RMS and
// Hausdorff distance (OpenMeshSkinned::surface_distance), in % of the original's rest bounding-box diagonal. One JSON
// line per candidate.
#include "gltf_spec.hh"

#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>

namespace {

OpenMeshSkinned::TriangleSoup soup(const omsk_spec::Soup& s) {
  OpenMeshSkinned::TriangleSoup t;
  t.points = s.points;
  t.triangles = s.triangles;
  return t;
}

int animation_named(const tinygltf::Model& m, const std::string& name) {
  for (size_t a = 0; a < m.animations.size(); ++a)
    if (m.animations[a].name == name) return static_cast<int>(a);
  return -1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"omsk-peer: held-out error of simplified characters, posed by the glTF spec"};
  std::string original_path;
  std::vector<std::string> candidates;
  int frames = 8;
  app.add_option("original", original_path, "The character as given to both tools (.glb/.gltf)")->required();
  app.add_option("candidates", candidates, "Simplified versions of it")->required();
  app.add_option("--frames", frames, "Held-out frames per animation (default 8)");
  CLI11_PARSE(app, argc, argv);
  try {
    const tinygltf::Model original = omsk_spec::load(original_path);
    const omsk_spec::Soup rest = omsk_spec::pose(original, -1, 0.0);
    const double diag = omsk_spec::diagonal(rest);
    struct Frame {
      int anim;
      double time;
    };
    std::vector<Frame> held;
    for (size_t a = 0; a < original.animations.size(); ++a)
      for (int i = 0; i < frames; ++i)
        held.push_back({static_cast<int>(a), omsk_spec::duration(original, int(a)) * (i + 0.5) / frames});
    if (held.empty()) held.push_back({-1, 0.0});
    // The posed original, measured once per frame for every candidate.
    std::vector<OpenMeshSkinned::MeasuredSurface> posed;
    for (const Frame& f : held) posed.emplace_back(soup(omsk_spec::pose(original, f.anim, f.time)), 20000, 1);
    for (const std::string& path : candidates) {
      const tinygltf::Model cand = omsk_spec::load(path);
      double rms = 0.0, haus = 0.0;
      size_t triangles = omsk_spec::pose(cand, -1, 0.0).triangles.size();
      for (size_t i = 0; i < held.size(); ++i) {
        int anim = held[i].anim < 0 ? -1 : animation_named(cand, original.animations[held[i].anim].name);
        // Unnamed animations get a name on the way through a tool: match them by position then.
        if (anim < 0 && held[i].anim >= 0 && original.animations[held[i].anim].name.empty() &&
            cand.animations.size() == original.animations.size())
          anim = held[i].anim;
        if (held[i].anim >= 0 && anim < 0)
          throw std::runtime_error(path + ": has no animation named \"" + original.animations[held[i].anim].name +
                                   "\"");
        const OpenMeshSkinned::MeasuredSurface c(soup(omsk_spec::pose(cand, anim, held[i].time)), 20000, 2);
        const auto d = OpenMeshSkinned::surface_distance(posed[i], c);
        rms += d.rms;
        haus = std::max(haus, d.hausdorff);
      }
      nlohmann::ordered_json j = {{"original", original_path},
                                  {"candidate", path},
                                  {"triangles", triangles},
                                  {"frames", held.size()},
                                  {"heldout_rms", 100.0 * rms / held.size() / diag},
                                  {"heldout_hausdorff", 100.0 * haus / diag}};
      std::cout << j.dump() << std::endl;
    }
  } catch (const std::exception& e) {
    std::cerr << "omsk-peer: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

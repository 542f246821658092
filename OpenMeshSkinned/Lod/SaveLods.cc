#include "SaveLods.hh"

#include <OpenMeshSkinned/IO/ExportGltf.hh>
#include <OpenMeshSkinned/IO/OutputSet.hh>

#include <filesystem>

namespace OpenMeshSkinned {

std::string lod_file_path(const std::string& output, size_t i, size_t n) {
  if (n == 1) return output;
  const std::filesystem::path p(output);
  return (p.parent_path() / (p.stem().string() + "_lod" + std::to_string(i + 1) + p.extension().string())).string();
}

GltfNodeExtras lod_node_extras(const LodReport& r) {
  GltfNodeExtras e = {{"lod_ratio", r.ratio}};
  if (!r.evaluated) return e;
  e.push_back({"lod_heldout_rms_percent", r.rms});
  e.push_back({"lod_heldout_hausdorff_percent", r.hausdorff});
  e.push_back({"lod_unity_relative_screen_height", r.switch_hint.unity_relative_height});
  e.push_back({"lod_unreal_screen_size", r.switch_hint.unreal_screen_size});
  e.push_back({"lod_hint_screen_height_px", double(kSwitchHintScreenHeight)});
  return e;
}

std::vector<std::string> save_lods(const LodChain& chain, const std::string& output,
                                   const std::vector<std::string>& inputs) {
  const std::string ext = std::filesystem::path(output).extension().string();
  if (ext != ".glb" && ext != ".gltf") throw IOError(output + ": output must end in .glb or .gltf");
  if (chain.levels.empty()) throw IOError(output + ": the chain has no level to write");
  OutputSet outputs(inputs);
  std::vector<std::string> paths;
  for (size_t i = 0; i < chain.levels.size(); ++i) paths.push_back(lod_file_path(output, i, chain.levels.size()));
  for (const auto& p : paths) outputs.add(p);
  for (size_t i = 0; i < paths.size(); ++i)
    export_gltf(chain.levels[i].mesh, outputs.staging(paths[i]), lod_node_extras(chain.levels[i].report));
  outputs.commit();
  return paths;
}

}  // namespace OpenMeshSkinned

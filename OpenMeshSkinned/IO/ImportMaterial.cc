#include "OpenMeshSkinned/IO/ImportMaterial.hh"

#include "OpenMeshSkinned/IO/AssimpMaterial.hh"
#include "OpenMeshSkinned/IO/GltfMaterials.hh"
#include "OpenMeshSkinned/IO/IOError.hh"

#include <assimp/material.h>
#include <assimp/scene.h>

#include <new>

namespace OpenMeshSkinned {

std::vector<Material> read_materials(const aiScene* scene, const std::string& source, const std::string& read_path,
                                     std::vector<std::string>& warnings) {
  std::vector<Material> file, out;
  std::vector<int> order;
  bool from_file = false;
  try {
    from_file = read_gltf_materials(read_path, source, file, order, warnings);
  } catch (const IOError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {  // a field of the wrong type in the file's JSON
    warnings.push_back(std::string("the file's materials could not be read (") + e.what() +
                       "): kept as the reader reports them");
    file.clear();
    order.clear();
  }
  if (from_file) {
    // assimp numbers the materials it read in its own order and appends a default material for primitives
    // without one (glTF's default material is the empty one). Its names must agree with the file's.
    bool agree = order.size() <= scene->mNumMaterials && scene->mNumMaterials <= order.size() + 1;
    for (unsigned m = 0; m < scene->mNumMaterials && agree; ++m) {
      aiString name;
      const std::string reader =
          scene->mMaterials[m]->Get(AI_MATKEY_NAME, name) == AI_SUCCESS ? name.C_Str() : std::string();
      if (m < order.size()) {
        out.push_back(file[size_t(order[m])]);
        agree = out.back().name.empty() || out.back().name == reader;
      } else {
        Material d;
        d.name = reader;
        d.gltf = "{}";
        out.push_back(std::move(d));
      }
    }
    if (agree) return out;
    warnings.push_back("the file's materials could not be matched to the reader's: kept as the reader reports them");
    out.clear();
  }
  for (unsigned m = 0; m < scene->mNumMaterials; ++m)
    out.push_back(read_material(scene, scene->mMaterials[m], source, warnings));
  return out;
}

}  // namespace OpenMeshSkinned

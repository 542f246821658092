#pragma once
/** \file ImportGeometry.hh
 *  The import step that turns assimp meshes into one OpenMesh mesh: each instance in its bind space,
 *  skin weights read and checked, split copies welded, faces with per-corner normals, UV sets and colours
 *  (CornerAttributes.hh).
 *  Internal to the importer (Import.cc).
 */

#include "OpenMeshSkinned/IO/ImportOptions.hh"
#include "OpenMeshSkinned/IO/ImportScene.hh"
#include "OpenMeshSkinned/Mesh/CornerAttributes.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"
#include "OpenMeshSkinned/Skin/SkinnedMesh.hh"

#include <memory>

namespace OpenMeshSkinned::detail {

/// Everything one import's instances share: the target mesh, its handles, and the welding table.
class GeometryBuilder {
public:
  GeometryBuilder(SkinnedMesh& mesh, size_t n_targets, const ImportOptions& opt, ImportReport& rep,
                  const std::string& path);
  ~GeometryBuilder();

  /// Room in the welding table for \p vertices file vertices (all instances'): no rehash while adding.
  void reserve(size_t vertices);
  /// Adds instance \p in, whose morph targets start at \p target_base.
  void add(const aiScene* scene, const SceneNodes& sn, JointMap& joints, const MeshInstance& in, size_t target_base);

private:
  Eigen::Matrix4d bind_space(const aiMesh* am, const SceneNodes& sn, const JointMap& joints, int node) const;
  std::vector<Influences> read_weights(const aiMesh* am, JointMap& joints, const Eigen::Matrix4d& B_inv,
                                       int node_joint);
  void add_faces(const aiMesh* am, const std::vector<SkinnedMesh::VertexHandle>& vmap,
                 const Eigen::Matrix3d& normal_matrix);
  OpenMesh::Vec4f corner_value(const aiMesh* am, const CornerChannel& ch, unsigned src);
  void note_dropped(const aiMesh* am);
  void warn(int& slot, const std::string& text);

  struct Weld;
  SkinnedMesh& mesh_;
  size_t n_targets_;
  const ImportOptions& opt_;
  ImportReport& rep_;
  std::string path_;
  OpenMesh::VPropHandleT<Influences> h_inf_;
  OpenMesh::FPropHandleT<int> h_fmat_;
  OpenMesh::VPropHandleT<MorphDeltas> h_delta_;
  std::unique_ptr<Weld> weld_;
  // What is not kept, one warning line each (rewritten as later meshes add to it): its index in rep_.warnings.
  int tangent_warning_ = -1, target_warning_ = -1, clamp_warning_ = -1, uvw_warning_ = -1;
  size_t clamped_colours_ = 0;
};

}  // namespace OpenMeshSkinned::detail

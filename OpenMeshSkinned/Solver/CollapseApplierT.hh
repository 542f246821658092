#pragma once
/** \file CollapseApplierT.hh
 *  What a collapse does to the surviving vertex v1 besides OpenMesh's halfedge collapse: its place and skin
 *  (the solver's answer), its per-pose quadrics and posed positions, the normals of its faces, its corners'
 *  UVs and colours (CornerTransferT) and its morph offsets (MorphTransferT), and the answers made stale.
 *
 *  Usage, around each collapse: record() before, apply() after.
 */

#include "OpenMeshSkinned/Collapse/CornerTransferT.hh"
#include "OpenMeshSkinned/Collapse/MorphTransferT.hh"
#include "OpenMeshSkinned/Solver/EdgeAnswersT.hh"
#include "OpenMeshSkinned/Solver/PoseCacheT.hh"

#include <OpenMesh/Tools/Decimater/CollapseInfoT.hh>

#include <cstddef>

namespace OpenMeshSkinned {

template <typename Mesh>
class CollapseApplierT {
public:
  using VertexHandle = typename Mesh::VertexHandle;
  using CollapseInfo = OpenMesh::Decimater::CollapseInfoT<Mesh>;

  CollapseApplierT(Mesh& mesh, PoseCacheT<Mesh>& poses, EdgeAnswersT<Mesh>& answers)
      : mesh_(mesh), poses_(poses), answers_(answers), corners_(mesh), morph_(mesh) {}

  void prepare() { corners_.prepare(); }

  /// Before the collapse of \p ci: what v1's corners and morph offsets will be interpolated from.
  void record(const CollapseInfo& ci) {
    corners_.record(ci.v0, ci.v1);
    morph_.record(ci.v0, ci.v1);
  }

  /** After the collapse of \p ci: v1 stands for v0's faces too, and goes where \p placed says (null: it
   *  stays, and a skin over the cap is reduced by the weight solve). */
  void apply(const CollapseInfo& ci, const CollapseResult* placed) {
    const VertexHandle v0 = ci.v0, v1 = ci.v1;
    answers_.will_change(v1);
    poses_.merge_quadrics(v0, v1);
    if (placed) {
      const Eigen::Vector3d& p = placed->position;
      mesh_.set_point(v1, typename Mesh::Point(p.x(), p.y(), p.z()));
      mesh_.property(poses_.influences(), v1) = placed->weights;
      poses_.update(v1);
      if (mesh_.has_face_normals())
        for (auto fh : mesh_.vf_range(v1)) mesh_.set_normal(fh, mesh_.calc_face_normal(fh));
    } else if (mesh_.property(poses_.influences(), v1).size() > answers_.settings().max_influences) {
      reduce_vertex(v1);
    }
    // Moved or not, v1's corners that came from v0 carry v0's UVs and colours: re-interpolate all of them.
    corners_.apply(v1);
    morph_.apply(v1);
    answers_.collapsed(v0, v1);
  }

  /** Reduces every vertex with more than the cap's bones by the weight solve on its own quadrics at its own
   *  position (not by plain truncation). Returns how many vertices changed. */
  size_t reduce_input_influences() {
    size_t changed = 0;
    for (auto vh : mesh_.vertices())
      if (mesh_.property(poses_.influences(), vh).size() > answers_.settings().max_influences) {
        reduce_vertex(vh);
        ++changed;
      }
    return changed;
  }

private:
  void reduce_vertex(VertexHandle vh) {
    mesh_.property(poses_.influences(), vh) = answers_.reduced_skin(vh);
    poses_.update(vh);
    answers_.vertex_changed(vh);
  }

  Mesh& mesh_;
  PoseCacheT<Mesh>& poses_;
  EdgeAnswersT<Mesh>& answers_;
  CornerTransferT<Mesh> corners_;
  MorphTransferT<Mesh> morph_;
};

}  // namespace OpenMeshSkinned

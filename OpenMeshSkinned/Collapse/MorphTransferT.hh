#pragma once
/** \file MorphTransferT.hh
 *  Morph offsets of a vertex that a collapse moved. The surviving vertex's offsets are interpolated at its
 *  new position in the faces around the collapse as they were before it (closest point of the closest
 *  face, barycentric), as its UVs are: a vertex that lands between two old ones morphs like the surface
 *  it replaces, not like whichever endpoint it was.
 *
 *  Usage, around each collapse: record() before, apply() after. Does nothing on a mesh without morph
 *  targets, so it costs nothing there.
 */

#include "OpenMeshSkinned/Mesh/ClosestPoint.hh"
#include "OpenMeshSkinned/Skin/LinearBlendSkinning.hh"
#include "OpenMeshSkinned/Skin/Morph.hh"

#include <vector>

namespace OpenMeshSkinned {

template <typename Mesh>
class MorphTransferT {
public:
  using VertexHandle = typename Mesh::VertexHandle;

  explicit MorphTransferT(Mesh& mesh) : mesh_(mesh) { active_ = morph_deltas_handle(mesh_, h_); }

  bool active() const { return active_; }

  /// Remembers the faces around \p v0 and \p v1 with their vertices' positions and offsets.
  void record(VertexHandle v0, VertexHandle v1) {
    faces_.clear();
    if (!active_) return;
    for (const VertexHandle c : {v0, v1})
      for (auto fh : mesh_.vf_range(c)) {
        Source s;
        int k = 0;
        for (auto vh : mesh_.fv_range(fh)) {
          s.p[k] = to_eigen(mesh_.point(vh));
          s.d[k] = &mesh_.property(h_, vh);
          ++k;
        }
        faces_.push_back(s);
      }
  }

  /// Sets \p v1's offsets from the recorded faces at its current position. Call after the collapse.
  void apply(VertexHandle v1) {
    if (!active_ || faces_.empty()) return;
    const Eigen::Vector3d p = to_eigen(mesh_.point(v1));
    double best = HUGE_VAL;
    const Source* at = nullptr;
    Eigen::Vector3d bary, b;
    for (const Source& s : faces_) {
      const double d = closest_barycentric(s.p, p, b);
      if (d < best) best = d, at = &s, bary = b;
    }
    result_.assign(at->d[0]->size(), Eigen::Vector3f::Zero());
    for (int k = 0; k < 3; ++k)
      for (size_t t = 0; t < result_.size() && t < at->d[k]->size(); ++t)
        result_[t] += static_cast<float>(bary[k]) * (*at->d[k])[t];
    mesh_.property(h_, v1) = result_;
  }

private:
  // Offsets are read through pointers: the collapse deletes v0 but keeps its property storage, and
  // nothing writes v1's offsets before apply() has read them into result_.
  struct Source {
    Eigen::Vector3d p[3];
    const MorphDeltas* d[3];
  };
  Mesh& mesh_;
  OpenMesh::VPropHandleT<MorphDeltas> h_;
  bool active_ = false;
  std::vector<Source> faces_;
  MorphDeltas result_;
};

}  // namespace OpenMeshSkinned

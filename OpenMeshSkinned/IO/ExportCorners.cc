#include "OpenMeshSkinned/IO/ExportCorners.hh"

#include "OpenMeshSkinned/IO/ExportParts.hh"
#include "OpenMeshSkinned/Skin/SkinProperties.hh"

#include <algorithm>

namespace OpenMeshSkinned::detail {

std::vector<Written> written_sets(const SkinnedMesh& mesh, int first_uv) {
  std::vector<Written> out;
  int n_uv = first_uv, n_color = 0;
  for (const CornerChannel& c : corner_channels(mesh)) {
    if (c.kind == CornerKind::TexCoord) {
      out.push_back({c, "TEXCOORD_" + std::to_string(n_uv++), 2});
      continue;
    }
    bool alpha = false;
    for (auto heh : mesh.halfedges())
      if (!mesh.is_boundary(heh) && mesh.property(c.handle, heh)[3] != 1.0f) alpha = true;
    out.push_back({c, "COLOR_" + std::to_string(n_color++), alpha ? 4 : 3});
  }
  return out;
}

void append_set(const Written& w, OpenMesh::Vec4f x, std::vector<float>& out) {
  for (int k = 0; k < 4; ++k)
    if (!std::isfinite(x[k])) x = w.channel.fallback();
  if (w.channel.kind == CornerKind::TexCoord) {
    out.insert(out.end(), {x[0], 1.0f - x[1]});
    return;
  }
  for (int k = 0; k < w.components; ++k) out.push_back(std::clamp(x[k], 0.0f, 1.0f));
}

void float_weights(const Influences& inf, int slots, std::vector<uint16_t>& joints, std::vector<float>& weights) {
  std::vector<float> w(slots, 0.0f);
  std::vector<uint16_t> j(slots, 0);
  float s = 0.0f;
  for (int i = 0; i < inf.size() && i < slots; ++i) {
    j[i] = static_cast<uint16_t>(inf[i].joint);
    w[i] = static_cast<float>(inf[i].weight);
    s += w[i];
  }
  if (s > 0.0f)
    for (float& x : w) x /= s;
  float rest = 1.0f;
  for (int i = 1; i < slots; ++i) rest -= w[i];
  w[0] = rest;  // the heaviest slot absorbs the rounding
  joints.insert(joints.end(), j.begin(), j.end());
  weights.insert(weights.end(), w.begin(), w.end());
}

std::vector<TangentCorner> tangent_corners(const SkinnedMesh& mesh,
                                           const std::vector<SkinnedMesh::HalfedgeHandle>& hehs,
                                           const std::vector<Eigen::Vector3d>& normals, int set) {
  CornerChannel channel{CornerKind::TexCoord, set, OpenMesh::HPropHandleT<OpenMesh::Vec4f>()};
  if (set > 0) mesh.get_property_handle(channel.handle, corner_property_name(CornerKind::TexCoord, set));
  std::vector<TangentCorner> out;
  for (size_t k = 0; k < hehs.size(); ++k) {
    const auto vh = mesh.to_vertex_handle(hehs[k]);
    const auto p = mesh.point(vh);
    Eigen::Vector2d uv(0, 0);
    if (set == 0) {
      const auto t = mesh.texcoord2D(hehs[k]);
      if (std::isfinite(t[0]) && std::isfinite(t[1])) uv = Eigen::Vector2d(t[0], t[1]);
    } else {
      const auto t = mesh.property(channel.handle, hehs[k]);
      if (std::isfinite(t[0]) && std::isfinite(t[1])) uv = Eigen::Vector2d(t[0], t[1]);
    }
    // The normal as written (in float), so that corners written as one vertex share one tangent.
    const Eigen::Vector3d n = normals[k].cast<float>().cast<double>();
    out.push_back({vh.idx(), Eigen::Vector3d(p[0], p[1], p[2]), n, uv});
  }
  return out;
}

bool writes_first_uv_set(const SkinnedMesh& mesh) {
  if (!mesh.has_halfedge_texcoords2D()) return false;
  // TEXCOORD_1 needs a TEXCOORD_0, zero or not, and so does a textured material (a file whose textures
  // have no UVs to read would otherwise become one the validator refuses).
  for (const CornerChannel& c : corner_channels(mesh))
    if (c.kind == CornerKind::TexCoord) return true;
  for (const Material& m : materials(mesh))
    if (!m.textures.empty()) return true;
  for (auto heh : mesh.halfedges()) {
    if (mesh.is_boundary(heh)) continue;  // no face, no corner: its UV is never set
    const auto t = mesh.texcoord2D(heh);
    if (std::isfinite(t[0]) && std::isfinite(t[1]) && t != SkinnedMesh::TexCoord2D(0, 0)) return true;
  }
  return false;
}

std::vector<int> written_uv_sets(const SkinnedMesh& mesh) {
  std::vector<int> out(kMaxTexCoordSets, -1);
  int next = 0;
  if (writes_first_uv_set(mesh)) out[0] = next++;
  for (const CornerChannel& c : corner_channels(mesh))
    if (c.kind == CornerKind::TexCoord) out[c.set] = next++;
  return out;
}

int written_uv_index(const std::vector<int>& written, int set) {
  return set >= 0 && size_t(set) < written.size() && written[set] >= 0 ? written[set] : 0;
}

}  // namespace OpenMeshSkinned::detail

#pragma once
// Shared test helpers: real characters, invariant checks, and a flip-watching module.

#include <OpenMeshSkinned/IO/Import.hh>
#include <OpenMeshSkinned/Mesh/Procedural.hh>
#include <OpenMeshSkinned/Skin/LinearBlendSkinning.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <OpenMesh/Tools/Decimater/ModBaseT.hh>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace omsk_test {

using Mesh = OpenMeshSkinned::SkinnedMesh;

inline std::string model(const std::string& rel) { return std::string(OMSK_TEST_MODELS) + "/" + rel; }

/// A real character with K example poses from its first clip (the bind pose alone when it has none).
inline Mesh load_character(const std::string& rel, int poses = 8) {
  Mesh mesh;
  OpenMeshSkinned::import_skinned(model(rel), mesh);
  auto& clips = OpenMeshSkinned::clips(mesh);
  if (!clips.empty())
    OpenMeshSkinned::example_poses(mesh) =
        OpenMeshSkinned::sample_poses_evenly(OpenMeshSkinned::skeleton(mesh), clips[0], poses);
  else
    OpenMeshSkinned::use_bind_pose_only(mesh);
  return mesh;
}

/** A 3x3 vertex grid over [0,2]^2 in z = 0 with UV = position / 2 and corner normals +z, except that the right
 *  column of faces is a separate chart whose UVs are shifted by (+10, 0): the edges on x = 1 are a UV seam.
 *  Border halfedges (no face) keep whatever OpenMesh left in them. */
inline Mesh grid_with_uv_seam() {
  Mesh mesh;
  OpenMeshSkinned::request_skinned_attributes(mesh);
  std::vector<Mesh::VertexHandle> v;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) v.push_back(mesh.add_vertex(Mesh::Point(k, i, 0)));
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 2; ++k) {
      const auto a = v[i * 3 + k], b = v[i * 3 + k + 1], c = v[(i + 1) * 3 + k], d = v[(i + 1) * 3 + k + 1];
      for (auto fh : {mesh.add_face(a, b, d), mesh.add_face(a, d, c)})
        for (auto h : mesh.fh_range(fh)) {
          const auto p = mesh.point(mesh.to_vertex_handle(h));
          mesh.set_texcoord2D(h, Mesh::TexCoord2D(p[0] / 2 + (k == 1 ? 10 : 0), p[1] / 2));
          mesh.set_normal(h, Mesh::Normal(0, 0, 1));
        }
    }
  return mesh;
}

/// Most influences any vertex carries.
template <typename M>
int max_influences(const M& mesh) {
  const auto h = OpenMeshSkinned::influences_handle(mesh);
  int n = 0;
  for (auto vh : mesh.vertices()) n = std::max(n, mesh.property(h, vh).size());
  return n;
}

/// A six-bone tube whose joints blend over wide zones, so vertices carry up to six influences.
inline Mesh many_influence_tube(int around, int along) {
  OpenMeshSkinned::TubeOptions opt;
  opt.around = around;
  opt.along = along;
  opt.bones = 6;
  opt.blend = 0.3;
  return OpenMeshSkinned::make_skinned_tube(opt, 60.0);
}

/// Weights >= 0, sum 1 within 1e-6, at most \p cap influences, joints in range; manifold vertices.
template <typename M>
void expect_valid_skin(const M& mesh, int cap) {
  const auto h = OpenMeshSkinned::influences_handle(mesh);
  const int nj = OpenMeshSkinned::skeleton(mesh).size();
  int bad = 0;
  for (auto vh : mesh.vertices()) {
    const auto& inf = mesh.property(h, vh);
    bool ok = !inf.empty() && inf.size() <= cap && std::abs(inf.sum() - 1.0) <= 1e-6 && mesh.is_manifold(vh);
    for (const auto& jw : inf) ok = ok && jw.weight >= 0.0 && jw.joint >= 0 && jw.joint < nj;
    if (!ok && bad++ < 5) ADD_FAILURE() << "vertex " << vh.idx() << " has an invalid skin or is not manifold";
  }
  EXPECT_EQ(bad, 0);
}

/** Binary module that refuses nothing and records, for every collapse, whether any surviving face around it
 *  turned by more than max_angle in any example pose. Add it after the modules under test. */
template <typename M>
class FlipWatcherT : public OpenMesh::Decimater::ModBaseT<M> {
public:
  DECIMATING_MODULE(FlipWatcherT, M, FlipWatcher);
  explicit FlipWatcherT(M& mesh) : Base(mesh, true) {}

  double max_angle_deg = 90.0;
  size_t collapses = 0;
  size_t flipped = 0;

  void preprocess_collapse(const CollapseInfo& ci) override {
    faces_.clear();
    before_.clear();
    for (auto c : {ci.v0, ci.v1})
      for (auto fh : Base::mesh().vf_range(c)) {
        bool removed = false;
        for (auto v : Base::mesh().fv_range(fh)) removed |= (v == (c == ci.v0 ? ci.v1 : ci.v0));
        if (!removed && std::find(faces_.begin(), faces_.end(), fh) == faces_.end()) faces_.push_back(fh);
      }
    before_ = normals();
  }
  void postprocess_collapse(const CollapseInfo&) override {
    ++collapses;
    const auto after = normals();
    const double min_cos = std::cos(max_angle_deg * M_PI / 180.0) - 1e-9;
    for (size_t i = 0; i < after.size(); ++i)
      if (before_[i].norm() > 0 &&
          (after[i].norm() == 0 || after[i].normalized().dot(before_[i].normalized()) < min_cos)) {
        ++flipped;
        break;
      }
  }

private:
  std::vector<Eigen::Vector3d> normals() {
    const auto& m = Base::mesh();
    const auto h = OpenMeshSkinned::influences_handle(m);
    std::vector<Eigen::Vector3d> out;
    for (const auto& pose : OpenMeshSkinned::example_poses(m))
      for (auto fh : faces_) {
        Eigen::Vector3d p[3];
        int k = 0;
        for (auto v : m.fv_range(fh))
          p[k++] = OpenMeshSkinned::skin_point(OpenMeshSkinned::to_eigen(m.point(v)), m.property(h, v), pose);
        out.push_back((p[1] - p[0]).cross(p[2] - p[0]));
      }
    return out;
  }
  std::vector<typename M::FaceHandle> faces_;
  std::vector<Eigen::Vector3d> before_;
};

}  // namespace omsk_test

#include <OpenMeshSkinned/Decimater/ModSkinnedFoldOverT.hh>
#include <OpenMeshSkinned/Decimater/ModSkinnedQuadricT.hh>
#include <OpenMeshSkinned/Decimater/ModWeightCapT.hh>
#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>

namespace omsk_test {

struct Modules {
  bool quadric = true;
  bool cap = true;
  bool fold = true;
  int max_influences = 4;
  double max_angle = 90.0;
  bool fold_fallback = false;  // ModSkinnedFoldOverT::set_fallback_placement
};

/// The three skinned modules added to \p dec as the tool adds them (cap 4, fold-over at 90 degrees).
template <typename Decimater>
struct SkinnedModules {
  typename OpenMeshSkinned::ModSkinnedQuadricT<Mesh>::Handle quadric;
  typename OpenMeshSkinned::ModWeightCapT<Mesh>::Handle cap;
  typename OpenMeshSkinned::ModSkinnedFoldOverT<Mesh>::Handle fold;
  explicit SkinnedModules(Decimater& dec) {
    dec.add(quadric);
    dec.add(cap);
    dec.add(fold);
  }
};

/// Both meshes have the same vertices (positions) and faces, in the same order.
inline void expect_same_mesh(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.n_vertices(), b.n_vertices());
  ASSERT_EQ(a.n_faces(), b.n_faces());
  for (auto vh : a.vertices()) EXPECT_EQ(a.point(vh), b.point(vh));
  for (auto fh : a.faces()) EXPECT_EQ(a.fv_range(fh).to_vector(), b.fv_range(fh).to_vector());
}

struct RunResult {
  size_t faces_before = 0, faces_after = 0, collapses = 0, flipped = 0, forced = 0, fallbacks = 0;
  size_t fold_fallbacks = 0;  // collapses made off their folding solved placement (Modules::fold_fallback)
};

/** Decimates \p mesh to \p ratio of its faces with the chosen modules and a FlipWatcher after them, driven
 *  by \p Decimater (OpenMesh's DecimaterT by default, or OpenMeshSkinned::LazyDecimaterT). */
template <typename Decimater = OpenMesh::Decimater::DecimaterT<Mesh>>
RunResult decimate(Mesh& mesh, double ratio, const Modules& m = {}) {
  using namespace OpenMeshSkinned;
  Decimater dec(mesh);
  typename ModSkinnedQuadricT<Mesh>::Handle hq;
  typename ModWeightCapT<Mesh>::Handle hc;
  typename ModSkinnedFoldOverT<Mesh>::Handle hf;
  typename FlipWatcherT<Mesh>::Handle hw;
  if (m.quadric) dec.add(hq);
  if (m.cap) dec.add(hc);
  if (m.fold) dec.add(hf);
  dec.add(hw);
  if (m.cap) dec.module(hc).set_max_influences(m.max_influences);
  if (m.fold) dec.module(hf).set_max_angle(m.max_angle);
  if (m.fold) dec.module(hf).set_fallback_placement(m.fold_fallback);
  dec.module(hw).max_angle_deg = m.max_angle;
  EXPECT_TRUE(dec.initialize());
  RunResult r;
  r.faces_before = mesh.n_faces();
  dec.decimate_to_faces(0, static_cast<size_t>(ratio * r.faces_before));
  r.collapses = dec.module(hw).collapses;
  r.flipped = dec.module(hw).flipped;
  if (m.quadric) {
    r.forced = dec.module(hq).solver().stats().forced_flips;
    r.fallbacks = dec.module(hq).solver().stats().placement_fallbacks;
    r.fold_fallbacks = dec.module(hq).solver().stats().fold_fallbacks;
  }
  mesh.garbage_collection();
  r.faces_after = mesh.n_faces();
  return r;
}

/// RMS surface distance (fraction of the rest bounding-box diagonal) between two meshes in one pose.
inline double posed_rms(const Mesh& original, const Mesh& lod, const OpenMeshSkinned::Pose& pose) {
  using namespace OpenMeshSkinned;
  return surface_distance(posed_soup(original, pose), posed_soup(lod, pose), 20000).rms / bbox_diagonal(original);
}

}  // namespace omsk_test

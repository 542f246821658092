// ModFrameFoldOverT: no face turns by more than the limit in any example frame.
#include "frame_modules.hh"

#include <OpenMeshSkinned/Decimater/ModFrameQuadricT.hh>

using namespace OpenMeshSkinned;
using namespace omsk_test;

namespace {

// Records, per collapse, whether a face around it turned by more than max_angle in any example frame
// (frames posed with morph offsets, unlike the skinned FlipWatcher).
template <typename M>
class FrameFlipWatcherT : public OpenMesh::Decimater::ModBaseT<M> {
public:
  DECIMATING_MODULE(FrameFlipWatcherT, M, FrameFlipWatcher);
  explicit FrameFlipWatcherT(M& mesh) : Base(mesh, true) {}
  double max_angle = 60.0;
  size_t collapses = 0, flipped = 0;

  void initialize() override { frames_ = example_frame_points(Base::mesh()); }
  void preprocess_collapse(const CollapseInfo& ci) override {
    faces_.clear();
    for (auto fh : Base::mesh().vf_range(ci.v0))
      if (fh != ci.fl && fh != ci.fr) faces_.push_back(fh);
    before_ = normals();
    v0_ = ci.v0.idx(), v1_ = ci.v1.idx();
  }
  void postprocess_collapse(const CollapseInfo&) override {
    ++collapses;
    const auto after = normals();
    const double min_cos = std::cos(max_angle * M_PI / 180.0) - 1e-9;
    for (size_t i = 0; i < after.size(); ++i)
      if (before_[i].norm() > 0 &&
          (after[i].norm() == 0 || after[i].normalized().dot(before_[i].normalized()) < min_cos)) {
        ++flipped;
        break;
      }
  }

private:
  std::vector<Eigen::Vector3d> normals() {
    std::vector<Eigen::Vector3d> out;
    for (const auto& p : frames_)
      for (auto fh : faces_) {
        Eigen::Vector3d q[3];
        int k = 0;
        for (auto v : Base::mesh().fv_range(fh)) q[k++] = p[v.idx()];
        out.push_back((q[1] - q[0]).cross(q[2] - q[0]));
      }
    return out;
  }
  std::vector<FramePoints> frames_;
  std::vector<typename M::FaceHandle> faces_;
  std::vector<Eigen::Vector3d> before_;
  int v0_ = -1, v1_ = -1;
};

struct Watched {
  size_t collapses, flipped;
};

Watched run(Mesh mesh, bool check) {
  OpenMesh::Decimater::DecimaterT<Mesh> dec(mesh);
  ModFrameQuadricT<Mesh>::Handle hq;
  ModFrameFoldOverT<Mesh>::Handle hf;
  FrameFlipWatcherT<Mesh>::Handle hw;
  dec.add(hq);
  if (check) {
    dec.add(hf);
    dec.module(hf).set_max_angle(60.0);
    EXPECT_NEAR(dec.module(hf).max_angle(), 60.0, 1e-9);
  }
  dec.add(hw);
  EXPECT_TRUE(dec.initialize());
  dec.decimate_to_faces(0, 40);
  return {dec.module(hw).collapses, dec.module(hw).flipped};
}

}  // namespace

TEST(ModFrameFoldOver, NoCollapseTurnsAFaceBeyondTheLimitInAnyFrame) {
  const Mesh mesh = frame_leg();
  const Watched with = run(mesh, true), without = run(mesh, false);
  std::printf("collapses that turned a face by > 60 degrees: %zu of %zu with the check, %zu of %zu without\n",
              with.flipped, with.collapses, without.flipped, without.collapses);
  EXPECT_GT(with.collapses, 1000u);
  EXPECT_EQ(with.flipped, 0u);
  EXPECT_GT(without.flipped, 0u);
}

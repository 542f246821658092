// The final fit's skin step: each vertex's weights solved against the fit's residuals, its position fixed.
#include "helpers.hh"

#include <OpenMeshSkinned/Skin/Validate.hh>
#include <OpenMeshSkinned/Solver/RefitWeights.hh>

#include <stdexcept>

using namespace OpenMeshSkinned;
using omsk_test::Mesh;

namespace {

// One residual per vertex and pose: the vertex to where \p truth (the same mesh, another skin) puts it.
std::vector<WeightResidual> vertex_targets(const Mesh& truth, const std::vector<Pose>& poses) {
  std::vector<WeightResidual> out;
  for (size_t k = 0; k < poses.size(); ++k) {
    const auto y = skin_positions(truth, poses[k]);
    for (auto vh : truth.vertices()) {
      WeightResidual r;
      r.v = {vh.idx(), -1, -1};
      r.bary = Eigen::Vector3d(1, 0, 0);
      r.target = y[vh.idx()];
      r.pose = int(k);
      out.push_back(r);
    }
  }
  return out;
}

double posed_error(const Mesh& a, const Mesh& b, const std::vector<Pose>& poses) {
  double sum = 0.0;
  for (const Pose& p : poses) {
    const auto ya = skin_positions(a, p), yb = skin_positions(b, p);
    for (size_t i = 0; i < ya.size(); ++i) sum += (ya[i] - yb[i]).squaredNorm();
  }
  return sum;
}

// \p truth with every vertex bound to its heaviest joint alone.
Mesh made_rigid(const Mesh& truth) {
  Mesh rigid = truth;
  for (auto vh : rigid.vertices()) rigid.property(influences_handle(rigid), vh).keep_heaviest(1);
  return rigid;
}

}  // namespace

// Vertices made rigid to their heaviest joint get their blend back wherever their own and their neighbours'
// joints include the ones their true skin uses: each is solved to within rounding of where it belongs.
TEST(RefitWeights, GivesRigidVerticesTheirBlendBackFromTheirNeighboursJoints) {
  const Mesh truth = make_bending_cylinder(12, 24);
  const auto poses = example_poses(truth);
  Mesh rigid = made_rigid(truth);
  const auto h = influences_handle(rigid);
  // Which blended vertices can be given their blend back.
  std::vector<char> reachable(rigid.n_vertices(), 0);
  size_t n_reachable = 0;
  for (auto vh : rigid.vertices()) {
    const Influences& t = truth.property(h, vh);
    if (t.size() < 2) continue;
    bool all = true;
    for (const JointWeight& jw : t) {
      bool seen = rigid.property(h, vh)[0].joint == jw.joint;
      for (auto wh : rigid.vv_range(vh)) seen |= rigid.property(h, wh)[0].joint == jw.joint;
      all &= seen;
    }
    reachable[vh.idx()] = all;
    n_reachable += all;
  }
  ASSERT_GT(n_reachable, 20u);
  const double before = posed_error(truth, rigid, poses);
  WeightRefitSettings s;
  s.regularization = 1e-12;
  const size_t changed = refit_weights(rigid, poses, vertex_targets(truth, poses), s);
  EXPECT_GT(changed, n_reachable / 2);
  EXPECT_LT(posed_error(truth, rigid, poses), 0.5 * before);
  const double d = bbox_diagonal(truth);
  for (auto vh : rigid.vertices()) {
    if (!reachable[vh.idx()]) continue;
    for (const Pose& p : poses) {
      const Eigen::Vector3d a = skin_point(to_eigen(truth.point(vh)), truth.property(h, vh), p);
      const Eigen::Vector3d b = skin_point(to_eigen(rigid.point(vh)), rigid.property(h, vh), p);
      ASSERT_LT((a - b).norm(), 1e-6 * d) << "vertex " << vh.idx();
    }
  }
  ValidationOptions vo;
  vo.max_influences = s.max_influences;
  EXPECT_NO_THROW(validate_skin(rigid, vo));
}

// The cap holds: at one influence every vertex stays rigid (to the joint that serves it best).
TEST(RefitWeights, KeepsTheCapOnInfluences) {
  const Mesh truth = make_bending_cylinder(12, 24);
  const auto poses = example_poses(truth);
  Mesh rigid = made_rigid(truth);
  const auto h = influences_handle(rigid);
  WeightRefitSettings s;
  s.max_influences = 1;
  refit_weights(rigid, poses, vertex_targets(truth, poses), s);
  for (auto vh : rigid.vertices()) {
    ASSERT_EQ(rigid.property(h, vh).size(), 1);
    EXPECT_EQ(rigid.property(h, vh)[0].weight, 1.0);
  }
}

// Where the skin already puts every vertex on its targets, no skin changes, not even by the solver's rounding.
TEST(RefitWeights, ASkinOnItsTargetsStaysAsItIs) {
  const Mesh truth = make_bending_cylinder(12, 24);
  const auto poses = example_poses(truth);
  Mesh same = truth;
  EXPECT_EQ(refit_weights(same, poses, vertex_targets(truth, poses)), 0u);
  const auto h = influences_handle(truth);
  for (auto vh : truth.vertices()) EXPECT_EQ(same.property(h, vh), truth.property(h, vh));
}

TEST(RefitWeights, RefusesAResidualNamingNoVertexOrPose) {
  Mesh mesh = make_bending_cylinder(8, 8);
  const auto poses = example_poses(mesh);
  WeightResidual r;
  r.v = {int(mesh.n_vertices()), -1, -1};
  EXPECT_THROW(refit_weights(mesh, poses, {r}), std::invalid_argument);
  r.v = {0, -1, -1};
  r.pose = int(poses.size());
  EXPECT_THROW(refit_weights(mesh, poses, {r}), std::invalid_argument);
  r.pose = 0;
  WeightRefitSettings s;
  s.max_influences = 0;
  EXPECT_THROW(refit_weights(mesh, poses, {r}, s), std::invalid_argument);
}

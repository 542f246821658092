// omsk-peer: held-out error of simplified characters against their original, whichever tool made them,
// with every file posed by the glTF specification itself (tests/support/gltf_spec: tinygltf, no code shared
// with the library's import or skinning), so ours and gltfpack's outputs are judged the same way.
//
//   omsk-peer ORIGINAL.glb CANDIDATE.glb [CANDIDATE.glb ...] [--frames K]
//
// Frames: K per animation of the original at (i + 0.5) / K of its length, i = 0..K-1 (the tool's own
// example poses are K' evenly spaced times over all clips end to end, both ends included; gltfpack sees
// no pose). A candidate's animation is matched by name (by position for unnamed ones). Error: Metro-style RMS and
// Hausdorff distance (OpenMeshSkinned::surface_distance), in % of the original's rest bounding-box diagonal; for
// textured characters also the texture-space deviation in the rest pose (uv_rms, uv_p95: % of the texture's
// width between the UV at a point of the original and the UV at the candidate's nearest point). One JSON line per
// candidate.
#include "gltf_spec.hh"

#include <OpenMeshSkinned/Eval/SurfaceDistance.hh>
#include <OpenMeshSkinned/Mesh/ClosestPoint.hh>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

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

// Texture-space deviation in the rest pose: area samples of the original's triangles, each with the UV its
// triangle interpolates there, against the UV the candidate's nearest surface point carries, in % of the
// texture's width. RMS and 95th percentile: the largest is a sample whose nearest point lies across a UV
// seam, on every tool.
struct UvDeviation {
  bool valid = false;
  double rms = 0.0, p95 = 0.0;
};
UvDeviation uv_deviation(const omsk_spec::Soup& original, const omsk_spec::Soup& candidate, size_t n = 20000) {
  UvDeviation out;
  if (!original.has_uv || !candidate.has_uv || original.triangles.empty() || candidate.triangles.empty()) return out;
  std::vector<double> cum;
  double total = 0.0;
  for (const auto& t : original.triangles) {
    const auto& p = original.points;
    total += 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm();
    cum.push_back(total);
  }
  if (!(total > 0.0)) return out;
  const OpenMeshSkinned::MeasuredSurface surface(soup(candidate), 0, 1);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> d;
  for (size_t s = 0; s < n; ++s) {
    const size_t i =
        std::min(cum.size() - 1, size_t(std::lower_bound(cum.begin(), cum.end(), u(rng) * total) - cum.begin()));
    double r1 = u(rng), r2 = u(rng);
    if (r1 + r2 > 1.0) r1 = 1.0 - r1, r2 = 1.0 - r2;
    const auto& t = original.triangles[i];
    const Eigen::Vector3d p = original.points[t[0]] + r1 * (original.points[t[1]] - original.points[t[0]]) +
                              r2 * (original.points[t[2]] - original.points[t[0]]);
    const Eigen::Vector2d uv = original.uvs[t[0]] + r1 * (original.uvs[t[1]] - original.uvs[t[0]]) +
                               r2 * (original.uvs[t[2]] - original.uvs[t[0]]);
    int tri = -1;
    surface.distance(p, tri);
    if (tri < 0) continue;
    const auto& c = candidate.triangles[tri];
    const Eigen::Vector3d corners[3] = {candidate.points[c[0]], candidate.points[c[1]], candidate.points[c[2]]};
    Eigen::Vector3d b;
    OpenMeshSkinned::closest_barycentric(corners, p, b);
    const Eigen::Vector2d uc = b[0] * candidate.uvs[c[0]] + b[1] * candidate.uvs[c[1]] + b[2] * candidate.uvs[c[2]];
    d.push_back(100.0 * (uv - uc).norm());
  }
  if (d.empty()) return out;
  double sq = 0.0;
  for (double x : d) sq += x * x;
  out.valid = true;
  out.rms = std::sqrt(sq / d.size());
  std::nth_element(d.begin(), d.begin() + long(0.95 * (d.size() - 1)), d.end());
  out.p95 = d[size_t(0.95 * (d.size() - 1))];
  return out;
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
      const omsk_spec::Soup cand_rest = omsk_spec::pose(cand, -1, 0.0);
      const size_t triangles = cand_rest.triangles.size();
      const UvDeviation uv = uv_deviation(rest, cand_rest);
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
      if (uv.valid) {
        j["uv_rms"] = uv.rms;
        j["uv_p95"] = uv.p95;
      }
      std::cout << j.dump() << std::endl;
    }
  } catch (const std::exception& e) {
    std::cerr << "omsk-peer: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

#include "Report.hh"

#include <OpenMeshSkinned/Lod/LodPoses.hh>

#include <iomanip>
#include <iostream>
#include <sstream>

namespace skinned_decimate {

namespace {

json times_json(const std::vector<OpenMeshSkinned::Clip>& clips, const std::vector<OpenMeshSkinned::PoseTime>& t) {
  json a = json::array();
  for (const auto& p : t) a.push_back({{"clip", clips[p.clip].name}, {"time", p.time}});
  return a;
}

// An error column of the report: "-" when not measured (--no-eval).
std::string error_cell(const json& v) { return v.is_number() ? fmt(v.get<double>(), 4) : "-"; }

}  // namespace

std::string fmt(double v, int prec) { return OpenMeshSkinned::fixed_number(v, prec); }

void print_table(const std::string& title, const std::vector<OpenMeshSkinned::LodLevel>& chain, bool have_heldout) {
  std::cout << title << "\n"
            << "  " << std::left << std::setw(8) << "ratio" << std::right << std::setw(10) << "triangles"
            << std::setw(10) << "vertices" << std::setw(10) << "seconds" << std::setw(10) << "max infl" << std::setw(14)
            << (have_heldout ? "heldout RMS%" : "rest RMS%") << std::setw(15)
            << (have_heldout ? "heldout Haus%" : "rest Haus%") << std::setw(8) << "joints" << std::setw(8) << "keys"
            << "\n";
  for (const auto& [lod, mesh] : chain)
    std::cout << "  " << std::left << std::setw(8) << fmt(lod.ratio, 4) << std::right << std::setw(10) << lod.faces
              << std::setw(10) << lod.vertices << std::setw(10) << fmt(lod.seconds, 2) << std::setw(10)
              << lod.max_influences << std::setw(14) << (lod.evaluated ? fmt(lod.rms, 4) : "-") << std::setw(15)
              << (lod.evaluated ? fmt(lod.hausdorff, 4) : "-") << std::setw(8) << lod.joints << std::setw(8) << lod.keys
              << "\n";
  // Counted over the whole pass, so the last level has the run's count.
  if (!chain.empty() && chain.back().report.non_finite_weights > 0)
    std::cout << "  the weight solver refused " << chain.back().report.non_finite_weights
              << " problems whose numbers overflowed (non-finite): those collapses were given infinite cost and "
                 "not made\n";
  for (const auto& [lod, mesh] : chain) {
    if (lod.fold_fallbacks > 0)
      std::cout << "  ratio " << fmt(lod.ratio, 4) << ": " << lod.fold_fallbacks
                << " collapses were made at the midpoint or an endpoint, their best placement folding a face, to "
                   "come closer to the target (--strict-fold keeps them waiting)\n";
    if (lod.fold_limit > 90.0)
      std::cout << "  ratio " << fmt(lod.ratio, 4) << ": the fold-over limit was relaxed to " << fmt(lod.fold_limit, 0)
                << " degrees to come closer to the target (--strict-fold keeps 90)\n";
  }
  for (const auto& [lod, mesh] : chain)
    if (lod.faces > lod.target && lod.at_floor)
      std::cout << "  ratio " << fmt(lod.ratio, 4) << ": target of " << lod.target
                << " triangles not reached; stopped at " << lod.faces
                << ": no collapse is left that keeps the mesh manifold (" << lod.pieces << " pieces)\n";
    else if (lod.faces > lod.target)
      std::cout << "  ratio " << fmt(lod.ratio, 4) << ": target of " << lod.target
                << " triangles not reached; stopped at " << lod.faces
                << " (every remaining collapse is refused: it would break the mesh, fold a face in some pose, "
                   "remove a vertex --joint-guard keeps, or exceed --max-error)\n";
  for (const auto& [lod, mesh] : chain)
    if (lod.deviation_bound >= 0.0)
      std::cout << "  ratio " << fmt(lod.ratio, 4) << ": no vertex of the input is further than "
                << fmt(lod.deviation_bound, 4) << "% of the diagonal from it in any example pose (--max-error)\n";
}

void print_comparison(const json& runs) {
  std::cout << "comparison (held-out error, % of the rest-pose bounding-box diagonal)\n  " << std::left << std::setw(9)
            << "method" << std::setw(8) << "ratio" << std::right << std::setw(10) << "triangles" << std::setw(10)
            << "seconds" << std::setw(14) << "mean RMS%" << std::setw(15) << "max Haus%"
            << "\n";
  for (const auto& r : runs)
    for (const auto& l : r["lods"])
      std::cout << "  " << std::left << std::setw(9) << r["method"].get<std::string>() << std::setw(8)
                << fmt(l["ratio"].get<double>(), 4) << std::right << std::setw(10) << l["faces"].get<size_t>()
                << std::setw(10) << fmt(l["seconds"].get<double>(), 2) << std::setw(14) << error_cell(l["heldout_rms"])
                << std::setw(15) << error_cell(l["heldout_hausdorff"]) << "\n";
}

json lod_json(const OpenMeshSkinned::LodReport& lod, const std::string& file,
              const std::vector<OpenMeshSkinned::Clip>& clips, const OpenMeshSkinned::PoseSchedule& sched,
              bool bind_pose_in_examples) {
  json l = {{"ratio", lod.ratio},
            {"target_faces", lod.target},
            {"target_reached", lod.faces <= lod.target},
            {"faces", lod.faces},
            {"vertices", lod.vertices},
            {"seconds", lod.seconds},
            {"max_influences", lod.max_influences},
            {"joints", lod.joints},
            {"fold_limit_deg", lod.fold_limit},
            {"fold_fallbacks", lod.fold_fallbacks},
            {"at_topology_floor", lod.at_floor},
            {"deviation_bound", lod.deviation_bound >= 0.0 ? json(lod.deviation_bound) : json(nullptr)},
            {"keys", lod.keys},
            {"heldout_rms", lod.evaluated ? json(lod.rms) : json(nullptr)},
            {"heldout_hausdorff", lod.evaluated ? json(lod.hausdorff) : json(nullptr)},
            {"example_pose_times", times_json(clips, sched.examples)},
            {"bind_pose_in_examples", bind_pose_in_examples},
            {"heldout_times", times_json(clips, sched.held_out)}};
  if (lod.evaluated)
    l["switch_hint"] = {{"screen_height_px", OpenMeshSkinned::kSwitchHintScreenHeight},
                        {"unity_relative_screen_height", lod.switch_hint.unity_relative_height},
                        {"unreal_screen_size", lod.switch_hint.unreal_screen_size}};
  if (!file.empty()) l["file"] = file;
  return l;
}

}  // namespace skinned_decimate

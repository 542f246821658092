#pragma once
// What a run prints and writes: the table per character and method, the comparison table, the JSON report.

#include "Options.hh"

#include <OpenMeshSkinned/Lod/LodReport.hh>

#include <OpenMeshSkinned/Skin/PoseSchedule.hh>

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace skinned_decimate {

using json = nlohmann::ordered_json;

std::string fmt(double v, int prec);

/// The LOD table, and a line per level whose target could not be reached.
void print_table(const std::string& title, const std::vector<OpenMeshSkinned::LodLevel>& chain, bool have_heldout);

/// One table over several runs: method x LOD.
void print_comparison(const json& runs);

/// The report entry of one level: what was asked, what came out, and in which poses it was judged.
json lod_json(const OpenMeshSkinned::LodReport& lod, const std::string& file,
              const std::vector<OpenMeshSkinned::Clip>& clips, const OpenMeshSkinned::PoseSchedule& sched,
              bool bind_pose_in_examples);

}  // namespace skinned_decimate

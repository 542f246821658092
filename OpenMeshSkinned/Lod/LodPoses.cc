#include "LodPoses.hh"

#include "LodPoseCount.hh"

#include <OpenMeshSkinned/Deform/PoseSelection.hh>
#include <OpenMeshSkinned/IO/IOError.hh>
#include <OpenMeshSkinned/Skin/FrameAnimation.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace OpenMeshSkinned {

namespace {

// Each selection with what the pose list says of it.
struct Selection {
  std::string name, label;
};

const std::vector<Selection>& selections() {
  static const std::vector<Selection> s = {{"even", ""},
                                           {"motion", " (evenly over the motion)"},
                                           {"spread", " (spread over the motion)"},
                                           {"ga", " (chosen by the key-frame GA)"}};
  return s;
}

}  // namespace

const std::vector<std::string>& pose_selections() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const Selection& s : selections()) n.push_back(s.name);
    return n;
  }();
  return names;
}

std::string pose_selection_names() {
  const auto& n = pose_selections();
  std::string s;
  for (size_t i = 0; i < n.size(); ++i) s += (i == 0 ? "" : i + 1 == n.size() ? " or " : ", ") + n[i];
  return s;
}

std::string fixed_number(double v, int precision) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(precision) << v;
  return os.str();
}

LodPoses select_lod_poses(const SkinnedMesh& mesh, const LodOptions& opt, const std::string& name,
                          const LodCallbacks& callbacks, bool poses_given) {
  const auto& all = clips(mesh);
  const Skeleton& skel = skeleton(mesh);
  LodPoses p;
  if (all.empty()) {
    if (poses_given)
      callbacks.warn(name + " has no animation: --poses ignored, decimating and judging in the rest pose only");
    p.examples = p.heldout = {Pose::identity(skel.size())};
    return p;
  }
  // A frame animation learns from, and is judged on, stored frames, never the blend of two; with few of
  // them, half are kept back to judge on.
  const size_t stored = frame_times(mesh).size();
  const int wanted = lod_pose_count(opt, mesh);
  const int k = stored > 0 ? std::min<int>(wanted, int((stored + 1) / 2)) : wanted;
  const int clip = lod_pose_clip(opt, mesh, name);
  p.schedule = make_pose_schedule(all, k, clip);
  snap_to_frames(p.schedule, frame_times(mesh));
  const std::string& select = opt.pose_select;
  bool selected = false;  // by something other than even times
  if (select != "even") {
    const auto candidates = candidate_frames(mesh, p.schedule.held_out, clip);
    selected = candidates.size() >= (select == "ga" ? 2u : 1u);
    if (!selected)
      callbacks.warn(name + ": --pose-select " + select + " has too few frames to choose from (the rest are held " +
                     "out): the example poses are at even times");
    else
      p.schedule.examples = select == "ga"       ? select_poses_ga(mesh, candidates, size_t(k))
                            : select == "spread" ? select_poses_spread(mesh, candidates, size_t(k), opt.bind_pose)
                                                 : select_poses_by_motion(mesh, candidates, size_t(k));
  }
  p.examples = poses_at(skel, all, p.schedule.examples);
  // The bind pose too, unless asked not to: it is the pose every other tool judges, and a handful of
  // clip frames can miss the neutral configuration entirely.
  if (opt.bind_pose) p.examples.push_back(Pose::identity(skel.size()));
  p.heldout = poses_at(skel, all, p.schedule.held_out.empty() ? p.schedule.examples : p.schedule.held_out);
  std::string how;
  if (selected)
    for (const Selection& s : selections())
      if (s.name == select) how = s.label;
  std::string line = name + ": example poses" + how + " at";
  for (const auto& t : p.schedule.examples) line += " " + all[t.clip].name + "@" + fixed_number(t.time, 3) + "s";
  callbacks.say(line + (opt.bind_pose ? " + bind pose" : ""));
  // Keys of huge but finite values can still overflow once composed down a chain of joints.
  for (const auto* set : {&p.examples, &p.heldout})
    for (const Pose& pose : *set)
      if (!pose.finite())
        throw IOError(name + ": pose \"" + pose.label +
                      "\" is not finite: its keys' translations or scales are too large to compose");
  return p;
}

}  // namespace OpenMeshSkinned

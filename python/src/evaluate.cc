// oms.evaluate(): one LOD against its original in held-out frames, on its own.
#include "binding.hh"
#include "options.hh"
#include "progress.hh"

#include <OpenMeshSkinned/Lod/CheckLodOptions.hh>
#include <OpenMeshSkinned/Lod/Evaluate.hh>
#include <OpenMeshSkinned/Lod/LodPoses.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <set>

namespace omsk_python {

namespace {

using namespace OpenMeshSkinned;

// The make_lods() keywords that choose the frames, and those of the measurement.
const std::set<std::string> kEvaluateKeywords = {"poses",   "pose_clip",        "bind_pose",    "pose_select",
                                                 "threads", "per_vertex_error", "max_memory_mb"};

// (clip, seconds) pairs, the clip by name or index, as frames of \p mesh.
std::vector<PoseTime> frame_times_of(const py::sequence& frames, const Mesh& m) {
  const auto& all = clips(*m.mesh);
  std::vector<PoseTime> times;
  for (const py::handle f : frames) {
    const auto pair = f.cast<std::pair<py::object, double>>();
    PoseTime t;
    t.time = pair.second;
    if (py::isinstance<py::int_>(pair.first)) {
      t.clip = pair.first.cast<int>();
    } else {
      const std::string name = pair.first.cast<std::string>();
      t.clip = -1;
      for (size_t i = 0; i < all.size(); ++i)
        if (all[i].name == name) t.clip = int(i);
      if (t.clip < 0) raise(exceptions().options, ("evaluate(): no clip named \"" + name + "\"").c_str());
    }
    if (t.clip < 0 || size_t(t.clip) >= all.size())
      raise(exceptions().options, ("evaluate(): clip " + std::to_string(t.clip) + " is not one of the " +
                                   std::to_string(all.size()) + " clips")
                                      .c_str());
    times.push_back(t);
  }
  return times;
}

// The LOD's own poses of \p times: its skeleton or clips may have been reduced (max_joints, anim_error,
// keyframes), and then only its clips pose it as the original's pose the original.
std::vector<Pose> lod_poses(const SkinnedMesh& original, const SkinnedMesh& lod, const std::vector<PoseTime>& times) {
  if (times.empty()) return {Pose::identity(skeleton(lod).size())};
  if (clips(lod).size() != clips(original).size())
    throw LodOptionsError("evaluate(): the LOD has " + std::to_string(clips(lod).size()) + " clips, its original " +
                          std::to_string(clips(original).size()) + ": not a LOD of it");
  return poses_at(skeleton(lod), clips(lod), times);
}

HeldOutError evaluate_py(const Mesh& original, const Mesh& lod, const py::object& frames, const py::object& progress,
                         const py::kwargs& kwargs) {
  for (const auto& [key, value] : kwargs)
    if (!kEvaluateKeywords.count(py::str(key)))
      throw py::type_error("evaluate() got an unexpected keyword argument '" + std::string(py::str(key)) + "'");
  const LodOptions options = lod_options(kwargs, "evaluate");
  const std::string name = original.path.empty() ? "the mesh" : original.path;
  std::vector<PoseTime> times;
  const bool chosen = frames.is_none();
  if (!chosen) times = frame_times_of(frames, original);
  PythonProgress state(progress);
  LodCallbacks cb;
  cb.progress = [&state](const char* stage, double fraction) { return state(stage, fraction); };
  try {
    py::gil_scoped_release nogil;
    const SkinnedMesh& o = *original.mesh;
    std::vector<Pose> poses;
    if (chosen) {
      check_lod_options(options, o, name);
      const LodPoses p = select_lod_poses(o, options, name);
      times = p.schedule.held_out.empty() ? p.schedule.examples : p.schedule.held_out;
      poses = p.heldout;
    } else {
      poses = times.empty() ? std::vector<Pose>{Pose::identity(skeleton(o).size())}
                            : poses_at(skeleton(o), clips(o), times);
    }
    EvaluateOptions eo;
    eo.threads = options.threads;
    eo.per_vertex_error = options.per_vertex_error;
    const auto errors = evaluate_lods(o, {lod.mesh.get()}, poses, {lod_poses(o, *lod.mesh, times)}, eo, cb);
    return errors.at(0);
  } catch (const LodCancelled&) {
    state.rethrow_if_raised();
    throw;
  }
}

}  // namespace

void add_evaluate(py::module_& m) {
  py::class_<HeldOutError>(m, "HeldOutError", "A LOD's distance from its original over a set of frames.")
      .def_readonly("rms", &HeldOutError::rms,
                    "Mean over the frames of each frame's symmetric RMS surface distance, % of the original's "
                    "rest-pose bounding-box diagonal.")
      .def_readonly("hausdorff", &HeldOutError::hausdorff,
                    "Max over the frames of the symmetric Hausdorff distance, % of the diagonal.")
      .def_property_readonly(
          "vertex_error",
          [](const HeldOutError& e) { return py::array_t<float>(e.vertex_error.size(), e.vertex_error.data()); },
          "(N,) float32 copy: each LOD vertex's worst distance over the frames, % (empty unless "
          "per_vertex_error=True).")
      .def("__repr__", [](const HeldOutError& e) {
        return "HeldOutError(rms=" + std::string(py::repr(py::float_(e.rms))) +
               ", hausdorff=" + std::string(py::repr(py::float_(e.hausdorff))) + ")";
      });
  m.def("evaluate", &evaluate_py, py::arg("original"), py::arg("lod"), py::arg("frames") = py::none(), py::kw_only(),
        py::arg("progress") = py::none(),
        R"(Measures lod against original, both posed in the same frames (each by its own skeleton and clips): the
symmetric surface distances make_lods() reports, in % of the original's rest-pose bounding-box diagonal.

frames: a list of (clip name or index, seconds), e.g. a LodChain's heldout_frames; None: the held-out frames
make_lods() would judge in, chosen with the keywords poses, pose_clip, bind_pose, pose_select (and
max_memory_mb) as make_lods() takes them. Also threads and per_vertex_error. An original without clips is judged
in its rest pose. The GIL is released meanwhile; progress as in make_lods(). Returns a HeldOutError.)");
}

}  // namespace omsk_python

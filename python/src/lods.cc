// oms.make_lods() and what it returns (LodChain, Lod, LodReport), and oms.save(lods, path).
#include "binding.hh"
#include "options.hh"
#include "progress.hh"

#include <OpenMeshSkinned/IO/IOError.hh>
#include <OpenMeshSkinned/Lod/MakeLods.hh>
#include <OpenMeshSkinned/Lod/SaveLods.hh>
#include <OpenMeshSkinned/Skin/SkinProperties.hh>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <mutex>

namespace omsk_python {

namespace {

using namespace OpenMeshSkinned;

// One level of a chain: shares the chain, so that its mesh stays valid while Python holds either.
struct Lod {
  std::shared_ptr<LodChain> chain;
  size_t index = 0;
  const LodLevel& level() const { return chain->levels[index]; }
};

py::list frame_list(const std::vector<PoseTime>& times, const std::vector<std::string>& clip_names) {
  py::list l;
  for (const PoseTime& t : times) l.append(py::make_tuple(clip_names.at(size_t(t.clip)), t.time));
  return l;
}

py::dict report_dict(const LodReport& r) {
  py::dict d;
  d["ratio"] = r.ratio, d["target"] = r.target, d["faces"] = r.faces, d["vertices"] = r.vertices;
  d["seconds"] = r.seconds, d["max_influences"] = r.max_influences, d["keys"] = r.keys, d["joints"] = r.joints;
  d["fold_limit"] = r.fold_limit, d["at_floor"] = r.at_floor, d["pieces"] = r.pieces;
  d["fold_fallbacks"] = r.fold_fallbacks;
  d["deviation_bound"] = r.deviation_bound < 0.0 ? py::object(py::none()) : py::cast(r.deviation_bound);
  d["evaluated"] = r.evaluated;
  d["rms"] = r.evaluated ? py::cast(r.rms) : py::object(py::none());
  d["hausdorff"] = r.evaluated ? py::cast(r.hausdorff) : py::object(py::none());
  return d;
}

Chain make_lods_py(const Mesh& m, const py::object& progress, const py::kwargs& kwargs) {
  const LodOptions options = lod_options(kwargs, "make_lods");
  Chain c;
  c.input_path = m.path;
  for (const Clip& clip : clips(*m.mesh)) c.clip_names.push_back(clip.name);
  PythonProgress state(progress);
  std::mutex lines;
  LodCallbacks cb;
  cb.progress = [&state](const char* stage, double fraction) { return state(stage, fraction); };
  cb.message = [&](const std::string& line) {
    const std::lock_guard<std::mutex> lock(lines);
    c.messages.push_back(line);
  };
  cb.warning = [&](const std::string& line) {
    const std::lock_guard<std::mutex> lock(lines);
    c.warnings.push_back(line);
  };
  try {
    py::gil_scoped_release nogil;
    c.chain = std::make_shared<LodChain>(make_lods(*m.mesh, options, cb, m.path.empty() ? "the mesh" : m.path));
  } catch (const LodCancelled&) {
    state.rethrow_if_raised();
    throw;
  }
  return c;
}

std::vector<std::string> save_chain(const Chain& c, const std::string& path) {
  try {
    py::gil_scoped_release nogil;
    return save_lods(*c.chain, path, c.input_path.empty() ? std::vector<std::string>{} : std::vector{c.input_path});
  } catch (const IOError& e) {
    raise(exceptions().write, e.what());
  }
}

// LodReport: the figures of one level.
void add_lod_report(py::module_& m) {
  py::class_<LodReport>(m, "LodReport", "How one LOD was made and how far it is from the input (read-only).")
      .def_readonly("ratio", &LodReport::ratio, "The share of the input's triangles asked for.")
      .def_readonly("target", &LodReport::target, "Triangles asked for.")
      .def_readonly("faces", &LodReport::faces, "Triangles it has.")
      .def_readonly("vertices", &LodReport::vertices, "Vertices it has.")
      .def_readonly("seconds", &LodReport::seconds, "From the start of the decimation to this level.")
      .def_readonly("max_influences", &LodReport::max_influences, "Most bones on any of its vertices.")
      .def_readonly("keys", &LodReport::keys, "Key frames over its clips' channels (fewer with anim_error).")
      .def_readonly("joints", &LodReport::joints, "Its skeleton's joints (fewer with max_joints).")
      .def_readonly("fold_limit", &LodReport::fold_limit,
                    "The largest face turn allowed to reach the target, degrees (90 unless relaxed).")
      .def_readonly("at_floor", &LodReport::at_floor,
                    "True when it stopped above the target: no collapse keeps the mesh manifold.")
      .def_readonly("pieces", &LodReport::pieces, "Its connected pieces (when at_floor).")
      .def_readonly("fold_fallbacks", &LodReport::fold_fallbacks,
                    "Collapses made off their solved placement, which folded, to reach the target.")
      .def_property_readonly(
          "deviation_bound",
          [](const LodReport& r) {
            return r.deviation_bound < 0.0 ? py::object(py::none()) : py::cast(r.deviation_bound);
          },
          "With max_error: bound on the input's vertices' distance to it, % of the diagonal; else None.")
      .def_readonly("evaluated", &LodReport::evaluated, "Whether it was measured in held-out frames.")
      .def_property_readonly(
          "rms", [](const LodReport& r) { return r.evaluated ? py::cast(r.rms) : py::object(py::none()); },
          "Held-out RMS surface distance, % of the input's rest-pose bounding-box diagonal (None: not evaluated).")
      .def_property_readonly(
          "hausdorff", [](const LodReport& r) { return r.evaluated ? py::cast(r.hausdorff) : py::object(py::none()); },
          "Held-out Hausdorff distance, % of the diagonal (None: not evaluated).")
      .def_property_readonly(
          "vertex_error",
          [](const LodReport& r) { return py::array_t<float>(r.vertex_error.size(), r.vertex_error.data()); },
          "(N,) float32 copy: each vertex's worst held-out error, % (empty unless per_vertex_error).")
      .def("to_dict", &report_dict, "The report as a dict (without vertex_error), as the command line's --report.")
      .def("__repr__", [](const LodReport& r) { return "LodReport(" + std::string(py::str(report_dict(r))) + ")"; });
}

// Lod and LodChain: the levels and what can be done with them.
void add_lod_chain(py::module_& m) {
  py::class_<Lod>(m, "Lod", "One level of a LodChain: its mesh and its report.")
      .def_property_readonly(
          "mesh",
          [](const Lod& l) {
            // Aliasing: the mesh lives inside the chain, which it keeps alive.
            return Mesh{std::shared_ptr<const SkinnedMesh>(l.chain, &l.level().mesh), "", {}};
          },
          "The LOD as a Mesh (shares the chain's data: no copy until an array is read).")
      .def_property_readonly(
          "report", [](const Lod& l) { return l.level().report; }, "Its LodReport (a copy).")
      .def("__repr__", [](const Lod& l) {
        const LodReport& r = l.level().report;
        return "<openmeshskinned.Lod " + std::to_string(l.index + 1) + ": ratio " + std::to_string(r.ratio) + ", " +
               std::to_string(r.faces) + " triangles>";
      });

  py::class_<Chain>(m, "LodChain",
                    "What make_lods() returns: the LODs largest first (a sequence of Lod), the method that made "
                    "them, and the frames they were made and judged in.")
      .def(
          "__len__", [](const Chain& c) { return c.chain->levels.size(); }, "The number of LODs.")
      .def(
          "__getitem__",
          [](const Chain& c, py::ssize_t i) {
            const py::ssize_t n = py::ssize_t(c.chain->levels.size());
            if (i < 0) i += n;
            if (i < 0 || i >= n) throw py::index_error("LOD index out of range");
            return Lod{c.chain, size_t(i)};
          },
          "The i-th LOD (0: the largest).")
      .def_property_readonly(
          "method", [](const Chain& c) { return c.chain->method; },
          "The method that made them (the one asked for, or the mesh's default).")
      .def_property_readonly(
          "example_frames", [](const Chain& c) { return frame_list(c.chain->poses.schedule.examples, c.clip_names); },
          "The clip frames the decimater learnt from: list of (clip name, seconds); the bind pose comes on top "
          "unless bind_pose=False. Empty for a mesh without clips (its rest pose).")
      .def_property_readonly(
          "heldout_frames", [](const Chain& c) { return frame_list(c.chain->poses.schedule.held_out, c.clip_names); },
          "The frames the LODs were judged in, never learnt from: list of (clip name, seconds); evaluate() "
          "takes them as its frames. Empty for a mesh without clips (judged in its rest pose).")
      .def_property_readonly(
          "decimate_seconds", [](const Chain& c) { return c.chain->decimate_seconds; },
          "Seconds spent decimating and fitting.")
      .def_property_readonly(
          "evaluate_seconds", [](const Chain& c) { return c.chain->evaluate_seconds; },
          "Seconds spent reducing skeleton and clips and measuring.")
      .def_property_readonly(
          "messages", [](const Chain& c) { return c.messages; },
          "What was chosen or done, one line each (the command line prints them).")
      .def_property_readonly(
          "warnings", [](const Chain& c) { return c.warnings; }, "What was changed or not applied, one line each.")
      .def("__repr__", [](const Chain& c) {
        return "<openmeshskinned.LodChain " + c.chain->method + ": " + std::to_string(c.chain->levels.size()) +
               " LODs>";
      });
}

}  // namespace

void add_lods(py::module_& m) {
  add_lod_report(m);
  add_lod_chain(m);
  m.def("make_lods", &make_lods_py, py::arg("mesh"), py::kw_only(), py::arg("progress") = py::none(),
        ("Makes the LODs of mesh in one pass, largest first: what the skinned-decimate command does between reading "
         "and writing (example poses, decimation with a snapshot per level, fold-limit ladder, final fit, skeleton "
         "and motion LoD, held-out evaluation). Returns a LodChain; mesh is not changed.\n\n"
         "progress(stage: str, fraction: float) is called on this thread at each stage and as it advances; return "
         "False to stop (raises Cancelled); an exception it raises ends the call. The GIL is released meanwhile.\n"
         "Raises OptionsError (the command line's one-line message) for a request that cannot be carried out, "
         "FileError when the clips' poses do not compose, TypeError for an unknown keyword.\n\n"
         "Keywords (LodOptions, with its defaults; None keeps the default):\n" +
         options_doc())
            .c_str());
  m.def(
      "default_options", [] { return options_dict(LodOptions()); },
      "Every make_lods() keyword with its default (a dict), from the C++ LodOptions.");
  m.def(
      "lod_methods",
      [] {
        std::vector<std::string> names;
        for (const LodMethod& x : OpenMeshSkinned::lod_methods()) names.push_back(x.name);
        return names;
      },
      "The decimation methods make_lods(method=...) accepts, the product first.");
  m.def("_save_chain", &save_chain, py::arg("lods"), py::arg("path"));
}

}  // namespace omsk_python

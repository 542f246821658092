// LodOptions as Python keywords: one table of the fields (name, type, meaning), so that make_lods(),
// default_options() and the docstring all follow the C++ struct and its defaults.
#include "options.hh"

#include <OpenMeshSkinned/Lod/LodPoseCount.hh>

#include <pybind11/stl.h>

#include <algorithm>
#include <functional>
#include <type_traits>

namespace omsk_python {

namespace {

using OpenMeshSkinned::LodOptions;

struct Field {
  const char* name;
  const char* type;  // for the docstring and the TypeError
  const char* help;
  std::function<void(LodOptions&, py::handle)> set;
  std::function<py::object(const LodOptions&)> get;
};

template <typename T>
Field field(const char* name, const char* type, const char* help, T LodOptions::*member) {
  return {name, type, help, [member](LodOptions& o, py::handle v) { o.*member = v.cast<T>(); },
          [member](const LodOptions& o) { return py::cast(o.*member); }};
}

const std::string& poses_help() {
  using namespace OpenMeshSkinned;
  static const std::string s =
      "example poses: evenly spaced times over the clips (plus the bind pose); 0: " + lod_pose_count_rule();
  return s;
}

const std::vector<Field>& fields() {
  static const std::vector<Field> all = {
      field("method", "str", "the priority module (lod_methods()); '': skinned, or frames for a frame animation",
            &LodOptions::method),
      field("ratios", "list of float", "one LOD per ratio of the input's triangles, in (0, 1]", &LodOptions::ratios),
      field("faces", "list of int >= 0", "one LOD per triangle count instead of ratios", &LodOptions::faces),
      field("max_influences", "int", "bones per vertex at every level, 1..8", &LodOptions::max_influences),
      field("poses", "int >= 0", poses_help().c_str(), &LodOptions::poses),
      {"pose_clip", "str or int", "the clip (name or index) the example poses come from; '': all, end to end",
       [](LodOptions& o, py::handle v) {
         o.pose_clip = py::isinstance<py::int_>(v) ? std::to_string(v.cast<long long>()) : v.cast<std::string>();
       },
       [](const LodOptions& o) { return py::cast(o.pose_clip); }},
      field("bind_pose", "bool", "the bind pose among the example poses", &LodOptions::bind_pose),
      field("pose_select", "str",
            "how the example poses are chosen: 'even' (evenly spaced times), 'motion' (evenly spaced over the "
            "motion), 'spread' (farthest first over the motion) or 'ga' (the key-frame GA)",
            &LodOptions::pose_select),
      field("threads", "int", "threads for solving and measuring (0: the hardware's)", &LodOptions::threads),
      field("evaluate", "bool", "measure every LOD in held-out frames", &LodOptions::evaluate),
      field("per_vertex_error", "bool", "keep each LOD vertex's worst held-out error (report.vertex_error)",
            &LodOptions::per_vertex_error),
      field("refit", "bool",
            "final fit of the LODs' rest positions in the example poses (with edge flips, skin weights and each "
            "stored frame of a frame animation on small inputs)",
            &LodOptions::refit),
      field("strict_fold", "bool", "never relax the 90-degree fold-over limit to reach a target",
            &LodOptions::strict_fold),
      field("area_exponent", "float",
            "the skinned and frames priorities are energy / area**area_exponent, in [0, 1]: 0 the energy, 1 per "
            "area (a mean squared distance); -1: skinned 0.5 up to 20,000 vertices, 1 above; frames 0.25 when "
            "the coarsest level keeps at most half of the triangles, 0 otherwise",
            &LodOptions::area_exponent),
      field("area_floor", "float",
            "below this many of the coarsest level's mean triangles a collapse is priced per area (0: no floor)",
            &LodOptions::area_floor),
      field("joint_guard", "float", "Savoye-Meyer joint-region guard TAU (0: off)", &LodOptions::joint_guard),
      field("normal_weight", "float", "weight of the shading-normal term in the collapse cost (0: geometry only)",
            &LodOptions::normal_weight),
      field("max_error", "float", "bound on the input's vertices' distance to the LOD, % of the diagonal (0: none)",
            &LodOptions::max_error),
      field("max_joints", "list of int", "skeleton LoD: joints kept, one per LOD, the last repeating ([]: all)",
            &LodOptions::max_joints),
      field("joint_energy", "float", "skeleton LoD: minor joints under this joint energy go (0: none by energy)",
            &LodOptions::joint_energy),
      field("anim_error", "float", "motion LoD: keys dropped while no vertex moves further, % of the diagonal",
            &LodOptions::anim_error),
      field("anim_frames", "bool", "motion LoD by merging whole key frames (the paper's) instead of channels",
            &LodOptions::anim_frames),
      field("keyframes", "int >= 0", "frame animations: keep this many stored frames, chosen by the GA (0: all)",
            &LodOptions::keyframes),
      field("max_memory_mb", "int >= 0", "refuse a number of poses whose poses would need more (0: no limit)",
            &LodOptions::max_memory_mb),
  };
  return all;
}

}  // namespace

LodOptions lod_options(const py::kwargs& kwargs, const char* function) {
  LodOptions o;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    const auto& all = fields();
    const auto f = std::find_if(all.begin(), all.end(), [&](const Field& x) { return name == x.name; });
    if (f == all.end())
      throw py::type_error(std::string(function) + "() got an unexpected keyword argument '" + name + "'");
    if (value.is_none()) continue;  // None: the default
    try {
      f->set(o, value);
    } catch (const py::cast_error&) {
      throw py::type_error(std::string(function) + "(): " + name + " must be " + f->type + ", not " +
                           std::string(py::str(py::type::of(value).attr("__name__"))));
    }
  }
  return o;
}

py::dict options_dict(const LodOptions& o) {
  py::dict d;
  for (const Field& f : fields()) d[f.name] = f.get(o);
  return d;
}

namespace {

// A number as the tool's command line reads it back to the same double (Python's shortest repr).
std::string number(double v) { return py::repr(py::float_(v)); }

template <typename T>
std::string joined(const std::vector<T>& values) {
  std::string s;
  for (const T& v : values) {
    if (!s.empty()) s += ",";
    if constexpr (std::is_floating_point_v<T>)
      s += number(v);
    else
      s += std::to_string(v);
  }
  return s;
}

}  // namespace

std::vector<std::string> tool_arguments(const LodOptions& o) {
  const LodOptions d;
  if (o.per_vertex_error)
    throw py::type_error("per_vertex_error is not an option of the tool's runs (html=True writes each page with it)");
  if (o.faces.size() > 1)
    throw OpenMeshSkinned::LodOptionsError("the tool makes a chain from ratios: faces takes one count in a batch");
  std::vector<std::string> a;
  const auto flag = [&a](bool on, const char* name) {
    if (on) a.push_back(name);
  };
  const auto value = [&a](bool on, const char* name, const std::string& v) {
    if (on) a.insert(a.end(), {name, v});
  };
  value(!o.method.empty(), "--method", o.method);
  value(o.faces.empty() && o.ratios != d.ratios, "--lods", joined(o.ratios));
  value(!o.faces.empty(), "--faces", o.faces.empty() ? "" : std::to_string(o.faces[0]));
  value(o.max_influences != d.max_influences, "--max-influences", std::to_string(o.max_influences));
  value(o.poses != d.poses, "--poses", std::to_string(o.poses));
  value(o.pose_clip != d.pose_clip, "--pose-clip", o.pose_clip);
  flag(!o.bind_pose, "--no-bind-pose");
  value(o.pose_select != d.pose_select, "--pose-select", o.pose_select);
  value(o.threads != d.threads, "--threads", std::to_string(o.threads));
  flag(!o.evaluate, "--no-eval");
  flag(!o.refit, "--no-refit");
  flag(o.strict_fold, "--strict-fold");
  value(o.area_exponent != d.area_exponent, "--error", number(o.area_exponent));
  value(o.area_floor != d.area_floor, "--area-floor", number(o.area_floor));
  value(o.joint_guard != d.joint_guard, "--joint-guard", number(o.joint_guard));
  value(o.normal_weight != d.normal_weight, "--normal-weight", number(o.normal_weight));
  value(o.max_error != d.max_error, "--max-error", number(o.max_error));
  value(!o.max_joints.empty(), "--max-joints", joined(o.max_joints));
  value(o.joint_energy != d.joint_energy, "--joint-energy", number(o.joint_energy));
  value(o.anim_error != d.anim_error, "--anim-error", number(o.anim_error));
  value(o.anim_frames, "--anim-method", "frames");
  value(o.keyframes != d.keyframes, "--keyframes", std::to_string(o.keyframes));
  value(o.max_memory_mb != d.max_memory_mb, "--max-memory", std::to_string(o.max_memory_mb));
  return a;
}

std::string options_doc() {
  const LodOptions d;
  std::string s;
  for (const Field& f : fields())
    s += std::string("    ") + f.name + " (" + f.type + ", default " + std::string(py::repr(f.get(d))) +
         "): " + f.help + "\n";
  return s;
}

}  // namespace omsk_python

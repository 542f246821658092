#include "OpenMeshSkinned/IO/GltfInterpolation.hh"

#include "OpenMeshSkinned/IO/GltfAccessors.hh"
#include "OpenMeshSkinned/IO/GltfJson.hh"
#include "OpenMeshSkinned/IO/IOError.hh"

#include <cmath>

namespace OpenMeshSkinned::detail {
namespace {

using json = nlohmann::json;

struct Keys {
  std::vector<double> times, values;  // values: n per key
};

// STEP: each key's value holds until the next key; LINEAR reaches it through a short ramp just before.
Keys step_as_linear(const std::vector<double>& in, const std::vector<double>& out, size_t n) {
  Keys k;
  for (size_t i = 0; i < in.size(); ++i) {
    if (i > 0) {
      const double ramp = std::min(kStepRampSeconds, 0.5 * (in[i] - in[i - 1]));
      const float before = float(in[i] - ramp);
      // Times are written as floats and must increase: a gap too short for a float between them gets no ramp.
      if (before > float(k.times.back()) && before < float(in[i])) {
        k.times.push_back(before);
        k.values.insert(k.values.end(), out.begin() + long((i - 1) * n), out.begin() + long(i * n));
      }
    }
    k.times.push_back(in[i]);
    k.values.insert(k.values.end(), out.begin() + long(i * n), out.begin() + long((i + 1) * n));
  }
  return k;
}

// CUBICSPLINE: the spec's Hermite curve (in-tangent, value, out-tangent per key) at equal steps.
Keys cubic_as_linear(const std::vector<double>& in, const std::vector<double>& out, size_t n, bool rotation) {
  Keys k;
  auto at = [&](size_t key, int part, size_t c) { return out[(3 * key + size_t(part)) * n + c]; };
  auto push = [&](double t, std::vector<double> v) {
    if (rotation) {
      double len = 0;
      for (double x : v) len += x * x;
      len = std::sqrt(len);
      if (len > 0)
        for (double& x : v) x /= len;
    }
    k.times.push_back(t);
    k.values.insert(k.values.end(), v.begin(), v.end());
  };
  for (size_t i = 0; i + 1 < in.size(); ++i) {
    const double dt = in[i + 1] - in[i];
    for (int s = 0; s < kCubicSegments; ++s) {
      const double u = double(s) / kCubicSegments, u2 = u * u, u3 = u2 * u;
      std::vector<double> v(n);
      for (size_t c = 0; c < n; ++c)
        v[c] = (2 * u3 - 3 * u2 + 1) * at(i, 1, c) + (u3 - 2 * u2 + u) * dt * at(i, 2, c) +
               (-2 * u3 + 3 * u2) * at(i + 1, 1, c) + (u3 - u2) * dt * at(i + 1, 0, c);
      // Steps too short for a float between them and both keys are left out (times must increase).
      if (s > 0 && !(float(in[i] + u * dt) > float(k.times.back()) && float(in[i] + u * dt) < float(in[i + 1])))
        continue;
      push(s == 0 ? in[i] : in[i] + u * dt, v);
    }
  }
  std::vector<double> last(n);
  for (size_t c = 0; c < n; ++c) last[c] = at(in.size() - 1, 1, c);
  push(in.back(), last);
  return k;
}

// A new float accessor of \p type holding \p values; its bounds when \p bounded (a sampler's input needs them).
size_t add_float_accessor(json& doc, const std::string& type, const std::vector<double>& values, size_t count,
                          bool bounded, GltfBytes& bytes) {
  json acc = {{"componentType", kFloat}, {"count", count}, {"type", type}};
  if (bounded) acc["min"] = json::array({0}), acc["max"] = json::array({0});
  array_of(doc, "accessors").push_back(acc);
  const size_t a = doc["accessors"].size() - 1;
  write_float_accessor(doc, a, values, bytes);
  return a;
}

}  // namespace

std::vector<std::string> linearize_samplers(json& doc, GltfBytes& bytes, const std::string& shown_as) {
  if (!doc.contains("animations") || !doc["animations"].is_array()) return {};
  size_t n_step = 0, n_cubic = 0;
  json& animations = doc["animations"];
  for (size_t a = 0; a < animations.size(); ++a) {
    json& anim = animations[a];
    if (!anim.is_object() || !anim.contains("samplers") || !anim["samplers"].is_array()) continue;
    json& samplers = anim["samplers"];
    for (size_t s = 0; s < samplers.size(); ++s) {
      json& sampler = samplers[s];
      const std::string interpolation = sampler.is_object() ? sampler.value("interpolation", "LINEAR") : "";
      if (interpolation != "STEP" && interpolation != "CUBICSPLINE") continue;
      const std::string what = shown_as + ": animation " + std::to_string(a) + " sampler " + std::to_string(s);
      const size_t n_acc = array_of(doc, "accessors").size();
      const size_t ia = index_in(sampler, "input", n_acc, what + " input"),
                   oa = index_in(sampler, "output", n_acc, what + " output");
      const std::vector<double> in = accessor_values(doc, ia, bytes, shown_as);
      const std::vector<double> out = accessor_values(doc, oa, bytes, shown_as);
      const bool cubic = interpolation == "CUBICSPLINE";
      const size_t per_key = cubic ? 3 * in.size() : in.size();
      if (in.empty() || out.empty() || out.size() % per_key != 0)
        throw IOError(what + " (" + interpolation + ") has " + std::to_string(out.size()) + " output values for " +
                      std::to_string(in.size()) + " keys");
      const size_t n = out.size() / per_key;
      // Said here in the file's own key numbers: the rewritten keys are numbered otherwise.
      for (size_t k = 0; k < in.size(); ++k)
        if (!std::isfinite(in[k]))
          throw IOError(what + " (" + interpolation + "): key " + std::to_string(k) + " has the time " +
                        std::to_string(in[k]));
      for (size_t i = 0; i < out.size(); ++i)
        if (!std::isfinite(out[i]))
          throw IOError(what + " (" + interpolation + "): key " + std::to_string(i / (out.size() / in.size())) +
                        " has the non-finite value " + std::to_string(out[i]));
      bool rotation = false;
      if (anim.contains("channels") && anim["channels"].is_array())
        for (const json& ch : anim["channels"])
          rotation |= ch.is_object() && ch.value("sampler", -1) == long(s) && ch.contains("target") &&
                      ch["target"].is_object() && ch["target"].value("path", "") == "rotation";
      const Keys keys = cubic ? cubic_as_linear(in, out, n, rotation && n == 4) : step_as_linear(in, out, n);
      const std::string out_type = doc["accessors"][oa].value("type", "SCALAR");
      if (out_type != "SCALAR" && component_count(out_type) != n)
        throw IOError(what + " (" + interpolation + ") has " + out_type + " outputs holding " + std::to_string(n) +
                      " values per key");
      const size_t out_count = out_type == "SCALAR" ? keys.values.size() : keys.times.size();
      sampler["input"] = add_float_accessor(doc, "SCALAR", keys.times, keys.times.size(), true, bytes);
      sampler["output"] = add_float_accessor(doc, out_type, keys.values, out_count, false, bytes);
      sampler["interpolation"] = "LINEAR";
      ++(cubic ? n_cubic : n_step);
    }
  }
  std::vector<std::string> notes;
  if (n_step)
    notes.push_back(std::to_string(n_step) + " STEP animation sampler" + (n_step > 1 ? "s" : "") +
                    " kept as LINEAR keys that switch within 1 ms before each key (assimp 5.2 would blend them)");
  if (n_cubic)
    notes.push_back(std::to_string(n_cubic) + " CUBICSPLINE animation sampler" + (n_cubic > 1 ? "s" : "") +
                    " kept as LINEAR keys on the curve, " + std::to_string(kCubicSegments) +
                    " per interval (assimp 5.2 would drop the tangents)");
  return notes;
}

}  // namespace OpenMeshSkinned::detail

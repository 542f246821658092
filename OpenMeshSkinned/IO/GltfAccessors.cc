#include "OpenMeshSkinned/IO/GltfAccessors.hh"

#include "OpenMeshSkinned/IO/GltfJson.hh"
#include "OpenMeshSkinned/IO/IOError.hh"

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>

namespace OpenMeshSkinned::detail {

using json = nlohmann::json;

size_t component_size(int type) {
  switch (type) {
    case kByte:
    case kUnsignedByte:
      return 1;
    case kShort:
    case kUnsignedShort:
      return 2;
    case kUnsignedInt:
    case kFloat:
      return 4;
    default:
      return 0;
  }
}

size_t component_count(const std::string& type) {
  static const std::map<std::string, size_t> n = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4},
                                                  {"MAT2", 4},   {"MAT3", 9}, {"MAT4", 16}};
  const auto it = n.find(type);
  return it == n.end() ? 0 : it->second;
}

double read_component(const char* p, int type, bool normalized) {
  auto get = [p](auto v) {
    std::memcpy(&v, p, sizeof v);
    return v;
  };
  switch (type) {
    case kByte: {
      const double v = get(int8_t());
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case kUnsignedByte: {
      const double v = get(uint8_t());
      return normalized ? v / 255.0 : v;
    }
    case kShort: {
      const double v = get(int16_t());
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case kUnsignedShort: {
      const double v = get(uint16_t());
      return normalized ? v / 65535.0 : v;
    }
    case kUnsignedInt: {
      const double v = get(uint32_t());
      return normalized ? v / 4294967295.0 : v;
    }
    default:
      return get(float());
  }
}

bool fits(size_t start, size_t count, size_t step, size_t elem, size_t size) {
  if (count == 0) return start <= size;
  if (start > size || elem > size - start) return false;
  return step == 0 || (count - 1) <= (size - start - elem) / step;
}

namespace {

// The sparse part's substitutions over \p out (\p count elements of \p n components of \p type).
void apply_sparse(json& doc, const json& sp, size_t count, size_t n, int type, bool normalized, GltfBytes& bytes,
                  const std::string& what, std::vector<double>& out) {
  const size_t cs = component_size(type);
  const size_t k = sp.value("count", size_t(0));
  if (!sp.contains("indices") || !sp.contains("values")) throw IOError(what + " has an incomplete sparse part");
  const json &si = sp["indices"], &sv = sp["values"];
  const int itype = si.value("componentType", 0);
  const size_t ics = component_size(itype);
  const std::string idata = bytes.view_bytes(index_in(si, "bufferView", doc["bufferViews"].size(), what));
  const std::string vdata = bytes.view_bytes(index_in(sv, "bufferView", doc["bufferViews"].size(), what));
  const size_t ioff = si.value("byteOffset", size_t(0)), voff = sv.value("byteOffset", size_t(0));
  if (ics == 0 || !fits(ioff, k, ics, ics, idata.size()) || !fits(voff, k, n * cs, n * cs, vdata.size()))
    throw IOError(what + ": its sparse part runs past its buffer views");
  for (size_t j = 0; j < k; ++j) {
    const auto i = size_t(read_component(idata.data() + ioff + j * ics, itype, false));
    if (i >= count) throw IOError(what + ": a sparse index is out of range");
    for (size_t c = 0; c < n; ++c)
      out[i * n + c] = read_component(vdata.data() + voff + (j * n + c) * cs, type, normalized);
  }
}

}  // namespace

std::vector<double> accessor_values(json& doc, size_t a, GltfBytes& bytes, const std::string& shown_as,
                                    bool as_stored) {
  const json& acc = doc["accessors"][a];
  const std::string what = shown_as + ": accessor " + std::to_string(a);
  const size_t n = component_count(acc.value("type", "")), count = acc.value("count", size_t(0));
  const int type = acc.value("componentType", 0);
  const size_t cs = component_size(type);
  if (n == 0 || cs == 0) throw IOError(what + " has an unknown type");
  const bool normalized = !as_stored && acc.value("normalized", false);
  if (count > (size_t(1) << 32))
    throw IOError(what + " claims " + std::to_string(count) + " elements, more than any buffer holds");
  std::vector<double> out(count * n, 0.0);
  if (acc.contains("bufferView")) {
    const size_t view = index_in(acc, "bufferView", doc["bufferViews"].size(), what);
    const std::string data = bytes.view_bytes(view);
    const size_t stride = doc["bufferViews"][view].value("byteStride", size_t(0));
    const size_t step = stride ? stride : n * cs, start = acc.value("byteOffset", size_t(0));
    if (!fits(start, count, step, n * cs, data.size())) throw IOError(what + " runs past its buffer view");
    for (size_t i = 0; i < count; ++i)
      for (size_t c = 0; c < n; ++c)
        out[i * n + c] = read_component(data.data() + start + i * step + c * cs, type, normalized);
  }
  if (acc.contains("sparse")) apply_sparse(doc, acc["sparse"], count, n, type, normalized, bytes, what, out);
  return out;
}

void point_accessor_at(json& accessor, size_t view, int component_type, size_t count) {
  accessor["bufferView"] = view;
  accessor.erase("byteOffset");
  accessor.erase("sparse");
  accessor["componentType"] = component_type;
  accessor["count"] = count;
}

void write_float_accessor(json& doc, size_t a, const std::vector<double>& values, GltfBytes& bytes) {
  json& acc = doc["accessors"][a];
  const size_t n = component_count(acc.value("type", ""));
  std::string data(values.size() * sizeof(float), '\0');
  std::vector<double> lo(n, std::numeric_limits<double>::infinity()), hi(n, -std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < values.size(); ++i) {
    const float f = float(values[i]);
    std::memcpy(data.data() + i * sizeof(float), &f, sizeof f);
    lo[i % n] = std::min(lo[i % n], double(f));
    hi[i % n] = std::max(hi[i % n], double(f));
  }
  point_accessor_at(acc, bytes.add_view(data), kFloat, acc.value("count", size_t(0)));
  acc.erase("normalized");
  if (acc.contains("min") || acc.contains("max")) {
    if (values.empty()) {
      acc.erase("min");
      acc.erase("max");
    } else {
      acc["min"] = lo;
      acc["max"] = hi;
    }
  }
}

}  // namespace OpenMeshSkinned::detail

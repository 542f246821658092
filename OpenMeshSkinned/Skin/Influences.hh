#pragma once
/** \file Influences.hh
 *  Per-vertex bone influences: a small fixed-capacity array kept sorted by weight, heaviest first.
 *
 *  Fixed capacity (not std::vector) because the decimater touches these millions of times: a vertex's
 *  skin must be copied and compared without allocating.
 */

#include <algorithm>
#include <array>
#include <cstdint>

namespace OpenMeshSkinned {

/// One bone influence: a joint index into the skeleton and its blend weight. Packed to 12 bytes (not 16):
/// every vertex of the original and of the mesh being decimated holds eight, the memory of a large
/// character's skins. x86-64 and ARMv8 load a double at 4-byte alignment without a fault.
struct __attribute__((packed, aligned(4))) JointWeight {
  int32_t joint = -1;
  double weight = 0.0;
};
static_assert(sizeof(JointWeight) == 12, "JointWeight is packed");

/** Up to kCapacity influences, sorted by weight (descending), ties by joint index (ascending).
 *  Weights of a valid skin are >= 0 and sum to 1 (see validate_skin()). */
class Influences {
public:
  static constexpr int kCapacity = 8;

  Influences() = default;

  /// A vertex moved rigidly by one joint.
  static Influences rigid(int32_t joint) {
    Influences inf;
    inf.data_[0] = {joint, 1.0};
    inf.size_ = 1;
    return inf;
  }

  int size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const JointWeight& operator[](int i) const { return data_[i]; }
  const JointWeight* begin() const { return data_.data(); }
  const JointWeight* end() const { return data_.data() + size_; }

  void clear() { size_ = 0; }

  /// Appends without sorting; returns false when full. Call sort() after a batch of pushes.
  bool push(int32_t joint, double weight) {
    if (size_ >= kCapacity) return false;
    data_[size_++] = {joint, weight};
    return true;
  }

  /// Adds \p weight to \p joint's entry, creating it if absent; returns false when full.
  bool add(int32_t joint, double weight) {
    for (int i = 0; i < size_; ++i)
      if (data_[i].joint == joint) {
        data_[i].weight += weight;
        return true;
      }
    return push(joint, weight);
  }

  void sort() {
    std::sort(data_.begin(), data_.begin() + size_, [](const JointWeight& a, const JointWeight& b) {
      return a.weight != b.weight ? a.weight > b.weight : a.joint < b.joint;
    });
  }

  double sum() const {
    double s = 0.0;
    for (int i = 0; i < size_; ++i) s += data_[i].weight;
    return s;
  }

  /// Weight of \p joint (0 when it has no influence).
  double weight_of(int32_t joint) const {
    for (int i = 0; i < size_; ++i)
      if (data_[i].joint == joint) return data_[i].weight;
    return 0.0;
  }

  /** The cap rule, the one place it is written: keeps the heaviest \p n influences (ties: lower joint
   *  index first) and rescales them to sum to one. */
  void keep_heaviest(int n) {
    sort();
    if (size_ > n) size_ = std::max(n, 0);
    normalize();
  }

  /** As add(), but when full the lightest influence gives way to a heavier new one (and a lighter new
   *  one is not kept). Returns false when some weight was dropped either way. */
  bool add_keeping_heaviest(int32_t joint, double weight) {
    if (add(joint, weight)) return true;
    sort();
    if (weight > data_[size_ - 1].weight) data_[size_ - 1] = {joint, weight};
    return false;
  }

  void normalize() {
    const double s = sum();
    if (s > 0.0)
      for (int i = 0; i < size_; ++i) data_[i].weight /= s;
  }

  bool operator==(const Influences& o) const {
    if (size_ != o.size_) return false;
    for (int i = 0; i < size_; ++i)
      if (data_[i].joint != o.data_[i].joint || data_[i].weight != o.data_[i].weight) return false;
    return true;
  }
  bool operator!=(const Influences& o) const { return !(*this == o); }

private:
  std::array<JointWeight, kCapacity> data_{};
  int32_t size_ = 0;
};

/** A blend of several skins being summed (a merged or subdivided vertex), wider than Influences so that
 *  no joint is lost before the cap: keep_heaviest() then applies the cap rule. */
class InfluenceSum {
public:
  static constexpr int kCapacity = 8 * Influences::kCapacity;

  /// Adds \p c times every weight of \p inf.
  void add(const Influences& inf, double c) {
    for (const JointWeight& jw : inf) add(jw.joint, c * jw.weight);
  }
  /// Adds \p weight to \p joint; when full, the lightest entry gives way to a heavier new joint.
  void add(int32_t joint, double weight) {
    for (int i = 0; i < size_; ++i)
      if (data_[i].joint == joint) {
        data_[i].weight += weight;
        return;
      }
    if (size_ < kCapacity) {
      data_[size_++] = {joint, weight};
      return;
    }
    auto lightest = std::min_element(data_.begin(), data_.end(),
                                     [](const JointWeight& a, const JointWeight& b) { return a.weight < b.weight; });
    if (weight > lightest->weight) *lightest = {joint, weight};
  }

  /// The heaviest \p n positive weights (at most Influences::kCapacity), renormalised: Influences::keep_heaviest.
  Influences keep_heaviest(int n) const {
    std::array<JointWeight, kCapacity> v = data_;
    const int m = std::min(std::max(n, 0), Influences::kCapacity);
    std::partial_sort(v.begin(), v.begin() + std::min(m, size_), v.begin() + size_, heavier);
    Influences out;
    for (int i = 0; i < size_ && out.size() < m; ++i)
      if (v[i].weight > 0.0) out.push(v[i].joint, v[i].weight);
    out.keep_heaviest(m);
    return out;
  }

private:
  static bool heavier(const JointWeight& a, const JointWeight& b) {
    return a.weight != b.weight ? a.weight > b.weight : a.joint < b.joint;
  }
  std::array<JointWeight, kCapacity> data_{};
  int size_ = 0;
};

}  // namespace OpenMeshSkinned

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

/// One bone influence: a joint index into the skeleton and its blend weight.
struct JointWeight {
  int32_t joint = -1;
  double weight = 0.0;
};

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

  /// Keeps the heaviest \p n influences (after sort()) and rescales them to sum to one.
  void truncate_and_normalize(int n) {
    sort();
    if (size_ > n) size_ = n;
    normalize();
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

}  // namespace OpenMeshSkinned

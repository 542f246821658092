#pragma once
/** \file ThreadFill.hh
 *  Large tables first written on every thread.
 *
 *  A fresh table of tens of megabytes costs more in the kernel than in the program: each page is zeroed
 *  when first written, and in a virtual machine the host backs it then too. std::vector::assign() takes
 *  all those faults on the calling thread (measured in bench/README.md, "The tool end to end against
 *  gltfpack"). A ThreadTable allocates without writing, and fill_on_threads() writes each thread's own
 *  contiguous range, so the faults are taken side by side.
 */

#include "OpenMeshSkinned/Solver/Threads.hh"

#include <algorithm>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace OpenMeshSkinned {

/// An allocator whose value-less construction leaves a trivial element unwritten (default-initialised).
template <typename T>
struct DefaultInitAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// A vector whose resize() does not write the new elements when their default constructor writes nothing
/// (plain structs without initialisers, Eigen's fixed-size vectors): fill them with fill_on_threads().
template <typename T>
using ThreadTable = std::vector<T, DefaultInitAllocator<T>>;

/// Makes \p table \p n copies of \p value, each of \p threads threads writing its own contiguous share
/// (what was in the table before is discarded; its memory is released first, so the fill takes fresh pages
/// on every thread rather than the old ones on the caller's).
template <typename T>
void fill_on_threads(ThreadTable<T>& table, size_t n, const T& value, int threads) {
  static_assert(std::is_trivially_destructible_v<T>, "a table of plain numbers");
  ThreadTable<T>().swap(table);
  table.resize(n);
  T* data = table.data();
  const size_t k = static_cast<size_t>(std::max(threads, 1));
  run_on_threads(threads, [&](int t) { std::fill(data + n * t / k, data + n * (t + 1) / k, value); });
}

}  // namespace OpenMeshSkinned

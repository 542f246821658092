#pragma once
/** \file HugePages.hh
 *  Transparent huge pages for a whole program that decimates large meshes.
 *
 *  A decimation reads the mesh's arrays, the per-pose quadrics and the edge cache in mesh order, which
 *  is no order in memory: with 4 KB pages most of those reads miss the TLB, and in a virtual machine each
 *  4 KB page also costs a fault when first written. glibc (2.35 and later) puts its heap on transparent
 *  huge pages when the tunable glibc.malloc.hugetlb=1 is set, and Debian's kernels give them on such a
 *  request; but glibc reads its tunables only when a process starts. relaunch_with_huge_pages() therefore
 *  starts the program again, once, with the tunable added (bench/README.md, "Huge pages": faster in a
 *  virtual machine, the same output).
 *
 *  It also asks for one malloc arena for all threads (glibc.malloc.arena_max=1): with each thread's own
 *  arena, the threads that start late (the final fit's, the evaluation's) took fresh pages of their own
 *  and runs on two threads spent more time in the kernel (bench/README.md, "Huge pages"); with huge
 *  pages off, one arena made no difference.
 */

#include <string>

namespace OpenMeshSkinned {

/// The GLIBC_TUNABLES value that adds glibc.malloc.hugetlb=1 and glibc.malloc.arena_max=1 to \p current
/// (null when unset), the second unless \p current names an arena_max of its own; empty when \p current
/// already names glibc.malloc.hugetlb, whatever its value: the user's choice stands.
std::string tunables_with_huge_pages(const char* current);

/** Call first thing in main(), before any thread starts or anything is written: on Linux with glibc,
 *  unless GLIBC_TUNABLES already names glibc.malloc.hugetlb, adds it and executes the program again
 *  (/proc/self/exe) with the same \p argv. Returns when there is nothing to do, or when that fails (the
 *  program then goes on as it is). GLIBC_TUNABLES=glibc.malloc.hugetlb=0 turns it off. */
void relaunch_with_huge_pages(char** argv);

}  // namespace OpenMeshSkinned

#include "OpenMeshSkinned/Platform/HugePages.hh"

#include <unistd.h>

#include <cstdlib>

namespace OpenMeshSkinned {

std::string tunables_with_huge_pages(const char* current) {
  const std::string given = current ? current : "";
  if (given.find("glibc.malloc.hugetlb") != std::string::npos) return {};
  std::string out = given;
  auto add = [&](const char* tunable) { out += (out.empty() ? "" : ":") + std::string(tunable); };
  add("glibc.malloc.hugetlb=1");
  if (given.find("glibc.malloc.arena_max") == std::string::npos) add("glibc.malloc.arena_max=1");
  return out;
}

void relaunch_with_huge_pages(char** argv) {
#if defined(__linux__) && defined(__GLIBC__)
  if (!argv || !argv[0]) return;
  const std::string value = tunables_with_huge_pages(std::getenv("GLIBC_TUNABLES"));
  if (value.empty()) return;
  // Set before the exec, so the relaunched program finds it and does not relaunch again.
  if (::setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
  ::execv("/proc/self/exe", argv);
#else
  (void)argv;
#endif
}

}  // namespace OpenMeshSkinned

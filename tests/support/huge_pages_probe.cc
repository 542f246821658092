// Relaunches itself with huge pages (Platform/HugePages.hh), then prints its pid, its GLIBC_TUNABLES and its
// arguments, one per line: test_huge_pages checks what the relaunched program sees.
#include <OpenMeshSkinned/Platform/HugePages.hh>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  std::printf("before %d\n", static_cast<int>(::getpid()));
  std::fflush(stdout);
  OpenMeshSkinned::relaunch_with_huge_pages(argv);
  const char* t = std::getenv("GLIBC_TUNABLES");
  std::printf("tunables %s\n", t ? t : "(unset)");
  for (int i = 1; i < argc; ++i) std::printf("arg %s\n", argv[i]);
  return 3;
}

// Transparent huge pages for a whole program (Platform/HugePages.hh).
#include <OpenMeshSkinned/Platform/HugePages.hh>

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

using OpenMeshSkinned::tunables_with_huge_pages;

TEST(HugePages, TheTunablesAreAddedToWhatTheUserSet) {
  EXPECT_EQ(tunables_with_huge_pages(nullptr), "glibc.malloc.hugetlb=1:glibc.malloc.arena_max=1");
  EXPECT_EQ(tunables_with_huge_pages(""), "glibc.malloc.hugetlb=1:glibc.malloc.arena_max=1");
  EXPECT_EQ(tunables_with_huge_pages("glibc.malloc.check=3"),
            "glibc.malloc.check=3:glibc.malloc.hugetlb=1:glibc.malloc.arena_max=1");
}

TEST(HugePages, TheUsersOwnArenaCountStands) {
  EXPECT_EQ(tunables_with_huge_pages("glibc.malloc.arena_max=4"), "glibc.malloc.arena_max=4:glibc.malloc.hugetlb=1");
}

TEST(HugePages, TheUsersOwnHugePageSettingStands) {
  EXPECT_EQ(tunables_with_huge_pages("glibc.malloc.hugetlb=0"), "");
  EXPECT_EQ(tunables_with_huge_pages("glibc.malloc.check=3:glibc.malloc.hugetlb=2"), "");
}

namespace {

struct Probe {
  std::string out;
  int status = -1;
};

// Runs the probe under \p env (a shell prefix) with two arguments, one with a space.
Probe run_probe(const std::string& env) {
  const std::string cmd = env + " '" OMSK_HUGE_PAGES_PROBE "' first 'second arg' 2>&1";
  Probe p;
  FILE* f = ::popen(cmd.c_str(), "r");
  if (!f) return p;
  std::array<char, 256> buf;
  while (std::fgets(buf.data(), buf.size(), f)) p.out += buf.data();
  p.status = ::pclose(f);
  return p;
}

}  // namespace

TEST(HugePages, TheProgramRunsAgainOnceWithTheTunableAndItsArguments) {
  const Probe p = run_probe("env -u GLIBC_TUNABLES");
  ASSERT_TRUE(WIFEXITED(p.status)) << p.out;
  EXPECT_EQ(WEXITSTATUS(p.status), 3) << p.out;
  // Started twice (the relaunch keeps the process), the rest printed once, by the relaunched program.
  size_t befores = 0;
  for (size_t at = p.out.find("before "); at != std::string::npos; at = p.out.find("before ", at + 1)) ++befores;
  ASSERT_EQ(befores, 2u) << p.out;
  // An exec, not a child: the same process both times.
  const size_t first = p.out.find("before "), second = p.out.find("before ", first + 1);
  EXPECT_EQ(p.out.substr(first, p.out.find('\n', first) - first),
            p.out.substr(second, p.out.find('\n', second) - second))
      << p.out;
  EXPECT_NE(p.out.find("tunables glibc.malloc.hugetlb=1:glibc.malloc.arena_max=1\narg first\narg second arg\n"),
            std::string::npos)
      << p.out;
}

TEST(HugePages, NoRelaunchWhenTheUserChose) {
  const Probe p = run_probe("env GLIBC_TUNABLES=glibc.malloc.hugetlb=0");
  ASSERT_TRUE(WIFEXITED(p.status)) << p.out;
  EXPECT_EQ(WEXITSTATUS(p.status), 3) << p.out;
  EXPECT_EQ(p.out.find("before ", p.out.find("before ") + 1), std::string::npos) << p.out;
  EXPECT_NE(p.out.find("tunables glibc.malloc.hugetlb=0\n"), std::string::npos) << p.out;
}

// A program in a process of its own (OpenMeshSkinned/Lod/ChildProcess.hh): how it ended, what it printed,
// and what it does not inherit.
#include "run_command.hh"

#include <OpenMeshSkinned/IO/IOError.hh>
#include <OpenMeshSkinned/Lod/ChildProcess.hh>

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

namespace fs = std::filesystem;
using OpenMeshSkinned::ChildProcess;

namespace {

std::string read(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), {});
}

}  // namespace

TEST(ChildProcess, GivesTheExitCodeAndTheOutputAndErrorsInTheLog) {
  const fs::path d = omsk_test::scratch_dir("child", "exit");
  ChildProcess c({"/bin/sh", "-c", "echo out; echo err >&2; read x || echo no-input; exit 7"}, (d / "log").string());
  c.wait();
  EXPECT_TRUE(c.exit_status().exited);
  EXPECT_EQ(c.exit_status().code, 7);
  EXPECT_EQ(read(d / "log"), "out\nerr\nno-input\n");
  EXPECT_GT(c.seconds(), 0.0);
  EXPECT_TRUE(c.poll());
}

TEST(ChildProcess, GivesTheSignalThatEndedItEvenWhenTheCallerBlocksOrIgnoresIt) {
  const fs::path d = omsk_test::scratch_dir("child", "signal");
  sigset_t term, old;
  sigemptyset(&term);
  sigaddset(&term, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &term, &old);
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGPIPE, &ignore, &previous);
  ChildProcess t({"/bin/sh", "-c", "kill -TERM $$; sleep 5"}, (d / "log").string());
  t.wait();
  ChildProcess p({"/bin/sh", "-c", "kill -PIPE $$; sleep 5"}, (d / "log2").string());
  p.wait();
  sigaction(SIGPIPE, &previous, nullptr);
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  EXPECT_FALSE(t.exit_status().exited);
  EXPECT_EQ(t.exit_status().signal, SIGTERM);
  EXPECT_EQ(p.exit_status().signal, SIGPIPE);
}

TEST(ChildProcess, KillStopsItAndWhatItStarted) {
  const fs::path d = omsk_test::scratch_dir("child", "kill");
  ChildProcess c({"/bin/sh", "-c", "sleep 30 & echo $! > '" + (d / "pid").string() + "'; wait"}, (d / "log").string());
  while (!fs::exists(d / "pid") || read(d / "pid").empty()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_FALSE(c.poll());
  c.kill();
  EXPECT_EQ(c.exit_status().signal, SIGKILL);
  const pid_t grandchild = std::stoi(read(d / "pid"));
  bool gone = false;
  for (int i = 0; i < 100 && !gone; ++i) {
    gone = ::kill(grandchild, 0) != 0;
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(gone);
}

TEST(ChildProcess, AProgramThatCannotRunOrALogThatCannotBeWrittenThrows) {
  const fs::path d = omsk_test::scratch_dir("child", "throw");
  EXPECT_THROW(ChildProcess({(d / "none").string()}, (d / "log").string()), OpenMeshSkinned::IOError);
  EXPECT_THROW(ChildProcess({"/bin/true"}, (d / "no/such/dir/log").string()), OpenMeshSkinned::IOError);
  EXPECT_THROW(ChildProcess({}, (d / "log").string()), OpenMeshSkinned::IOError);
}

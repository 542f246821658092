#pragma once
/** \file ChildProcess.hh
 *  A program run in a process of its own, for work that must not take the caller down when it crashes,
 *  runs out of memory or hangs: its output goes to a file, it leads a process group of its own (so that
 *  it and whatever it starts stop together), and it is killed when the thread that started it ends.
 */

#include <sys/types.h>

#include <chrono>
#include <string>
#include <vector>

namespace OpenMeshSkinned {

/// How a child ended.
struct ChildExit {
  bool exited = false;  ///< it returned from main or called exit(): code holds the status
  int code = -1;
  int signal = 0;  ///< the signal that ended it, when !exited
};

class ChildProcess {
public:
  /** Starts \p argv[0] (a path: no search of PATH) with \p argv, reading /dev/null, its output and errors
   *  written to \p log (created or emptied). The caller's signal mask and ignored signals are not passed
   *  on, and no core file is written when it crashes. Throws IOError when the log cannot be opened or the
   *  program cannot be run. */
  ChildProcess(const std::vector<std::string>& argv, const std::string& log);
  /// A child still running is killed (with its process group) and reaped.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  /// Whether it has ended; reaps it when it has. Does not wait.
  bool poll();
  /// Waits until it ends.
  void wait();
  /// Kills its process group (SIGKILL) and reaps it.
  void kill();
  /// How it ended, once poll() returned true (or after wait() or kill()).
  const ChildExit& exit_status() const { return exit_; }
  /// Seconds since it was started, up to its end once it has ended.
  double seconds() const;

private:
  void reaped(int status);
  pid_t pid_ = -1;
  bool running_ = false;
  ChildExit exit_;
  std::chrono::steady_clock::time_point start_, end_;
};

}  // namespace OpenMeshSkinned

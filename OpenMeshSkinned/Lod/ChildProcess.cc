#include "OpenMeshSkinned/Lod/ChildProcess.hh"

#include "OpenMeshSkinned/IO/IOError.hh"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace OpenMeshSkinned {

namespace {

// Between fork() and exec only async-signal-safe calls: the caller may have other threads, whose locks
// the child inherits held.
[[noreturn]] void exec_child(char* const* argv, int in_fd, int log_fd, int report_fd, pid_t parent) {
  ::setpgid(0, 0);
  // Ends with the thread that started it (a batch interrupted by Ctrl-C, a worker that dies): a child
  // outliving it would go on writing files nobody waits for.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(127);  // it ended before the line above
  ::dup2(in_fd, STDIN_FILENO);
  ::dup2(log_fd, STDOUT_FILENO);
  ::dup2(log_fd, STDERR_FILENO);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  for (int sig : {SIGPIPE, SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGCHLD}) ::sigaction(sig, &dfl, nullptr);
  const rlimit core{0, 0};
  ::setrlimit(RLIMIT_CORE, &core);  // a crash is an expected outcome here, reported by its signal
  ::execv(argv[0], argv);
  const int e = errno;
  [[maybe_unused]] const ssize_t n = ::write(report_fd, &e, sizeof e);
  ::_exit(127);
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv, const std::string& log) {
  if (argv.empty()) throw IOError("no program to run");
  std::vector<std::string> args = argv;
  std::vector<char*> cargv;
  for (std::string& a : args) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  const int log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log_fd < 0) throw IOError(log + ": cannot be written: " + std::strerror(errno));
  const int in_fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  int report[2] = {-1, -1};  // the child's errno when exec fails; closed by a successful exec
  if (in_fd < 0 || ::pipe2(report, O_CLOEXEC) != 0) {
    const std::string why = std::strerror(errno);
    for (int fd : {log_fd, in_fd, report[0], report[1]})
      if (fd >= 0) ::close(fd);
    throw IOError(argv[0] + ": cannot be started: " + why);
  }
  const pid_t parent = ::getpid();
  start_ = std::chrono::steady_clock::now();
  pid_ = ::fork();
  if (pid_ == 0) exec_child(cargv.data(), in_fd, log_fd, report[1], parent);
  const int fork_errno = errno;
  ::close(log_fd);
  ::close(in_fd);
  ::close(report[1]);
  if (pid_ < 0) {
    ::close(report[0]);
    throw IOError(argv[0] + ": cannot be started: " + std::strerror(fork_errno));
  }
  ::setpgid(pid_, pid_);  // also here, so that kill() reaches the group even before the child has run
  running_ = true;
  int child_errno = 0;
  ssize_t n;
  do n = ::read(report[0], &child_errno, sizeof child_errno);
  while (n < 0 && errno == EINTR);
  ::close(report[0]);
  if (n == sizeof child_errno) {
    wait();
    throw IOError(argv[0] + ": cannot be run: " + std::strerror(child_errno));
  }
}

ChildProcess::~ChildProcess() {
  if (running_) kill();
}

void ChildProcess::reaped(int status) {
  running_ = false;
  end_ = std::chrono::steady_clock::now();
  exit_.exited = WIFEXITED(status);
  exit_.code = exit_.exited ? WEXITSTATUS(status) : -1;
  exit_.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
}

bool ChildProcess::poll() {
  if (!running_) return true;
  int status = 0;
  const pid_t r = ::waitpid(pid_, &status, WNOHANG);
  if (r == pid_) reaped(status);
  if (r < 0 && errno == ECHILD) {  // reaped by someone else (a SIGCHLD handler of the host)
    running_ = false;
    end_ = std::chrono::steady_clock::now();
  }
  return !running_;
}

void ChildProcess::wait() {
  while (running_) {
    int status = 0;
    const pid_t r = ::waitpid(pid_, &status, 0);
    if (r == pid_)
      reaped(status);
    else if (r < 0 && errno != EINTR) {
      running_ = false;
      end_ = std::chrono::steady_clock::now();
    }
  }
}

void ChildProcess::kill() {
  if (!running_) return;
  ::kill(-pid_, SIGKILL);
  ::kill(pid_, SIGKILL);  // in case it had left the group
  wait();
}

double ChildProcess::seconds() const {
  const auto end = running_ ? std::chrono::steady_clock::now() : end_;
  return std::chrono::duration<double>(end - start_).count();
}

}  // namespace OpenMeshSkinned

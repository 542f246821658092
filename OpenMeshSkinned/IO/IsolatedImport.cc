#include "OpenMeshSkinned/IO/IsolatedImport.hh"

#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/IO/ImportArchive.hh"
#include "OpenMeshSkinned/IO/PrintableText.hh"

#include <assimp/importerdesc.h>
#include <assimp/Importer.hpp>

#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <new>
#include <sstream>

namespace OpenMeshSkinned {
namespace {

// The child's verdict, first byte of what it sends.
constexpr char kOk = 'K', kError = 'E', kOutOfMemory = 'M';
// The child sends its result's size in this many bytes (native order: the same machine) before the result.
constexpr size_t kSizeBytes = sizeof(uint64_t);
// What the child prints is kept up to this size (a reader in a loop may print without end).
constexpr size_t kMaxReaderOutput = 64 << 10;

bool write_all(int fd, const std::string& s) {
  size_t done = 0;
  while (done < s.size()) {
    const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += size_t(n);
  }
  return true;
}

std::string format_name(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  Assimp::Importer importer;
  const size_t i = importer.GetImporterIndex(ext.c_str());
  if (const aiImporterDesc* d = i == size_t(-1) ? nullptr : importer.GetImporterInfo(i)) return d->mName;
  return ext.empty() ? std::string("unknown") : "." + ext;
}

bool looks_like_oom(const std::string& message) {
  return message.find("bad_alloc") != std::string::npos || message.find("out of memory") != std::string::npos;
}

[[noreturn]] void run_child(int fd, int err_fd, const std::string& path, const ImportOptions& opt, FileReader read) {
  // What the reader or the C library prints (glibc's "double free or corruption" above a crash) goes to
  // the parent, which shows it only when asked: the user sees one line.
  ::dup2(err_fd, STDERR_FILENO);
  ::close(err_fd);
  rlimit core{0, 0};
  ::setrlimit(RLIMIT_CORE, &core);  // a crash of the reader is expected on bad files: no core dumps
  // The reader's crash must end the child by its signal, which the parent reports in one line: a handler
  // inherited from the host application (or a sanitizer's, which prints a report and exits) must not
  // turn it into something else.
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) ::signal(sig, SIG_DFL);
#if !defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer reserves terabytes of shadow address space, so the limit only applies without it.
  if (opt.memory_limit_mb > 0) {
    const rlim_t bytes = rlim_t(opt.memory_limit_mb) << 20;
    rlimit as{bytes, bytes};
    ::setrlimit(RLIMIT_AS, &as);
  }
#endif
  std::string out;
  try {
    SkinnedMesh mesh;
    const ImportReport rep = read(path, mesh, opt);
    out.assign(1, kOk);
    append_import(mesh, rep, out);
  } catch (const std::bad_alloc&) {
    out = std::string(1, kOutOfMemory);
  } catch (const std::length_error&) {  // a size read from the file beyond what a container can hold
    out = std::string(1, kOutOfMemory);
  } catch (const std::exception& e) {
    out = (looks_like_oom(e.what()) ? kOutOfMemory : kError) + std::string(e.what());
  }
  // Its size first: the parent takes the whole in one allocation (a string grown by doubling copies the
  // archive, tens of MB for a large character, into fresh memory at every step).
  char size[kSizeBytes];
  const uint64_t n = out.size();
  std::memcpy(size, &n, kSizeBytes);
  const bool sent = write_all(fd, std::string(size, kSizeBytes)) && write_all(fd, out);
  _exit(sent ? 0 : 1);  // _exit: none of the parent's atexit handlers or buffers run twice
}

// Reads what the child sends into \p bytes and what it prints into \p said (up to kMaxReaderOutput), until it
// closes its end or \p time_limit_seconds (0: none) pass; true when the time ran out. The child announces its
// result's size first: \p complete when the two agree. \p bytes takes it in one allocation when it is at most
// \p most bytes (a reader gone wrong may have spoilt the size).
bool read_child(int out_fd, int err_fd, double time_limit_seconds, size_t most, std::string& bytes, bool& complete,
                std::string& said) {
  std::string size_bytes;
  uint64_t announced = 0;
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(time_limit_seconds);
  bool timed_out = false, err_open = true;
  char buf[1 << 16];
  for (;;) {
    int wait_ms = -1;
    if (time_limit_seconds > 0) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      if (left <= 0) {
        timed_out = true;
        break;
      }
      wait_ms = int(std::min<long long>(left, 1 << 30));
    }
    pollfd p[2] = {{out_fd, POLLIN, 0}, {err_open ? err_fd : -1, POLLIN, 0}};
    const int r = ::poll(p, 2, wait_ms);
    if (r < 0 && errno == EINTR) continue;
    if (r == 0) continue;  // re-check the deadline
    if (p[1].revents) {
      const ssize_t n = ::read(err_fd, buf, sizeof buf);
      if (n > 0 && said.size() < kMaxReaderOutput)
        said.append(buf, std::min(size_t(n), kMaxReaderOutput - said.size()));
      if (n == 0 || (n < 0 && errno != EINTR)) err_open = false;
    }
    if (!p[0].revents) continue;
    const ssize_t n = ::read(out_fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of file: the child is done (or dead)
    size_t used = 0;
    if (size_bytes.size() < kSizeBytes) {
      used = std::min(kSizeBytes - size_bytes.size(), size_t(n));
      size_bytes.append(buf, used);
      if (size_bytes.size() == kSizeBytes) {
        std::memcpy(&announced, size_bytes.data(), kSizeBytes);
        if (announced <= most) {
          try {
            bytes.reserve(size_t(announced));
          } catch (const std::exception&) {  // no room in one piece: it grows as it comes
          }
        }
      }
    }
    bytes.append(buf + used, size_t(n) - used);
  }
  complete = size_bytes.size() == kSizeBytes && bytes.size() == announced;
  return timed_out;
}

// Throws the one-line error the child's end calls for: a time-out, running out of memory, a crash, no or an
// unreadable result, or the reader's own error.
void check_verdict(const std::string& path, const ImportOptions& opt, bool timed_out, int status,
                   const std::string& bytes, bool complete) {
  auto fail = [&path](const std::string& what) { return IOError(path + ": " + what); };
  const std::string format = " (format: " + format_name(path) + ")";
  if (timed_out)
    throw fail("the reader took longer than " + std::to_string(int(opt.time_limit_seconds)) + " s reading it" + format);
  const std::string limit = opt.memory_limit_mb ? " (limit " + std::to_string(opt.memory_limit_mb) + " MB)" : "";
  if (!bytes.empty() && bytes[0] == kOutOfMemory)
    throw fail("the reader ran out of memory" + limit + " reading it" + format);
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = sigabbrev_np(sig);
    throw fail(std::string("the reader crashed (SIG") + (name ? name : std::to_string(sig).c_str()) + ") reading it" +
               format);
  }
  if (bytes.empty() || !complete || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw fail("the reader stopped without a result reading it" + format);
  if (bytes[0] == kError) throw IOError(bytes.substr(1));  // the child's message already names the file
  if (bytes[0] != kOk) throw fail("the reader sent an unreadable result" + format);
}

}  // namespace

ImportReport import_isolated(const std::string& path, SkinnedMesh& mesh, const ImportOptions& opt, FileReader read) {
  auto fail = [&path](const std::string& what) { return IOError(path + ": " + what); };
  // The child's scratch files (a repaired or decoded glTF copy) go into a folder of the parent's, removed
  // here whatever becomes of the child: a killed or crashed child cleans up nothing itself.
  std::string scratch = (std::filesystem::temp_directory_path() / "omsk-read-XXXXXX").string();
  if (!::mkdtemp(scratch.data())) throw fail(std::string("cannot start the isolated reader: ") + std::strerror(errno));
  struct RemoveScratch {
    std::string dir;
    ~RemoveScratch() {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    }
  } remove_scratch{scratch};
  int fds[2], err[2];
  if (::pipe(fds) != 0) throw fail(std::string("cannot start the isolated reader: ") + std::strerror(errno));
  if (::pipe(err) != 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw fail(std::string("cannot start the isolated reader: ") + std::strerror(errno));
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    for (int f : {fds[0], fds[1], err[0], err[1]}) ::close(f);
    throw fail(std::string("cannot start the isolated reader: ") + std::strerror(errno));
  }
  if (pid == 0) {
    ::close(fds[0]);
    ::close(err[0]);
    ::setenv("TMPDIR", scratch.c_str(), 1);
    run_child(fds[1], err[1], path, opt, read);
  }
  ::close(fds[1]);
  ::close(err[1]);

  std::string bytes, said;
  bool complete = false;
  // What the child could have held under its memory limit (without one, what a large character's takes).
  const size_t most = opt.memory_limit_mb > 0 ? opt.memory_limit_mb << 20 : size_t(1) << 32;
  const bool timed_out = read_child(fds[0], err[0], opt.time_limit_seconds, most, bytes, complete, said);
  ::close(fds[0]);
  ::close(err[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }

  if (opt.show_reader_output && !said.empty()) {
    std::istringstream lines(said);
    for (std::string line; std::getline(lines, line);) std::cerr << "reader: " << printable_line(line, 1000) << "\n";
  }
  check_verdict(path, opt, timed_out, status, bytes, complete);
  ImportReport rep;
  load_import(bytes.data() + 1, bytes.size() - 1, mesh, rep);
  return rep;
}

}  // namespace OpenMeshSkinned

#pragma once
// Runs a command line in a folder and collects its exit code and combined output.
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace omsk_test {

struct CommandResult {
  int code;
  std::string out;
};

inline CommandResult run_command(const std::string& exe, const std::string& args, const std::filesystem::path& cwd) {
  const std::string cmd = "cd '" + cwd.string() + "' && '" + exe + "' " + args + " 2>&1";
  CommandResult r{0, ""};
  FILE* p = popen(cmd.c_str(), "r");
  char buf[512];
  while (fgets(buf, sizeof buf, p)) r.out += buf;
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace omsk_test

#pragma once
// Runs a command line in a folder and collects its exit code and combined output; reads the JSON it wrote.
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
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

/// A fresh, empty folder TMP/omsk_<kind>_<pid>/<name> for one test's files.
inline std::filesystem::path scratch_dir(const std::string& kind, const std::string& name) {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / ("omsk_" + kind + "_" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

/// The JSON file at \p path (a report the tool wrote); throws when it is missing or not JSON.
inline nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  return nlohmann::json::parse(in);
}

}  // namespace omsk_test

#pragma once
// Runs the Khronos glTF validator (npm gltf-validator, installed by scripts/setup into tools/) on a file
// the tests wrote; a test fails on any error and sees the warnings in its log.

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <string>

namespace omsk_test {

struct ValidatorResult {
  int exit_code = -1;
  std::string output;
};

inline ValidatorResult run_validator(const std::string& file) {
  const std::string cmd = std::string("node '") + OMSK_VALIDATOR + "' '" + file + "' 2>&1";
  ValidatorResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  while (fgets(buf.data(), buf.size(), p)) r.output += buf.data();
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// The validator reports 0 errors for \p file.
inline void expect_valid_gltf(const std::string& file) {
  const ValidatorResult r = run_validator(file);
  EXPECT_EQ(r.exit_code, 0) << "glTF validator on " << file << " (run scripts/setup if it is missing):\n" << r.output;
}

}  // namespace omsk_test

#pragma once
// What both libFuzzer targets do first: the first byte picks the format (the file extension assimp
// dispatches on), the rest is the file, written into the process's own scratch folder.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

namespace omsk_fuzz {

inline constexpr const char* kExtensions[] = {".x",   ".md5mesh", ".fbx", ".gltf", ".glb",
                                              ".obj", ".dae",     ".ply", ".smd",  ".b3d"};

/// The scratch folder of this process (made once).
inline const std::string& scratch_dir() {
  static const std::string dir = [] {
    char tmpl[] = "/tmp/omsk-fuzz-XXXXXX";
    return std::string(mkdtemp(tmpl));
  }();
  return dir;
}

/// Writes the input as a file and returns its path; empty when the input is too short or cannot be written.
inline std::string write_input(const uint8_t* data, size_t size) {
  if (size < 2) return {};
  const size_t n_ext = sizeof kExtensions / sizeof kExtensions[0];
  const std::string path = scratch_dir() + "/input" + kExtensions[data[0] % n_ext];
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return {};
  std::fwrite(data + 1, 1, size - 1, f);
  std::fclose(f);
  return path;
}

}  // namespace omsk_fuzz

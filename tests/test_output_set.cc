// OutputSet: outputs never land on an input or on each other, and a run's files appear all together or not.
#include <OpenMeshSkinned/IO/OutputSet.hh>

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

namespace fs = std::filesystem;
using OpenMeshSkinned::IOError;
using OpenMeshSkinned::OutputSet;
using OpenMeshSkinned::PathConflict;

namespace {
fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("omsk_outset_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
void write(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }
std::string read(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}
size_t files_in(const fs::path& d) { return std::distance(fs::directory_iterator(d), fs::directory_iterator()); }
}  // namespace

TEST(OutputSet, RefusesTheInputByNameSymlinkAndHardLink) {
  const auto d = scratch("input");
  write(d / "in.glb", "input");
  fs::create_symlink(d / "in.glb", d / "sym.glb");
  fs::create_hard_link(d / "in.glb", d / "hard.glb");
  OutputSet out({(d / "in.glb").string()});
  EXPECT_THROW(out.add((d / "in.glb").string()), PathConflict);
  EXPECT_THROW(out.add((d / "sub" / ".." / "in.glb").string()), PathConflict);
  EXPECT_THROW(out.add((d / "sym.glb").string()), PathConflict);
  EXPECT_THROW(out.add((d / "hard.glb").string()), PathConflict);
  EXPECT_EQ(read(d / "in.glb"), "input");
}

TEST(OutputSet, RefusesTheSameOutputTwice) {
  const auto d = scratch("twice");
  OutputSet out;
  out.add((d / "a.glb").string());
  EXPECT_THROW(out.add((d / "a.glb").string()), PathConflict);
  EXPECT_THROW(out.add((d / "." / "a.glb").string()), PathConflict);
}

TEST(OutputSet, MissingFolderIsAnError) {
  OutputSet out;
  EXPECT_THROW(out.add("/nonexistent-omsk-folder/a.glb"), IOError);
}

TEST(OutputSet, CommitPutsEveryFileInPlaceAndReplacesOldOnes) {
  const auto d = scratch("commit");
  write(d / "b.json", "old");
  OutputSet out;
  const auto a = out.add((d / "a.glb").string());
  const auto b = out.add((d / "b.json").string());
  EXPECT_EQ(fs::path(a).extension(), ".glb");  // writers that go by the extension still work
  write(a, "A");
  write(b, "B");
  EXPECT_FALSE(fs::exists(d / "a.glb"));  // nothing visible before commit
  EXPECT_EQ(read(d / "b.json"), "old");
  out.commit();
  EXPECT_EQ(read(d / "a.glb"), "A");
  EXPECT_EQ(read(d / "b.json"), "B");
  EXPECT_EQ(files_in(d), 2u);  // no staging or backup file left
}

TEST(OutputSet, AFailedRunLeavesNothing) {
  const auto d = scratch("failed");
  write(d / "keep.glb", "previous run");
  {
    OutputSet out;
    write(out.add((d / "keep.glb").string()), "new");
    write(out.add((d / "lod2.glb").string()), "new");
    // destroyed without commit, as when a later LOD throws
  }
  EXPECT_EQ(read(d / "keep.glb"), "previous run");
  EXPECT_EQ(files_in(d), 1u);
}

TEST(OutputSet, CommitRefusesWhenAFileWasNotWritten) {
  const auto d = scratch("unwritten");
  {
    OutputSet out;
    write(out.add((d / "a.glb").string()), "A");
    out.add((d / "b.glb").string());
    EXPECT_THROW(out.commit(), IOError);
  }
  EXPECT_EQ(files_in(d), 0u);
}

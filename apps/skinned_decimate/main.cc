// skinned-decimate: LOD chains from skinned characters, judged in poses the decimater never saw.
#include "BatchCommand.hh"
#include "CommandLine.hh"
#include "Options.hh"
#include "Run.hh"

#include <OpenMeshSkinned/IO/PrintableText.hh>
#include <OpenMeshSkinned/Lod/LodOptions.hh>
#include <OpenMeshSkinned/Lod/LodPoseCount.hh>
#include <OpenMeshSkinned/Platform/HugePages.hh>

#include <CLI/CLI.hpp>

#include <iostream>
#include <new>

using namespace skinned_decimate;

int main(int argc, char** argv) {
  // Large characters decimate markedly faster with the heap on huge pages (see HugePages.hh).
  OpenMeshSkinned::relaunch_with_huge_pages(argv);
  CLI::App app{
      "skinned-decimate: LODs of an animated character (skinned, or animated without a skeleton) that stay right "
      "in poses never seen.\n"
      "With no INPUT, runs the papers' test characters (DeCoro's leg, Landreneau-Schaefer's column)."};
  Options opt;
  OptionWords words;
  declare_options(app, opt, words);
  const BatchCommand batch(app);  // skinned-decimate batch IN_DIR -o OUT_DIR [the options above]
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "skinned-decimate: " << e.what() << "\n";
    return 2;
  }
  finish_options(app, words, opt);
  // Messages quote names and bytes of the file: shown as one printable line each.
  try {
    return batch.parsed() ? batch.run(app, opt) : run(opt);
  } catch (const UsageError& e) {
    std::cerr << "skinned-decimate: " << OpenMeshSkinned::printable_line(e.what(), 1000) << "\n";
    return 2;
  } catch (const OpenMeshSkinned::LodOptionsError& e) {
    std::cerr << "skinned-decimate: " << OpenMeshSkinned::printable_line(e.what(), 1000) << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "skinned-decimate: out of memory while " << current_stage() << ": try fewer --poses (now "
              << (opt.poses > 0 ? std::to_string(opt.poses) : "the default: " + OpenMeshSkinned::lod_pose_count_rule())
              << ") or --threads, or set --max-memory MB to be stopped before it runs out\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "skinned-decimate: " << OpenMeshSkinned::printable_line(e.what(), 1000) << "\n";
    return 1;
  }
}

// Running the assets of a batch: one child process of the tool each, skipped when up to date.
#include "OpenMeshSkinned/Lod/Batch.hh"

#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/IO/ImportFrames.hh"
#include "OpenMeshSkinned/IO/OutputSet.hh"
#include "OpenMeshSkinned/IO/PrintableText.hh"
#include "OpenMeshSkinned/Lod/ChildProcess.hh"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#ifndef OMSK_VERSION
#error "OMSK_VERSION must be defined by the build"
#endif

namespace OpenMeshSkinned {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// How often running children are looked at: short against any asset, and next to no load.
constexpr auto kPollInterval = std::chrono::milliseconds(20);

std::string out_file(const BatchOptions& o, const std::string& name, const char* suffix) {
  return (fs::path(o.out_dir) / (name + suffix)).string();
}

json fingerprint(const BatchInput& in, const BatchOptions& o) {
  std::error_code ec;
  return {{"tool", batch_tool_version()},
          {"arguments", o.arguments},
          {"html", o.html},
          {"input", fs::weakly_canonical(fs::absolute(in.path), ec).string()}};
}

// The input's files as the tool reads them: a numbered OBJ/PLY/STL/OFF file brings its whole sequence.
fs::file_time_type input_time(const BatchInput& in, const BatchOptions& o) {
  std::error_code ec;
  std::vector<std::string> files{in.path};
  std::string ext = fs::path(in.path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool no_sequence = std::count(o.arguments.begin(), o.arguments.end(), "--no-sequence") > 0;
  if (!no_sequence && (ext == ".obj" || ext == ".ply" || ext == ".stl" || ext == ".off"))
    files = numbered_sequence(in.path);
  fs::file_time_type newest = fs::file_time_type::min();
  for (const std::string& f : files) newest = std::max(newest, fs::last_write_time(f, ec));
  return newest;
}

// The sidecar keeps the result's paths relative to the output folder, so that a batch resumed from
// another working folder, or with the output folder moved, still finds its files.
void map_paths(AssetResult& r, const std::function<std::string(const std::string&)>& f) {
  for (std::string* p : {&r.log, &r.report, &r.page})
    if (!p->empty()) *p = f(*p);
  for (LodResult& l : r.lods)
    if (!l.file.empty()) l.file = f(l.file);
}

std::optional<AssetResult> up_to_date(const BatchInput& in, const BatchOptions& o) {
  std::ifstream f(out_file(o, in.name, ".batch.json"));
  if (!f) return std::nullopt;
  const json side = json::parse(f, nullptr, false);
  if (side.is_discarded() || !side.is_object() || side.value("fingerprint", json()) != fingerprint(in, o) ||
      !side.contains("result"))
    return std::nullopt;
  AssetResult r;
  try {
    r = parse_asset_result(side["result"].dump());
  } catch (const IOError&) {
    return std::nullopt;
  }
  if (r.status != AssetStatus::Ok) return std::nullopt;
  r.input = in.path;
  map_paths(r, [&o](const std::string& p) { return (fs::path(o.out_dir) / p).string(); });
  std::vector<std::string> files{r.report};
  if (o.html) files.push_back(r.page);
  for (const LodResult& l : r.lods) files.push_back(l.file);
  const fs::file_time_type input = input_time(in, o);
  std::error_code ec;
  for (const std::string& file : files) {
    const fs::file_time_type t = fs::last_write_time(file, ec);
    if (file.empty() || ec || !(t > input)) return std::nullopt;
  }
  r.status = AssetStatus::Skipped;
  r.reason = "up to date: made by this tool with the same options, after the input last changed";
  return r;
}

// The tool's own message: its last "skinned-decimate: ..." line that is not a warning.
std::string error_line(const std::string& log) {
  std::ifstream f(log, std::ios::binary);
  f.seekg(0, std::ios::end);
  const std::streamoff size = f.tellg();
  f.seekg(std::max<std::streamoff>(0, size - (1 << 16)));  // the end is where the error is
  std::string line, found;
  const std::string prefix = "skinned-decimate: ";
  while (std::getline(f, line))
    if (line.compare(0, prefix.size(), prefix) == 0 && line.compare(prefix.size(), 8, "warning:") != 0)
      found = line.substr(prefix.size());
  if (found.compare(0, 7, "error: ") == 0) found.erase(0, 7);
  return printable_line(found, 500);
}

// A killed child leaves its staged outputs (OutputSet: ".NAME.omsk-PID-N.ext") behind.
void remove_staged(const BatchOptions& o, const std::string& name, pid_t pid) {
  const fs::path base = fs::path(o.out_dir) / name;
  const std::string prefix = "." + base.filename().string(), token = ".omsk-" + std::to_string(pid) + "-";
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(base.parent_path(), ec)) {
    const std::string n = e.path().filename().string();
    if (n.compare(0, prefix.size(), prefix) == 0 && n.find(token) != std::string::npos) fs::remove(e.path(), ec);
  }
}

void read_lods(const json& run, AssetResult& r) {
  r.triangles_in = run.value("triangles_in", size_t(0));
  for (const json& l : run["lods"]) {
    LodResult lod;
    lod.ratio = l.value("ratio", 0.0);
    lod.triangles = l.value("faces", size_t(0));
    if (l.contains("heldout_rms") && l["heldout_rms"].is_number()) lod.heldout_rms = l["heldout_rms"];
    if (l.contains("heldout_hausdorff") && l["heldout_hausdorff"].is_number())
      lod.heldout_hausdorff = l["heldout_hausdorff"];
    lod.file = l.value("file", std::string());
    r.lods.push_back(lod);
  }
}

bool has_lods(const json& run) { return run.is_object() && run.contains("lods") && run["lods"].is_array(); }

void read_report(AssetResult& r) {
  std::ifstream f(r.report);
  const json rep = json::parse(f, nullptr, false);
  if (!f || rep.is_discarded() || !rep.is_object()) throw IOError("its report " + r.report + " cannot be read");
  // With --compare the report holds every method's run; the files are the chosen method's.
  const json* run = &rep;
  if (rep.contains("runs") && rep["runs"].is_array())
    for (const json& candidate : rep["runs"])
      if (has_lods(candidate) && !candidate["lods"].empty() && candidate["lods"][0].is_object() &&
          candidate["lods"][0].contains("file"))
        run = &candidate;
  if (!has_lods(*run)) throw IOError("its report " + r.report + " has no LODs");
  try {
    read_lods(*run, r);
  } catch (const json::exception& e) {
    throw IOError("its report " + r.report + " is not the tool's: " + e.what());
  }
}

void write_sidecar(const BatchInput& in, const BatchOptions& o, const AssetResult& r) {
  const std::string path = out_file(o, in.name, ".batch.json");
  AssetResult relative = r;
  const fs::path dir = fs::absolute(o.out_dir).lexically_normal();
  map_paths(relative, [&dir](const std::string& p) {
    return fs::absolute(p).lexically_normal().lexically_relative(dir).generic_string();
  });
  OutputSet out({in.path});
  std::ofstream f(out.add(path));
  f << json{{"fingerprint", fingerprint(in, o)}, {"result", json::parse(asset_result_json(relative))}}.dump(2) << "\n";
  f.close();
  if (!f) throw IOError(path + ": cannot be written");
  out.commit();
}

struct Started {
  BatchInput input;
  AssetResult result;
  std::unique_ptr<ChildProcess> child;  // none when skipped
};

Started start(const BatchInput& in, const BatchOptions& o) {
  Started s{in, {}, nullptr};
  AssetResult& r = s.result;
  if (!o.force)
    if (auto done = up_to_date(in, o)) {
      r = *done;
      return s;
    }
  r.input = in.path;
  r.name = in.name;
  r.log = out_file(o, in.name, ".log");
  r.report = out_file(o, in.name, ".report.json");
  if (o.html) r.page = out_file(o, in.name, ".html");
  std::error_code ec;
  fs::create_directories(fs::path(r.log).parent_path(), ec);
  if (ec) throw IOError(fs::path(r.log).parent_path().string() + ": cannot be made: " + ec.message());
  std::vector<std::string> argv{o.executable};
  argv.insert(argv.end(), o.arguments.begin(), o.arguments.end());
  for (const std::string& a : {std::string("-o"), out_file(o, in.name, ".glb"), std::string("--report"), r.report})
    argv.push_back(a);
  if (o.html) argv.insert(argv.end(), {"--html", r.page});
  argv.insert(argv.end(), {"--", in.path});  // an input named like an option stays the input
  s.child = std::make_unique<ChildProcess>(argv, r.log);
  return s;
}

enum class Stop { None, TimedOut, Cancelled };

AssetResult finish(Started& s, const BatchOptions& o, Stop stop) {
  AssetResult r = std::move(s.result);
  if (!s.child) return r;
  ChildProcess& c = *s.child;
  if (stop != Stop::None) c.kill();
  r.seconds = c.seconds();
  const ChildExit& e = c.exit_status();
  if (stop == Stop::Cancelled) {
    r.reason = "cancelled";
  } else if (stop == Stop::TimedOut) {
    std::ostringstream os;
    os << "timed out after " << o.asset_time_limit << " s";
    r.reason = os.str();
  } else if (!e.exited && e.signal > 0) {
    r.reason = "crashed (signal " + std::to_string(e.signal) + ": " + ::strsignal(e.signal) + ")";
  } else if (!e.exited) {
    r.reason = "ended, but its exit status was taken by another part of this process";
  } else if (e.code != 0) {
    r.reason = error_line(r.log);
    if (r.reason.empty())
      r.reason = "exited with code " + std::to_string(e.code) + " without a message (see " + r.log + ")";
  } else {
    try {
      read_report(r);
      std::vector<std::string> files{r.page};
      for (const LodResult& l : r.lods) files.push_back(l.file);
      std::error_code ec;
      for (const std::string& f : files)
        if (!f.empty() && !fs::is_regular_file(f, ec)) throw IOError("it exited without an error but wrote no " + f);
      r.status = AssetStatus::Ok;
    } catch (const IOError& err) {
      r.reason = err.what();
      r.lods.clear();
    }
  }
  if (r.status == AssetStatus::Failed) r.report = r.page = "";  // not written by this run: none to link
  if (!e.exited) remove_staged(o, r.name, c.pid());
  if (stop != Stop::Cancelled) write_sidecar(s.input, o, r);
  return r;
}

bool over_time(const ChildProcess& c, const BatchOptions& o) {
  return o.asset_time_limit > 0.0 && c.seconds() > o.asset_time_limit;
}

}  // namespace

std::string batch_tool_version() { return std::string("skinned-decimate ") + OMSK_VERSION; }

std::string progress_line(const BatchProgress& p) {
  return "batch: " + std::to_string(p.done) + "/" + std::to_string(p.total) + " done, " + std::to_string(p.failed) +
         " failed, " + std::to_string(p.skipped) + " skipped";
}

AssetResult run_asset(const BatchInput& input, const BatchOptions& options) {
  Started s = start(input, options);
  if (!s.child) return s.result;
  while (!s.child->poll()) {
    if (over_time(*s.child, options)) return finish(s, options, Stop::TimedOut);
    std::this_thread::sleep_for(kPollInterval);
  }
  return finish(s, options, Stop::None);
}

std::vector<AssetResult> run_batch(const std::vector<BatchInput>& inputs, const BatchOptions& options,
                                   const std::function<bool(const BatchProgress&)>& progress) {
  std::set<std::string> names;
  for (const BatchInput& in : inputs)
    if (!names.insert(in.name).second) throw IOError(in.path + ": another input has the name " + in.name);
  const size_t jobs = size_t(std::max(1, options.jobs));
  std::vector<AssetResult> results(inputs.size());
  std::vector<std::pair<size_t, Started>> running;
  BatchProgress p;
  p.total = inputs.size();
  bool cancelled = false;
  auto finished = [&](size_t i, AssetResult r) {
    results[i] = std::move(r);
    ++p.done;
    p.failed += results[i].status == AssetStatus::Failed;
    p.skipped += results[i].status == AssetStatus::Skipped;
    p.last = &results[i];
    if (progress && !cancelled && !progress(p)) cancelled = true;
  };
  size_t next = 0;
  while (!cancelled && (next < inputs.size() || !running.empty())) {
    while (!cancelled && next < inputs.size() && running.size() < jobs) {
      Started s = start(inputs[next], options);
      if (s.child)
        running.emplace_back(next, std::move(s));
      else
        finished(next, std::move(s.result));
      ++next;
    }
    bool any = false;
    for (size_t k = 0; k < running.size();) {
      Started& s = running[k].second;
      const bool ended = s.child->poll();
      if (ended || over_time(*s.child, options)) {
        const size_t i = running[k].first;
        AssetResult r = finish(s, options, ended ? Stop::None : Stop::TimedOut);
        running.erase(running.begin() + std::ptrdiff_t(k));
        finished(i, std::move(r));
        any = true;
      } else {
        ++k;
      }
    }
    if (!any && !running.empty()) std::this_thread::sleep_for(kPollInterval);
  }
  for (auto& [i, s] : running) results[i] = finish(s, options, Stop::Cancelled);
  for (; next < inputs.size(); ++next) {
    results[next].input = inputs[next].path;
    results[next].name = inputs[next].name;
    results[next].reason = "cancelled";
  }
  return results;
}

}  // namespace OpenMeshSkinned

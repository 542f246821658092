// A batch's results as JSON, and its summary: summary.json and the index page.
#include "OpenMeshSkinned/IO/IOError.hh"
#include "OpenMeshSkinned/IO/OutputSet.hh"
#include "OpenMeshSkinned/Lod/Batch.hh"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace OpenMeshSkinned {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double number_or_nan(const json& v) { return v.is_number() ? v.get<double>() : std::nan(""); }

json to_json(const AssetResult& r) {
  json lods = json::array();
  for (const LodResult& l : r.lods)
    lods.push_back({{"ratio", l.ratio},
                    {"triangles", l.triangles},
                    {"heldout_rms", number_or_null(l.heldout_rms)},
                    {"heldout_hausdorff", number_or_null(l.heldout_hausdorff)},
                    {"file", l.file}});
  return {{"input", r.input},   {"name", r.name},       {"status", status_name(r.status)},
          {"reason", r.reason}, {"seconds", r.seconds}, {"triangles_in", r.triangles_in},
          {"lods", lods},       {"log", r.log},         {"report", r.report},
          {"page", r.page}};
}

// A path of the batch as seen from the output folder, where the summary is.
std::string from_out_dir(const std::string& path, const std::string& out_dir) {
  if (path.empty()) return path;
  return fs::absolute(path)
      .lexically_normal()
      .lexically_relative(fs::absolute(out_dir).lexically_normal())
      .generic_string();
}

void write_file(const std::string& staged, const std::string& final_path, const std::string& text) {
  std::ofstream f(staged, std::ios::binary);
  f << text;
  f.close();
  if (!f) throw IOError(final_path + ": cannot be written");
}

std::string html_escape(const std::string& s) {
  std::string o;
  for (char c : s) switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      default:
        o += c;
    }
  return o;
}

// A relative link: each byte outside the unreserved set (and '/') percent-encoded, so that a name
// with a space, '#' or '?' still points at its file.
std::string url(const std::string& rel) {
  std::string o;
  char buf[4];
  for (unsigned char c : rel) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
      o += char(c);
    } else {
      std::snprintf(buf, sizeof buf, "%%%02X", c);
      o += buf;
    }
  }
  return html_escape(o);
}

std::string fixed(double v, int prec) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(prec);
  os << v;
  return os.str();
}

std::string error_text(double v) { return std::isfinite(v) ? fixed(v, 4) + "%" : "-"; }

std::string command_line(const std::vector<std::string>& args) {
  std::string s;
  for (const std::string& a : args) s += (s.empty() ? "" : " ") + a;
  return s;
}

std::string index_page(const json& summary) {
  size_t columns = 0;
  for (const json& r : summary["results"]) columns = std::max(columns, r["lods"].size());
  std::ostringstream h;
  h << "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>skinned-decimate batch: "
    << summary["assets"].get<size_t>() << " assets</title>\n<style>\n"
    << "body{font:14px system-ui,sans-serif;margin:1.5em;color:#222}table{border-collapse:collapse}\n"
    << "th,td{border:1px solid #ccc;padding:.3em .6em;text-align:left;vertical-align:top}\n"
    << "td.n{text-align:right;font-variant-numeric:tabular-nums}tr.failed td{background:#fde8e8}\n"
    << "tr.skipped td{color:#555}td.reason{color:#a00}code{font-size:90%}\n</style>\n</head>\n<body>\n"
    << "<h1>Batch: " << summary["assets"].get<size_t>() << " assets</h1>\n<p id=\"totals\">"
    << summary["ok"].get<size_t>() << " ok, " << summary["failed"].get<size_t>() << " failed, "
    << summary["skipped"].get<size_t>() << " skipped (up to date). " << html_escape(summary["tool"].get<std::string>())
    << ", options per asset: <code>" << html_escape(command_line(summary["arguments"].get<std::vector<std::string>>()))
    << "</code>. Errors are measured in held-out frames, in % of the rest-pose bounding-box diagonal.</p>\n"
    << "<table>\n<thead><tr><th>asset</th><th>status</th><th>triangles in</th>";
  for (size_t i = 0; i < columns; ++i) h << "<th>LOD " << i + 1 << ": triangles, held-out RMS, Hausdorff</th>";
  h << "<th>seconds</th><th>files</th></tr></thead>\n<tbody>\n";
  for (const json& r : summary["results"]) {
    const std::string status = r["status"], page = r["page"], input = r["input"];
    h << "<tr class=\"" << status << "\" data-name=\"" << html_escape(r["name"]) << "\"><td>";
    if (!page.empty() && status != "failed")
      h << "<a href=\"" << url(page) << "\">" << html_escape(input) << "</a>";
    else
      h << html_escape(input);
    h << "</td><td>" << status << "</td>";
    if (status == "failed") {
      h << "<td class=\"reason\" colspan=\"" << columns + 1 << "\">" << html_escape(r["reason"]) << "</td>";
    } else {
      h << "<td class=\"n\">" << r["triangles_in"].get<size_t>() << "</td>";
      for (size_t i = 0; i < columns; ++i) {
        h << "<td class=\"n\">";
        if (i < r["lods"].size()) {
          const json& l = r["lods"][i];
          h << "<a href=\"" << url(l["file"]) << "\">" << l["triangles"].get<size_t>() << "</a>, "
            << error_text(number_or_nan(l["heldout_rms"])) << ", " << error_text(number_or_nan(l["heldout_hausdorff"]));
        }
        h << "</td>";
      }
    }
    h << "<td class=\"n\">" << fixed(r["seconds"].get<double>(), 2) << "</td><td>";
    if (status != "failed") h << "<a href=\"" << url(r["report"]) << "\">report</a> ";
    h << "<a href=\"" << url(r["log"]) << "\">log</a></td></tr>\n";
  }
  h << "</tbody>\n</table>\n</body>\n</html>\n";
  return h.str();
}

}  // namespace

const char* status_name(AssetStatus s) {
  switch (s) {
    case AssetStatus::Ok:
      return "ok";
    case AssetStatus::Skipped:
      return "skipped";
    case AssetStatus::Failed:
      break;
  }
  return "failed";
}

std::string asset_result_json(const AssetResult& result) { return to_json(result).dump(); }

AssetResult parse_asset_result(const std::string& text) {
  const json j = json::parse(text, nullptr, false);
  try {
    if (j.is_discarded() || !j.is_object()) throw IOError("not a JSON object");
    AssetResult r;
    r.input = j.at("input");
    r.name = j.at("name");
    const std::string s = j.at("status");
    if (s != "ok" && s != "failed" && s != "skipped") throw IOError("unknown status " + s);
    r.status = s == "ok" ? AssetStatus::Ok : s == "skipped" ? AssetStatus::Skipped : AssetStatus::Failed;
    r.reason = j.at("reason");
    r.seconds = j.at("seconds");
    r.triangles_in = j.at("triangles_in");
    for (const json& l : j.at("lods"))
      r.lods.push_back({l.at("ratio"), l.at("triangles"), number_or_nan(l.at("heldout_rms")),
                        number_or_nan(l.at("heldout_hausdorff")), l.at("file")});
    r.log = j.at("log");
    r.report = j.at("report");
    r.page = j.at("page");
    return r;
  } catch (const json::exception& e) {
    throw IOError(std::string("not a batch result: ") + e.what());
  } catch (const IOError& e) {
    throw IOError(std::string("not a batch result: ") + e.what());
  }
}

void write_summary(const std::vector<AssetResult>& results, const BatchOptions& options) {
  json list = json::array();
  size_t ok = 0, failed = 0, skipped = 0;
  std::vector<std::string> inputs;
  for (const AssetResult& r : results) {
    ok += r.status == AssetStatus::Ok;
    failed += r.status == AssetStatus::Failed;
    skipped += r.status == AssetStatus::Skipped;
    inputs.push_back(r.input);
    json j = to_json(r);
    for (const char* key : {"log", "report", "page"}) j[key] = from_out_dir(j[key], options.out_dir);
    for (json& l : j["lods"]) l["file"] = from_out_dir(l["file"], options.out_dir);
    list.push_back(j);
  }
  const json summary = {{"tool", batch_tool_version()},
                        {"arguments", options.arguments},
                        {"html", options.html},
                        {"assets", results.size()},
                        {"ok", ok},
                        {"failed", failed},
                        {"skipped", skipped},
                        {"units", "percent of the rest-pose bounding-box diagonal"},
                        {"results", list}};
  const std::string json_path = (fs::path(options.out_dir) / "summary.json").string();
  const std::string html_path = (fs::path(options.out_dir) / "index.html").string();
  OutputSet out(inputs);
  const std::string json_staged = out.add(json_path), html_staged = out.add(html_path);
  write_file(json_staged, json_path, summary.dump(2) + "\n");
  write_file(html_staged, html_path, index_page(summary));
  out.commit();
}

}  // namespace OpenMeshSkinned

// The report page (--html) and its contact sheet (--preview), checked in a real browser (Debian's chromium
// through playwright-core, tests/browser/check-report.mjs): what a technical artist relies on when looking.
#include "fixtures.hh"
#include "gltf_spec.hh"
#include "run_command.hh"
#include "validate.hh"

#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace tinygltf {
std::string base64_decode(std::string const& s);  // exported by Debian's libtinygltf
}

namespace {
const std::string wuson = std::string("'") + OMSK_TEST_MODELS + "/X/Testwuson.X'";

fs::path scratch(const std::string& name) { return omsk_test::scratch_dir("html", name); }
std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}
nlohmann::json page_data(const std::string& html) {
  const std::string open = "<script id=\"omsk-data\" type=\"application/json\">";
  const size_t a = html.find(open);
  if (a == std::string::npos) return {};
  const size_t b = html.find("</script>", a);
  std::string s = html.substr(a + open.size(), b - a - open.size());
  for (size_t i = 0; (i = s.find("<\\/", i)) != std::string::npos;) s.replace(i, 3, "</");
  return nlohmann::json::parse(s);
}
// Runs the browser checks; false (with a skip) when no browser can run here.
bool browser_check(const fs::path& page, int views) {
  const auto r = omsk_test::run_command("node",
                                        std::string("'") + OMSK_SOURCE_DIR + "/tests/browser/check-report.mjs' '" +
                                            page.string() + "' " + std::to_string(views),
                                        page.parent_path());
  if (r.code == 77) return false;
  EXPECT_EQ(r.code, 0) << r.out;
  return true;
}
}  // namespace

TEST(HtmlReport, TheEmbeddedPagePlaysInABrowserAndTheViewsCarryTheError) {
  const auto d = scratch("embed");
  const auto r = omsk_test::run_command(OMSK_CLI_EXE, wuson + " -o w.glb --lods 0.5,0.2 --html w.html --quiet", d);
  ASSERT_EQ(r.code, 0) << r.out;
  const std::string html = slurp(d / "w.html");
  const auto data = page_data(html);
  ASSERT_EQ(data["sections"].size(), 1u);
  const auto& views = data["sections"][0]["views"];
  ASSERT_EQ(views.size(), 3u);  // the original and two LODs
  EXPECT_EQ(views[0]["label"], "original");
  EXPECT_GT(data["sections"][0]["error_scale"].get<double>(), 0.0);
  for (size_t i = 0; i < views.size(); ++i) {
    EXPECT_GT(views[i]["joints"].get<int>(), 10);  // the table's animation columns
    EXPECT_GT(views[i]["keys"].get<int>(), 0);
    // Each view is a valid GLB; the LODs carry the per-vertex held-out error as "_ERROR".
    const fs::path glb = d / ("view" + std::to_string(i) + ".glb");
    std::ofstream(glb, std::ios::binary) << tinygltf::base64_decode(views[i]["glb"].get<std::string>());
    omsk_test::expect_valid_gltf(glb.string());
    tinygltf::Model m;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, glb.string())) << err;
    size_t n_error = 0;
    for (const auto& prim : m.meshes[0].primitives)
      if (prim.attributes.count("_ERROR")) n_error += m.accessors[prim.attributes.at("_ERROR")].count;
    if (i == 0) {
      EXPECT_EQ(n_error, 0u);
    } else {
      EXPECT_GT(n_error, 0u);
      const size_t target = size_t(std::llround((i == 1 ? 0.5 : 0.2) * 3732));
      EXPECT_LE(views[i]["triangles"].get<size_t>(), target);
      EXPECT_GE(views[i]["triangles"].get<size_t>() + 2, target);
      EXPECT_GT(views[i]["rms"].get<double>(), 0.0);
    }
  }
  // The LOD files themselves do not carry the page's attribute.
  tinygltf::Model lod;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&lod, &err, &warn, (d / "w_lod1.glb").string()));
  for (const auto& prim : lod.meshes[0].primitives) EXPECT_EQ(prim.attributes.count("_ERROR"), 0u);
  if (!browser_check(d / "w.html", 3)) GTEST_SKIP() << "no Chromium here: the browser checks did not run";
}

TEST(HtmlReport, AssetsBesideThePageWorkToo) {
  const auto d = scratch("beside");
  const auto r = omsk_test::run_command(OMSK_CLI_EXE,
                                        wuson + " -o w.glb --ratio 0.3 --html w.html --html-assets beside --quiet", d);
  ASSERT_EQ(r.code, 0) << r.out;
  const auto data = page_data(slurp(d / "w.html"));
  for (const auto& v : data["sections"][0]["views"]) {
    EXPECT_FALSE(v.contains("glb"));
    EXPECT_TRUE(v.contains("asset"));
  }
  ASSERT_TRUE(fs::exists(d / "w.assets.js"));
  EXPECT_LT(fs::file_size(d / "w.html"), fs::file_size(d / "w.assets.js"));
  if (!browser_check(d / "w.html", 2)) GTEST_SKIP() << "no Chromium here: the browser checks did not run";
}

// A Mixamo-like character: its root rotated and scaled to centimetres, the skinned mesh under a node whose
// transform the spec ignores, and a rest pose away from where the clips play (the joints the clips move
// rest a diagonal off). The browser check frames every view whole at times over the clip.
TEST(HtmlReport, ARotatedScaledRootIsFramedWholeOverTheClip) {
  const auto d = scratch("rotated");
  tinygltf::Model m = omsk_fixtures::testwuson(d.string());
  const double diag = omsk_spec::diagonal(omsk_spec::pose(m, -1, 0.0));
  std::set<int> moved;
  for (const auto& c : m.animations[0].channels)
    if (c.target_path == "translation") moved.insert(c.target_node);
  ASSERT_FALSE(moved.empty());
  for (int n : moved) {
    auto& t = m.nodes[n].translation;
    if (t.empty()) t = {0.0, 0.0, 0.0};
    t[1] += diag;
  }
  omsk_fixtures::wrap_under_rotated_root(m);
  omsk_spec::save_glb(m, (d / "rot.glb").string());
  const auto r = omsk_test::run_command(OMSK_CLI_EXE, "rot.glb -o r.glb --ratio 0.5 --html r.html --quiet", d);
  ASSERT_EQ(r.code, 0) << r.out;
  if (!browser_check(d / "r.html", 2)) GTEST_SKIP() << "no Chromium here: the browser checks did not run";
}

TEST(HtmlReport, ThePreviewIsAContactSheetOfViewsByHeldOutFrames) {
  const auto d = scratch("preview");
  if (!fs::exists("/usr/bin/chromium") && !getenv("OMSK_CHROMIUM")) GTEST_SKIP() << "no Chromium here";
  const auto r = omsk_test::run_command(OMSK_CLI_EXE, wuson + " -o w.glb --lods 0.5,0.2 --preview w.png --quiet", d);
  ASSERT_EQ(r.code, 0) << r.out;
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load((d / "w.png").c_str(), &w, &h, &n, 3);
  ASSERT_NE(px, nullptr);
  // Rows: the original and two LODs (200 px and an 18 px caption each); columns: four held-out frames, each
  // as the views look and as their error, of 200 px after a 170 px label column.
  EXPECT_EQ(w, 170 + 4 * 2 * 200);
  EXPECT_EQ(h, 3 * 218);
  std::set<int> colours;
  for (int i = 0; i < w * h; i += 7) colours.insert(px[3 * i] << 16 | px[3 * i + 1] << 8 | px[3 * i + 2]);
  stbi_image_free(px);
  EXPECT_GT(colours.size(), 500u) << "the contact sheet looks blank";
  EXPECT_FALSE(fs::exists(d / "w.html")) << "--preview alone writes no page";
}

TEST(HtmlReport, APreviewThatCannotRenderIsOneLineAndLeavesNoFile) {
  const auto d = scratch("nobrowser");
  const auto r = omsk_test::run_command("env",
                                        "OMSK_CHROMIUM=/nonexistent/chromium '" + std::string(OMSK_CLI_EXE) + "' " +
                                            wuson + " -o w.glb --ratio 0.5 --html w.html --preview w.png --quiet",
                                        d);
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("--preview: no Chromium at /nonexistent/chromium"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(d / "w.png"));
  EXPECT_FALSE(fs::exists(d / "w.html"));
  EXPECT_FALSE(fs::exists(d / "w.glb"));
}

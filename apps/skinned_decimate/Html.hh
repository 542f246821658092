#pragma once
// The report page (--html) and its contact sheet (--preview): the original and every LOD side by side in a
// self-contained page whose viewer (tools/viewer, three.js) is linked into the tool at build time.

#include "Options.hh"

#include <OpenMeshSkinned/Lod/LodReport.hh>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace skinned_decimate {

/// One character on the page: its original and LODs (GLBs carrying the per-vertex error), one clip list.
struct HtmlSection {
  std::string title;
  nlohmann::ordered_json views = nlohmann::ordered_json::array();    // label, numbers, base64 GLB
  nlohmann::ordered_json clips = nlohmann::ordered_json::array();    // name, duration
  nlohmann::ordered_json preview = nlohmann::ordered_json::array();  // held-out {clip, time}: the sheet's columns
  std::vector<float> errors;  // every view's per-vertex errors, for the colour scale
};

/// Adds \p mesh as a view: exported to GLB with \p vertex_error (% of the diagonal, empty for none).
void add_view(HtmlSection& section, const std::string& label, const Mesh& mesh, const OpenMeshSkinned::LodReport* lod,
              const std::vector<float>& vertex_error);

/// Whether this build carries the viewer (built with Node.js and the npm tools present).
bool have_viewer();

/** The page. \p assets_beside: the GLBs go to \p assets_path (a script beside the page, named by
 *  \p assets_name relative to it) instead of into the page. */
std::string html_page(const std::string& title, const std::vector<HtmlSection>& sections, bool assets_beside,
                      const std::string& assets_name, std::string* assets_script);

/** Renders \p page_path's contact sheet (rows: views, columns: the sections' preview times) to \p png_path
 *  with headless Chromium (tools/viewer/preview.mjs). Throws with one line when it cannot. */
void render_preview(const std::string& page_path, const std::string& png_path);

}  // namespace skinned_decimate

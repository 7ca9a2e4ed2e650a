#pragma once
/// The data the report viewer (report/viewer.js) shows, as one JSON object embedded in
/// report.html. Arrays of numbers are base64 strings of little-endian typed arrays
/// ("f32:" float32, "u32:" uint32 prefixes), which keeps large meshes compact:
///
///   title                 string
///   body, garment         {positions: f32 n×3 (m), indices: u32 m×3} (body null if empty);
///                         garment.normals: f32 n×3, outward, optional
///   pinned                [garment vertex] held on the body
///   colorings[]           {field, label, unit, colormap, lo, hi (the colour range: 1st–99th
///                          percentile unless fixed), data_min, data_max, range_rule
///                          ("percentiles" | "fixed"), include_zero, values: f32 per garment
///                          face (scaled), lut: 256×3 sRGB bytes (continuous maps) or
///                          categories: [{value, label, color: [r,g,b] bytes}],
///                          negative_color: [r,g,b] bytes for values < 0 (lift-off), optional}
///   missing_colorings[]   labels of requested colourings whose field the fit lacks
///   pieces[]              {name, rest: f32 n×2 (m), triangles: u32 t×3, faces: u32 t
///                          (garment face of each triangle), boundary: [vertex], grain: [x,y],
///                          initial_outline: f32 n×2 (m), optional: before optimization,
///                          edges: [{kind: "seam" | "pinned", name, vertices: [vertex]}]}
///   summary               the run at a glance (FitView::summary), an object
///   fabric                the fabric, its curves and working points (fabric_outputs.hpp),
///                         or null
///   stats                 fit_statistics_json
///   parameters, history   as in FitView
///   pressure_regions[]    region_statistics_json of each FitView region (pressure_statistics.hpp)
///   measurements[]        the ease table, ease_table_json (report/ease_json.hpp)
///   pressure_histogram    {edges_mmhg, area_m2, warning_mmhg, share_above_warning, max_mmhg}
///                         of the whole garment, null without pressure
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tightfit/report/fit_colormap.hpp"
#include "tightfit/report/fit_view.hpp"

namespace tightfit {

/// Builds the viewer data of a valid view. Colourings whose field is absent are listed
/// in missing_colorings; InputError (naming `source`) for a colouring of a vector field.
nlohmann::json report_data_json(const FitView& view, const std::vector<FieldColoring>& colorings,
                                const std::string& title, const std::string& source);

}  // namespace tightfit

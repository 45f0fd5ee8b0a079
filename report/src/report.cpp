#include "saagen/report/report.hpp"

#include "saagen/error.hpp"
#include "saagen/io/input.hpp"
#include "saagen/io/output.hpp"
#include "saagen/reference/render/assets.hpp"
#include "saagen/report/comparison.hpp"
#include "saagen/report/findings.hpp"
#include "saagen/report/plots.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include <unistd.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_easy_font.h>
#include <stb/stb_image_write.h>

namespace saagen::report {
namespace {

namespace fs = std::filesystem;
using render::Variant;

std::string id_of(Variant variant) { return std::string(render::variant_id(variant)); }

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (double value : values) sum += value;
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}

// ---------------------------------------------------------------------------------------------
// Pictures. Display values: Reinhard x / (1 + x) (the tonemapped metric's operator), then the
// sRGB transfer function. Difference maps: the tonemapped difference variant - ground truth,
// red where the variant is brighter, blue where darker, full colour at |d| >= 0.25.

constexpr double difference_full_scale = 0.25;

std::uint8_t to_byte(double value) { return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255.0)); }

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

Rgb display(double radiance) {
  const std::uint8_t v = to_byte(render::display_value(radiance));
  return {v, v, v};
}

Rgb difference_colour(double radiance, double reference) {
  const double d = (render::tonemap(radiance) - render::tonemap(reference)) / difference_full_scale;
  const double m = render::srgb_encode(std::min(std::fabs(d), 1.0));
  return d >= 0.0 ? Rgb{to_byte(m), 0, 0} : Rgb{0, 0, to_byte(m)};
}

// Images of 256 px and more are shown at half size (2x2 box) to keep the report light.
int display_scale(const render::Image& image) { return image.width >= 256 ? 2 : 1; }

double box(const render::Image& image, int x, int y, int scale) {
  double sum = 0.0;
  for (int dy = 0; dy < scale; ++dy)
    for (int dx = 0; dx < scale; ++dx) sum += image.at(x * scale + dx, y * scale + dy);
  return sum / (scale * scale);
}

std::uint32_t crc32(std::string_view bytes) {
  std::uint32_t crc = 0xffffffffu;
  for (const char c : bytes) {
    crc ^= static_cast<unsigned char>(c);
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void put_be32(std::string& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((value >> shift) & 0xffu);
}

// The PNG with a tEXt chunk `keyword`=`text` after its IHDR chunk (8-byte signature, then IHDR:
// length 13, type, data, CRC = 25 bytes): how report images carry saagen's output tag.
std::string with_text_chunk(const std::string& png, std::string_view keyword, std::string_view text) {
  constexpr std::size_t after_ihdr = 8 + 25;
  std::string chunk = "tEXt";
  chunk.append(keyword).append(1, '\0').append(text);
  std::string out = png.substr(0, after_ihdr);
  put_be32(out, static_cast<std::uint32_t>(chunk.size() - 4));
  out += chunk;
  put_be32(out, crc32(chunk));
  out += png.substr(after_ihdr);
  return out;
}

// Column labels drawn into the sheet itself (so a PNG shared alone still says what it shows):
// stb_easy_font builds each glyph from axis-aligned quads, filled here at integer pixels. A
// label wraps after its '-', ':' and ' ' separators to fit the tile; kLabelLines lines at most.
constexpr int kLabelLineHeight = 11, kLabelLines = 4;

std::vector<std::string> wrap_label(const std::string& label, int max_width) {
  std::vector<std::string> lines{""};
  std::string token;
  auto width_of = [](std::string text) { return stb_easy_font_width(text.data()); };
  auto flush = [&]() {
    if (!lines.back().empty() && width_of(lines.back() + token) > max_width) lines.push_back("");
    lines.back() += token;
    token.clear();
  };
  for (char c : label) {
    token += c;
    if (c == '-' || c == ':' || c == ' ') flush();
  }
  flush();
  return lines;
}

void draw_text(std::vector<std::uint8_t>& pixels, int image_width, int image_height, int x, int y, const std::string& text) {
  struct Vertex {
    float x, y, z;
    unsigned char colour[4];
  };
  std::vector<Vertex> vertices(4 * 600);
  std::string buffer = text;
  unsigned char white[4] = {255, 255, 255, 255};
  const int quads = stb_easy_font_print(static_cast<float>(x), static_cast<float>(y), buffer.data(), white, vertices.data(),
                                        static_cast<int>(vertices.size() * sizeof(Vertex)));
  for (int q = 0; q < quads; ++q) {
    const Vertex& a = vertices[4 * q];
    const Vertex& c = vertices[4 * q + 2];
    for (int py = static_cast<int>(a.y); py < static_cast<int>(c.y); ++py)
      for (int px = static_cast<int>(a.x); px < static_cast<int>(c.x); ++px) {
        if (px < 0 || py < 0 || px >= image_width || py >= image_height) continue;
        const std::size_t index = (static_cast<std::size_t>(py) * image_width + px) * 3;
        pixels[index] = pixels[index + 1] = pixels[index + 2] = 255;
      }
  }
}

// A labelled image (PNG tile) beside the ground truth.
struct Tile {
  std::string label;
  const render::Image* image;
};

// One sheet (PNG bytes): a label band, then row 0 the ground truth and each tile, row 1 an empty
// cell then the difference maps; a 2-pixel grey gutter between tiles.
std::string grid_png(const render::Image& reference, const std::vector<Tile>& tiles) {
  const int scale = display_scale(reference);
  const int tile_w = reference.width / scale, tile_h = reference.height / scale, gutter = 2;
  const int band = kLabelLines * kLabelLineHeight + 4;
  const int columns = 1 + static_cast<int>(tiles.size());
  const int width = columns * tile_w + (columns - 1) * gutter, height = band + 2 * tile_h + gutter;
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width) * height * 3, 96);
  for (std::size_t i = 0; i < static_cast<std::size_t>(width) * band * 3; ++i) pixels[i] = 32;
  const auto put = [&](int column, int row, int x, int y, Rgb colour) {
    const std::size_t index = (static_cast<std::size_t>(band + row * (tile_h + gutter) + y) * width + column * (tile_w + gutter) + x) * 3;
    pixels[index] = colour.r, pixels[index + 1] = colour.g, pixels[index + 2] = colour.b;
  };
  const auto label = [&](int column, const std::string& text) {
    const std::vector<std::string> lines = wrap_label(text, tile_w - 4);
    for (std::size_t l = 0; l < lines.size() && l < kLabelLines; ++l)
      draw_text(pixels, width, height, column * (tile_w + gutter) + 2, 2 + static_cast<int>(l) * kLabelLineHeight, lines[l]);
  };
  label(0, "ground truth");
  for (std::size_t k = 0; k < tiles.size(); ++k) label(static_cast<int>(k) + 1, tiles[k].label);
  for (int y = 0; y < tile_h; ++y) {
    for (int x = 0; x < tile_w; ++x) {
      const double value_reference = box(reference, x, y, scale);
      put(0, 0, x, y, display(value_reference));
      put(0, 1, x, y, {0, 0, 0});
      for (std::size_t k = 0; k < tiles.size(); ++k) {
        const double value = box(*tiles[k].image, x, y, scale);
        put(static_cast<int>(k) + 1, 0, x, y, display(value));
        put(static_cast<int>(k) + 1, 1, x, y, difference_colour(value, value_reference));
      }
    }
  }
  std::string png;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &png, width, height, 3, pixels.data(), width * 3)) throw Error("cannot encode a PNG sheet");
  return with_text_chunk(png, "Software", std::string(output_tag) + " report");
}

std::string configuration_of(const render::ImageSet::Rendered& rendered) {
  return render::configuration_id(rendered.variant, rendered.feed, rendered.prefilter, rendered.lobe);
}

// Every configuration of a (scene, material) beside the ground truth.
std::string sheet_png(const render::ImageSet& set) {
  std::vector<Tile> tiles;
  for (const auto& rendered : set.variants) tiles.push_back({configuration_of(rendered), &rendered.image});
  return grid_png(set.reference, tiles);
}

std::string sheet_name(const render::ImageSet& set) {
  return fmt::format("sheet_{}_alpha{:.4f}.png", render::scene_name(set.scene), set.material.alpha);
}

// ---------------------------------------------------------------------------------------------
// Tables.

std::string optional_number(const std::optional<double>& value, const char* format) {
  return value ? fmt::format(fmt::runtime(format), *value) : std::string("-");
}

// ---------------------------------------------------------------------------------------------
// Tables: built once, printed for the terminal, Markdown and HTML.

struct TextTable {
  std::vector<std::string> headers;
  std::vector<std::vector<std::string>> rows;
};

std::string as_text(const TextTable& table) {
  std::vector<std::size_t> widths;
  for (const std::string& h : table.headers) widths.push_back(h.size());
  for (const auto& row : table.rows)
    for (std::size_t c = 0; c < row.size() && c < widths.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
  const auto line = [&](const std::vector<std::string>& cells) {
    std::string text;
    for (std::size_t c = 0; c < cells.size(); ++c)
      text += c == 0 ? fmt::format("{:<{}}", cells[c], widths[c]) : fmt::format("  {:>{}}", cells[c], widths[c]);
    return text + "\n";
  };
  std::string text = line(table.headers);
  for (const auto& row : table.rows) text += line(row);
  return text;
}

std::string as_markdown(const TextTable& table) {
  std::string text = "| " + fmt::format("{}", fmt::join(table.headers, " | ")) + " |\n|";
  for (std::size_t c = 0; c < table.headers.size(); ++c) text += "---|";
  text += "\n";
  for (const auto& row : table.rows) text += "| " + fmt::format("{}", fmt::join(row, " | ")) + " |\n";
  return text;
}

std::string html_escape(std::string_view text);

std::string as_html(const TextTable& table) {
  std::string text = "<table><tr>";
  for (const std::string& h : table.headers) text += "<th>" + html_escape(h) + "</th>";
  text += "</tr>\n";
  for (const auto& row : table.rows) {
    text += "<tr>";
    for (const std::string& cell : row) text += "<td>" + html_escape(cell) + "</td>";
    text += "</tr>\n";
  }
  return text + "</table>\n";
}

const std::vector<std::string> kMetricHeaders{"RMSE linear", "RMSE tonemapped", "LDR-FLIP",    "HDR-FLIP",        "max error",
                                              "TDE",         "excess flicker",  "lost motion", "flicker tm ratio"};

std::vector<std::string> metric_cells(const Metrics& m) {
  return {fmt::format("{:.4g}", m.rmse_linear),        fmt::format("{:.4g}", m.rmse_tonemapped), fmt::format("{:.4f}", m.flip_ldr),
          fmt::format("{:.4f}", m.flip_hdr),           fmt::format("{:.4g}", m.max_error),       fmt::format("{:.5f}", m.tde),
          fmt::format("{:.5f}", m.tde_excess_flicker), fmt::format("{:.5f}", m.tde_lost_motion), fmt::format("{:.3f}", m.flicker_display)};
}

// ISA inverse-throughput ratio (primary), lavapipe time ratio (secondary), SPIR-V delta.
std::vector<std::string> cost_cells(const CostTable* costs, const std::string& configuration) {
  return {optional_number(configuration_isa_cost(costs, configuration), "{:.3f}"),
          optional_number(configuration_cost(costs, configuration, true), "{:.3f}"),
          optional_number(configuration_cost(costs, configuration, false), "{:+.0f}")};
}

Metrics metrics_of(const VariantSummary& s) {
  Metrics m;
  m.rmse_linear = s.rmse_linear, m.rmse_tonemapped = s.rmse_tonemapped, m.max_error = s.max_error;
  m.flip_ldr = s.flip_ldr, m.flip_hdr = s.flip_hdr;
  m.tde = s.tde, m.tde_excess_flicker = s.tde_excess_flicker, m.tde_lost_motion = s.tde_lost_motion;
  m.flicker = s.flicker, m.flicker_display = s.flicker_display, m.cases = s.cases;
  return m;
}

TextTable summary_table(const std::vector<VariantSummary>& summary, const CostTable* costs) {
  TextTable t;
  t.headers = {"configuration"};
  t.headers.insert(t.headers.end(), kMetricHeaders.begin(), kMetricHeaders.end());
  t.headers.insert(t.headers.end(), {"ISA inv.thr", "time ratio", "dSPIR-V"});
  for (const VariantSummary& row : summary) {
    std::vector<std::string> cells{row.variant};
    for (auto& c : metric_cells(metrics_of(row))) cells.push_back(c);
    for (auto& c : cost_cells(costs, row.variant)) cells.push_back(c);
    t.rows.push_back(cells);
  }
  return t;
}

TextTable content_table(const render::TradeTable& table, Content content, const CostTable* costs) {
  TextTable t;
  t.headers = {"configuration"};
  t.headers.insert(t.headers.end(), kMetricHeaders.begin(), kMetricHeaders.end());
  t.headers.insert(t.headers.end(), {"ISA inv.thr", "time ratio", "dSPIR-V"});
  const RowFilter keep = [content](const render::TradeRow& row) { return content_of(row.scene) == content; };
  for (const std::string& id : configurations(table)) {
    const Metrics m = mean_metrics(table, id, keep);
    if (!m.cases) continue;
    std::vector<std::string> cells{id};
    for (auto& c : metric_cells(m)) cells.push_back(c);
    for (auto& c : cost_cells(costs, id)) cells.push_back(c);
    t.rows.push_back(cells);
  }
  return t;
}

std::string percent_change(double ours, double theirs) {
  return theirs > 0.0 ? fmt::format("{:+.1f} %", 100.0 * (ours - theirs) / theirs) : std::string("-");
}

TextTable recommendation_table(const std::vector<Recommendation>& recs, const CostTable* costs) {
  TextTable t{{"path", "content", "recommended", "LDR-FLIP", "TDE", "HDR-FLIP", "RMSE tonemapped", "ISA inv.thr", "time ratio", "dSPIR-V"},
              {}};
  for (const Recommendation& r : recs) {
    std::vector<std::string> cells{std::string(path_name(r.path)),
                                   std::string(content_name(r.content)),
                                   r.configuration,
                                   fmt::format("{:.4f}", r.metrics.flip_ldr),
                                   fmt::format("{:.5f}", r.metrics.tde),
                                   fmt::format("{:.4f}", r.metrics.flip_hdr),
                                   fmt::format("{:.4g}", r.metrics.rmse_tonemapped)};
    for (auto& c : cost_cells(costs, r.configuration)) cells.push_back(c);
    t.rows.push_back(cells);
  }
  return t;
}

TextTable switch_table(const std::vector<EngineSwitch>& switches) {
  TextTable t{{"switching from", "content", "engine LDR-FLIP", "saagen that beats it at <= cost", "LDR-FLIP", "change LDR-FLIP",
               "change TDE", "change HDR-FLIP", "change RMSE tm"},
              {}};
  for (const EngineSwitch& s : switches) {
    if (s.configuration.empty()) {
      t.rows.push_back({s.engine, std::string(content_name(s.content)), fmt::format("{:.4f}", s.engine_metrics.flip_ldr), "(none beats it)",
                        "-", "-", "-", "-", "-"});
      continue;
    }
    t.rows.push_back(
        {s.engine, std::string(content_name(s.content)), fmt::format("{:.4f}", s.engine_metrics.flip_ldr), s.configuration,
         fmt::format("{:.4f}", s.saagen_metrics.flip_ldr), percent_change(s.saagen_metrics.flip_ldr, s.engine_metrics.flip_ldr),
         percent_change(s.saagen_metrics.tde, s.engine_metrics.tde), percent_change(s.saagen_metrics.flip_hdr, s.engine_metrics.flip_hdr),
         percent_change(s.saagen_metrics.rmse_tonemapped, s.engine_metrics.rmse_tonemapped)});
  }
  return t;
}

// Compact: whether the recommendation beats none and every engine on the scene, and how many
// (baseline, metric) pairs it loses; the losses themselves are in the report (loss_lists_*).
TextTable verdict_table(const std::vector<SceneVerdict>& verdicts) {
  TextTable t{{"scene", "path", "recommended", "LDR-FLIP", "TDE", "RMSE tonemapped", "beats none and every engine"}, {}};
  for (const SceneVerdict& v : verdicts) {
    t.rows.push_back({std::string(render::scene_name(v.scene)), std::string(path_name(v.path)), v.configuration,
                      fmt::format("{:.4f}", v.recommended.flip_ldr), fmt::format("{:.5f}", v.recommended.tde),
                      fmt::format("{:.4g}", v.recommended.rmse_tonemapped),
                      v.losses.empty() ? "yes"
                                       : fmt::format("no: {} of {} comparisons lost", v.losses.size(),
                                                     v.baselines.size() * std::size(kVerdictMetrics))});
  }
  return t;
}

TextTable cases_table(const render::TradeTable& table) {
  TextTable t{{"scene", "alpha", "Fresnel", "configuration"}, {}};
  t.headers.insert(t.headers.end(), kMetricHeaders.begin(), kMetricHeaders.end());
  for (const render::TradeRow& row : table.rows) {
    std::vector<std::string> cells{std::string(render::scene_name(row.scene)), fmt::format("{}", row.alpha), row.fresnel ? "yes" : "no",
                                   render::configuration_id(row)};
    for (auto& c : metric_cells(row_metrics(row))) cells.push_back(c);
    t.rows.push_back(cells);
  }
  return t;
}

// The findings in order: recommendation, engine switches, per-scene verdicts. `section` formats
// a heading and a table.
template <class Section>
void for_each_finding(const render::TradeTable& table, const CostTable* costs, Section section) {
  const std::vector<Recommendation> recs = recommend(table);
  section(
      "Recommended configuration per render path and content (saagen's decision: what beats no SAA in image and video error "
      "beyond their intervals, the largest video-error gain; none where nothing does; the columns: the older means)",
      recommendation_table(recs, costs));
  section(std::string("Switching from an engine's shipped form: saagen's decision against it (what beats it in image and video "
                      "error beyond their intervals, the largest video-error gain) at equal or lower cost") +
              (costs ? "" : " (no cost file: cost not compared)"),
          switch_table(engine_switches(table, costs)));
  section("Per scene: the recommendation against no SAA and every engine (the older means: LDR-FLIP, TDE, HDR-FLIP, tonemapped RMSE)",
          verdict_table(scene_verdicts(table, recs)));
}

// ---------------------------------------------------------------------------------------------
// The short verdict: per render path and content, what to use and by how much it beats no SAA
// and the best engine form, in LDR-FLIP and TDE, then plainly where it loses.

// "engine-hdrp 0.0150, -20 %"
std::string against(const std::string& name, double theirs, double ours, int digits) {
  const double percent = theirs > 0.0 ? 100.0 * (ours - theirs) / theirs : 0.0;
  const std::string change = theirs <= 0.0               ? std::string()
                             : std::fabs(percent) < 10.0 ? fmt::format(", {:+.1f} %", percent)
                                                         : fmt::format(", {:+.0f} %", percent);
  return fmt::format("{} {:.{}f}{}", name, theirs, digits, change);
}

std::string metric_comparison(const char* metric, double ours, double none, const std::string& engine, double engine_value, int digits) {
  std::string text = fmt::format("{} {:.{}f} ({}", metric, ours, digits, against("none", none, ours, digits));
  if (!engine.empty()) text += "; best engine " + against(engine, engine_value, ours, digits);
  return text + ")";
}

// A decision's reason after "no filter -- ": without its own "no filter: ".
std::string without_no_filter(const std::string& reason) {
  constexpr std::string_view prefix = "no filter: ";
  return reason.starts_with(prefix) ? reason.substr(prefix.size()) : reason;
}

// The decision's own words: the chosen configuration's comparison with no SAA (image and flicker
// error, 95 % intervals), then its means beside no SAA's and the best engine's.
std::string headline(const Verdict& v) {
  const Recommendation& r = v.recommendation;
  if (r.configuration == "none")
    return fmt::format("{}, {}: no filter -- {}", path_name(r.path), content_name(r.content), without_no_filter(r.reason));
  return fmt::format(
      "{}, {}: {}; {}, {}", path_name(r.path), content_name(r.content), r.reason,
      metric_comparison("image error", r.metrics.image_error, v.none.image_error, v.best_engine_image, v.engine_image.image_error, 4),
      v.video ? metric_comparison("video error (10 - JOD)", r.metrics.video_error, v.none.video_error, v.best_engine_motion,
                                  v.engine_motion.video_error, 3)
              : metric_comparison("flicker error", r.metrics.flicker_error, v.none.flicker_error, v.best_engine_motion,
                                  v.engine_motion.flicker_error, 5));
}

// "HDR-FLIP to engine-godot (0.0512 vs 0.0498)", per content-mean loss.
std::string mean_losses(const Verdict& v) {
  std::vector<std::string> parts;
  for (const Loss& loss : v.losses)
    parts.push_back(fmt::format("{} to {} ({:.4g} vs {:.4g})", loss.metric, loss.baseline, loss.ours, loss.theirs));
  return fmt::format("{}", fmt::join(parts, ", "));
}

// "tubes: TDE (none + 2 engines), HDR-FLIP (engine-godot)": per scene, each lost metric and whom
// it is lost to (engines counted past two).
std::string scene_losses(const Verdict& v) {
  std::vector<std::string> scenes;
  for (const auto& [scene, losses] : v.scene_losses) {
    std::vector<std::string> metrics;
    for (const VerdictMetric& metric : kVerdictMetrics) {
      bool none = false;
      std::vector<std::string> engines;
      for (const Loss& loss : losses) {
        if (loss.metric != metric.name) continue;
        if (loss.baseline == "none")
          none = true;
        else
          engines.push_back(loss.baseline);
      }
      if (!none && engines.empty()) continue;
      std::vector<std::string> whom;
      if (none) whom.push_back("none");
      if (engines.size() > 2)
        whom.push_back(fmt::format("{} engines", engines.size()));
      else
        whom.insert(whom.end(), engines.begin(), engines.end());
      metrics.push_back(fmt::format("{} ({})", metric.name, fmt::join(whom, " + ")));
    }
    scenes.push_back(fmt::format("{}: {}", render::scene_name(scene), fmt::join(metrics, ", ")));
  }
  return fmt::format("{}", fmt::join(scenes, "; "));
}

// The verdict lines of one recommendation: the headline, then where it loses (or that it does not).
std::vector<std::string> verdict_lines(const Verdict& v) {
  std::vector<std::string> lines{headline(v)};
  const Recommendation& r = v.recommendation;
  if (r.speed_configuration != r.configuration)
    lines.push_back(r.speed_configuration == "none" ? "prefer speed: no filter -- " + without_no_filter(r.speed_reason)
                                                    : "prefer speed: " + r.speed_configuration + " -- " + r.speed_reason);
  // The older metrics, not the verdict's, so that nothing it gives up is hidden.
  if (!v.losses.empty()) lines.push_back("in the older metrics (means, no interval), loses on the content means: " + mean_losses(v));
  if (!v.scene_losses.empty()) lines.push_back("in the older metrics, loses per scene: " + scene_losses(v));
  if (v.losses.empty() && v.scene_losses.empty() && v.recommendation.configuration != "none")
    lines.push_back("in the older metrics too, beats none and every engine on LDR-FLIP, TDE, HDR-FLIP and tonemapped RMSE, on every scene");
  return lines;
}

// Verdicts grouped by render path, then content type.
std::vector<Verdict> ordered_verdicts(const render::TradeTable& table) {
  std::vector<Verdict> all = verdicts(table, recommend(table));
  std::stable_sort(all.begin(), all.end(),
                   [](const Verdict& a, const Verdict& b) { return a.recommendation.path < b.recommendation.path; });
  return all;
}

constexpr const char* kVerdictTitle = "Verdict: what to use per render path and content";
constexpr const char* kVerdictNote =
    "the decision's comparison with no SAA, paired, 95 % intervals, then means over the content's scenes and alphas, no Fresnel; "
    "lower is better; image error = LDR-FLIP of every animation frame, flicker error = pooled frame-to-frame change against the "
    "ground truth's (docs/TEMPORAL.md); % = change from the baseline";

// ---------------------------------------------------------------------------------------------
// Image strips: per scene, the ground truth, no SAA, the best engine form and the
// recommendations, at the alpha where no SAA errs most (largest LDR-FLIP).

struct Strip {
  std::string file;
  std::string caption;
  std::string png;
};

const render::ImageSet::Rendered* find_rendered(const render::ImageSet& set, const std::string& configuration) {
  for (const auto& rendered : set.variants)
    if (configuration_of(rendered) == configuration) return &rendered;
  return nullptr;
}

std::string strip_name(render::SceneId scene) { return fmt::format("strip_{}.png", render::scene_name(scene)); }

const render::ImageSet* worst_case_for_none(const render::TradeTable& table, render::SceneId scene) {
  const render::ImageSet* worst = nullptr;
  double worst_error = -1.0;
  for (const render::ImageSet& set : table.images) {
    if (set.scene != scene || set.material.fresnel) continue;
    const render::TradeRow* none = table.find(Variant::none, scene, set.material.alpha, false);
    if (none && none->flip_ldr > worst_error) worst = &set, worst_error = none->flip_ldr;
  }
  return worst;
}

std::vector<Strip> strips(const render::TradeTable& table, const std::vector<Verdict>& all) {
  std::vector<Strip> out;
  for (render::SceneId scene : table.config.scenes) {
    const render::ImageSet* set = worst_case_for_none(table, scene);
    if (!set) continue;
    std::vector<std::pair<std::string, std::string>> columns{{"none", "none"}};  // label, configuration
    for (const Verdict& v : all) {
      if (v.recommendation.content != content_of(scene)) continue;
      if (!v.best_engine_image.empty() && columns.size() == 1)
        columns.emplace_back("best engine: " + v.best_engine_image, v.best_engine_image);
      if (v.recommendation.configuration == "none") continue;  // no filter: the first column
      columns.emplace_back(fmt::format("{}: {}", path_name(v.recommendation.path), v.recommendation.configuration),
                           v.recommendation.configuration);
    }
    std::vector<Tile> tiles;
    std::vector<std::string> labels{"ground truth"};
    for (const auto& [label, configuration] : columns)
      if (const auto* rendered = find_rendered(*set, configuration)) tiles.push_back({label, &rendered->image}), labels.push_back(label);
    out.push_back(
        {strip_name(scene),
         fmt::format("{}, alpha {} (where no SAA errs most): {}", render::scene_name(scene), set->material.alpha, fmt::join(labels, ", ")),
         grid_png(set->reference, tiles)});
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// With TAA: per scene, at the alpha where none+taa errs most (largest LDR-FLIP of the animation),
// a crop of the animation's last frame (flicker resolution) enlarged: the ground truth, none+taa,
// the best saagen configuration and the best engine form under TAA (taa_comparisons, by their
// scene means), captioned with that case's figures.

std::string taa_strip_name(render::SceneId scene) { return fmt::format("taa_{}.png", render::scene_name(scene)); }

struct Crop {
  int x = 0, y = 0, size = 0, scale = 1;
};

// The square window of half the frame's smaller side (8 px at least) holding the most
// tonemapped ground-truth radiance (where the highlights are, whichever configuration is
// shown), and the integer enlargement that shows it at 128 px or more. A summed-area table.
Crop brightest_crop(const render::Image& reference) {
  const int w = reference.width, h = reference.height;
  Crop crop;
  crop.size = std::min(std::min(w, h), std::max(8, std::min(w, h) / 2));
  crop.scale = std::max(1, 128 / crop.size);
  std::vector<double> sat(static_cast<std::size_t>(w + 1) * (h + 1), 0.0);
  const auto at = [&](int x, int y) -> double& { return sat[static_cast<std::size_t>(y) * (w + 1) + x]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) at(x + 1, y + 1) = render::tonemap(reference.at(x, y)) + at(x, y + 1) + at(x + 1, y) - at(x, y);
  double best = -1.0;
  for (int y = 0; y + crop.size <= h; ++y)
    for (int x = 0; x + crop.size <= w; ++x) {
      const double sum = at(x + crop.size, y + crop.size) - at(x, y + crop.size) - at(x + crop.size, y) + at(x, y);
      if (sum > best) best = sum, crop.x = x, crop.y = y;
    }
  return crop;
}

render::Image cropped(const render::Image& image, const Crop& crop) {
  render::Image out(crop.size * crop.scale, crop.size * crop.scale);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) out.at(x, y) = image.at(crop.x + x / crop.scale, crop.y + y / crop.scale);
  return out;
}

std::string taa_configuration_of(const render::ImageSet::Rendered& rendered) {
  return render::configuration_id(rendered.variant, rendered.feed, rendered.prefilter, rendered.lobe, true);
}

// The +taa row of a case (scene, alpha, no Fresnel) by its configuration id.
const render::TradeRow* taa_row(const render::TradeTable& taa, render::SceneId scene, double alpha, const std::string& configuration) {
  for (const render::TradeRow& row : taa.rows)
    if (row.taa && !row.fresnel && row.scene == scene && row.alpha == alpha && render::configuration_id(row) == configuration) return &row;
  return nullptr;
}

const render::ImageSet* worst_case_for_none_taa(const render::TradeTable& taa, render::SceneId scene) {
  const render::ImageSet* worst = nullptr;
  double worst_error = -1.0;
  for (const render::ImageSet& set : taa.taa_images) {
    if (set.scene != scene || set.material.fresnel) continue;
    const render::TradeRow* none = taa_row(taa, scene, set.material.alpha, "none+taa");
    if (none && none->flip_ldr_animation > worst_error) worst = &set, worst_error = none->flip_ldr_animation;
  }
  return worst;
}

Strip taa_strip(const render::TradeTable& taa, const TaaComparison& comparison, const render::ImageSet& set) {
  const Crop crop = brightest_crop(set.reference);
  std::vector<std::pair<std::string, std::string>> columns{{"none+taa", "none+taa"}};  // label, configuration
  if (!comparison.best_saagen.empty()) columns.emplace_back("best saagen: " + comparison.best_saagen, comparison.best_saagen);
  if (!comparison.best_engine.empty()) columns.emplace_back("best engine: " + comparison.best_engine, comparison.best_engine);
  std::vector<render::Image> images;
  std::vector<std::string> labels, figures;
  images.reserve(columns.size());
  for (const auto& column : columns) {
    const std::string& configuration = column.second;  // a named copy: clang 14 cannot capture a structured binding
    const auto rendered = std::find_if(set.variants.begin(), set.variants.end(),
                                       [&](const render::ImageSet::Rendered& r) { return taa_configuration_of(r) == configuration; });
    const render::TradeRow* row = taa_row(taa, set.scene, set.material.alpha, configuration);
    if (rendered == set.variants.end() || !row) continue;
    images.push_back(cropped(rendered->image, crop));
    labels.push_back(column.first);  // the label of the image kept, also when an earlier column had none
    figures.push_back(fmt::format("{} {:.4f} / {:.2f}", column.first, row->image_error.mean, row->video_error.mean));
  }
  std::vector<Tile> tiles;
  for (std::size_t i = 0; i < images.size(); ++i) tiles.push_back({labels[i], &images[i]});
  const std::string scene(render::scene_name(set.scene));
  return {taa_strip_name(set.scene),
          fmt::format("{} under TAA, alpha {} (where none+taa errs most), last animation frame, the {} x {} px crop at ({}, {}) "
                      "shown {}x: ground truth, {} (image error / video error at this alpha)",
                      scene, set.material.alpha, crop.size, crop.size, crop.x, crop.y, crop.scale, fmt::join(figures, ", ")),
          grid_png(cropped(set.reference, crop), tiles)};
}

struct TaaSection {
  std::string note;
  TextTable table;
  std::vector<std::string> verdicts;  // per scene, the decision's reason under TAA
  std::vector<Strip> strips;
};

TaaSection taa_section(const render::TradeTable& taa) {
  TaaSection section;
  section.note = taa_note(taa);
  section.table.headers = taa_headers();
  section.table.headers.insert(section.table.headers.begin(), "scene");
  for (const TaaComparison& comparison : taa_comparisons(taa)) {
    for (const TaaComparisonRow& row : comparison.rows) {
      std::vector<std::string> columns = taa_columns(row);
      columns.insert(columns.begin(), std::string(render::scene_name(comparison.scene)));
      section.table.rows.push_back(std::move(columns));
    }
    section.verdicts.push_back(std::string(render::scene_name(comparison.scene)) + ": " + comparison.verdict);
    if (const render::ImageSet* set = worst_case_for_none_taa(taa, comparison.scene))
      section.strips.push_back(taa_strip(taa, comparison, *set));
  }
  return section;
}

constexpr const char* kTaaTitle = "With TAA: none+taa, the configuration the verdict takes under TAA and each engine form under TAA";
constexpr const char* kTaaImageNote =
    "Images: top, the crop of the animation's last frame; bottom, the tonemapped difference from the ground truth (red brighter, blue "
    "darker, full colour at 0.25).";

// ---------------------------------------------------------------------------------------------
// Pages.

const char* kMetricNote =
    "Metrics against the supersampled ground truth: RMSE of linear radiance; RMSE after Reinhard's x/(1+x); mean LDR-FLIP of the "
    "tonemapped images (Andersson et al. 2020, 67 pixels per degree); mean HDR-FLIP of the linear images (Andersson et al. 2021); "
    "TDE = temporal difference error of the animation in display values (tonemapped, sRGB-encoded): mean over pixels and frame "
    "pairs of |(I_t - I_t-1) - (R_t - R_t-1)| against the ground truth R (the pixel-level tLP of Chu et al. 2020), split into "
    "excess flicker (changes the ground truth does not make) and lost motion (changes it makes that are missing); flicker tm "
    "ratio (secondary) = the mean per-pixel temporal std of the tonemapped frames divided by the ground truth's, which rewards "
    "a highlight blurred away. Engines cost what deferred-sum costs (same operations).";

std::string html_escape(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else
      out += c;
  }
  return out;
}

// "; NAME at WxH px (animation wxh px), ..." for the scenes with sizes of their own.
std::string scene_sizes_line(const render::TradeConfig& c) {
  std::string line;
  for (const render::TradeSceneSize& size : c.scene_sizes) {
    if (std::find(c.scenes.begin(), c.scenes.end(), size.scene) == c.scenes.end()) continue;
    line += fmt::format("{}{} at {}x{} px, {} spp (animation {}x{} px, {} spp)", line.empty() ? "; " : ", ", render::scene_name(size.scene),
                        size.width, size.height, size.strata * size.strata, size.flicker_width, size.flicker_height,
                        size.flicker_strata * size.flicker_strata);
  }
  return line;
}

std::string config_line(const render::TradeTable& table) {
  const render::TradeConfig& c = table.config;
  return fmt::format(
             "{}x{} px, {} spp ground truth (Gaussian pixel filter, sigma^2 = 0.25 px^2); animation over {} frames at "
             "{} deg/frame and a camera pan of ({}, {}) px/frame ({}x{} px, {} spp); sigma^2 = {}, kappa = {}; {} derivatives; "
             "prefiltered rows at normal-map LOD bias {}",
             c.width, c.height, c.strata * c.strata, c.frames, c.rotation_degrees_per_frame, c.pan_pixels_per_frame.x,
             c.pan_pixels_per_frame.y, c.flicker_width, c.flicker_height, c.flicker_strata * c.flicker_strata, c.params.sigma2,
             c.params.kappa, c.derivative == ref::Derivative::coarse ? "coarse" : "fine", c.prefilter_lod_bias) +
         scene_sizes_line(c);
}

// Per scene and path with losses: "scene, path, configuration" and each loss.
std::vector<std::pair<std::string, std::vector<std::string>>> loss_lists(const render::TradeTable& table) {
  std::vector<std::pair<std::string, std::vector<std::string>>> lists;
  for (const SceneVerdict& v : scene_verdicts(table, recommend(table))) {
    if (v.losses.empty()) continue;
    std::vector<std::string> items;
    for (const Loss& loss : v.losses) items.push_back(describe(loss));
    lists.emplace_back(fmt::format("{}, {}: {}", render::scene_name(v.scene), path_name(v.path), v.configuration), items);
  }
  return lists;
}

constexpr const char* kLossListTitle = "Where the recommendation loses, per scene (against none and every engine)";

constexpr const char* kTradeTitle = "The trade per content and render path";
constexpr const char* kTradeNote =
    "Each plot: the shading cost of every configuration the path can use (the planner's ratio to no SAA) against its image error "
    "minus no SAA's, lower is better. The labelled points are the frontier (nothing is both cheaper and lower in error), with 95 % "
    "intervals and each one's outcome against no SAA in both metrics (image and flicker error); saagen's choice is ringed.";

std::string markdown_report(const render::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs,
                            const std::vector<std::string>& sheets, const std::vector<std::string>& plots,
                            const std::vector<Strip>& image_strips, const TaaSection* taa) {
  std::ostringstream md;
  md << "<!-- " << output_tag << " report -->\n# saagen speed/accuracy trade report\n\n## " << kVerdictTitle << "\n\n(" << kVerdictNote
     << ")\n\n";
  for (const Verdict& v : ordered_verdicts(table)) {
    const std::vector<std::string> lines = verdict_lines(v);
    md << "- **" << lines.front() << "**\n";
    for (std::size_t i = 1; i < lines.size(); ++i) md << "  - " << lines[i] << "\n";
  }
  md << "\n";
  for (const Strip& strip : image_strips) md << "![" << strip.caption << "](" << strip.file << ")\n\n";
  md << "## " << kTradeTitle << "\n\n" << kTradeNote << "\n\n";
  for (const std::string& plot : plots) md << "![" << plot << "](" << plot << ")\n\n";
  if (taa) {
    md << "## " << kTaaTitle << "\n\n(" << taa->note << ")\n\n";
    for (const std::string& verdict : taa->verdicts) md << "- " << verdict << "\n";
    md << "\n" << as_markdown(taa->table) << "\n" << kTaaImageNote << "\n\n";
    for (const Strip& strip : taa->strips) md << "![" << strip.caption << "](" << strip.file << ")\n\n";
  }
  md << config_line(table) << ".\n\n" << kMetricNote << "\n\n";
  if (costs) md << "Cost: " << costs->describe() << ".\n\n";
  for_each_finding(table, costs, [&](const std::string& title, const TextTable& t) {
    md << "## " << title << "\n\n" << as_markdown(t) << "\n";
  });
  md << "## " << kLossListTitle << "\n\n";
  for (const auto& [heading, items] : loss_lists(table)) {
    md << "- " << heading << "\n";
    for (const std::string& item : items) md << "  - " << item << "\n";
  }
  md << "\n## Summary (means over every scene and alpha, no Fresnel)\n\n" << as_markdown(summary_table(summary, costs));
  for (Content content : kContents)
    md << "\n## " << content_name(content) << " scenes (means over their scenes and alphas)\n\n"
       << as_markdown(content_table(table, content, costs));
  md << "\n## Every case\n\n" << as_markdown(cases_table(table));
  md << "\n## Images\n\nEach sheet: the ground truth, then every configuration's 1-spp image (top, labelled); their tonemapped "
        "differences from the ground truth, red brighter, blue darker, full colour at 0.25 (bottom).\n\n";
  for (const std::string& sheet : sheets) md << "![" << sheet << "](" << sheet << ")\n\n";
  return md.str();
}

std::string html_verdict(const render::TradeTable& table) {
  std::string html =
      fmt::format("<h2>{}</h2>\n<p>({})</p>\n<ul class=\"verdict\">\n", html_escape(kVerdictTitle), html_escape(kVerdictNote));
  for (const Verdict& v : ordered_verdicts(table)) {
    const std::vector<std::string> lines = verdict_lines(v);
    html += "<li><b>" + html_escape(lines.front()) + "</b>";
    for (std::size_t i = 1; i < lines.size(); ++i) html += "<br>" + html_escape(lines[i]);
    html += "</li>\n";
  }
  return html + "</ul>\n";
}

std::string html_loss_lists(const render::TradeTable& table) {
  std::string html = fmt::format("<h2>{}</h2>\n<ul>\n", html_escape(kLossListTitle));
  for (const auto& [heading, items] : loss_lists(table)) {
    html += "<li>" + html_escape(heading) + "<ul>";
    for (const std::string& item : items) html += "<li>" + html_escape(item) + "</li>";
    html += "</ul></li>\n";
  }
  return html + "</ul>\n";
}

std::string html_report(const render::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs,
                        const std::vector<std::string>& sheets, const std::vector<std::string>& plots,
                        const std::vector<std::string>& columns, const std::vector<Strip>& image_strips, const TaaSection* taa) {
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<!-- " << output_tag
       << " report -->\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>saagen trade report</title>\n"
          "<style>body{font-family:sans-serif;margin:2em;max-width:1500px}table{border-collapse:collapse}"
          "td,th{border:1px solid #bbb;padding:2px 8px;text-align:right}th{background:#eee}img{max-width:100%}"
          "ul.verdict li{margin-bottom:0.6em}figure{margin:1em 0}</style>\n"
          "</head><body>\n<h1>saagen speed/accuracy trade report</h1>\n"
       << html_verdict(table);
  html << "<h2>Per scene: ground truth, no SAA, best engine form, recommendation</h2>\n<p>Top: images; bottom: tonemapped difference "
          "from the ground truth (red brighter, blue darker, full colour at 0.25).</p>\n";
  for (const Strip& strip : image_strips)
    html << "<figure><img src=\"" << strip.file << "\" alt=\"" << html_escape(strip.caption) << "\"><figcaption>"
         << html_escape(strip.caption) << "</figcaption></figure>\n";
  html << "<h2>" << html_escape(kTradeTitle) << "</h2>\n<p>" << html_escape(kTradeNote) << "</p>\n";
  for (const std::string& plot : plots) html << "<img src=\"" << plot << "\" alt=\"" << plot << "\">\n";
  if (taa) {
    html << "<h2>" << html_escape(kTaaTitle) << "</h2>\n<p>(" << html_escape(taa->note) << ")</p>\n<ul>\n";
    for (const std::string& verdict : taa->verdicts) html << "<li>" << html_escape(verdict) << "</li>\n";
    html << "</ul>\n" << as_html(taa->table) << "<p>" << html_escape(kTaaImageNote) << "</p>\n";
    for (const Strip& strip : taa->strips)
      html << "<figure><img src=\"" << strip.file << "\" alt=\"" << html_escape(strip.caption) << "\"><figcaption>"
           << html_escape(strip.caption) << "</figcaption></figure>\n";
  }
  html << "<p>" << html_escape(config_line(table)) << "</p>\n<p>" << html_escape(kMetricNote) << "</p>\n";
  if (costs) html << "<p>Cost: " << html_escape(costs->describe()) << ".</p>\n";
  for_each_finding(table, costs, [&](const std::string& title, const TextTable& t) {
    html << "<h2>" << html_escape(title) << "</h2>\n" << as_html(t);
  });
  html << html_loss_lists(table);
  html << "<h2>Summary (means over every scene and alpha, no Fresnel)</h2>\n" << as_html(summary_table(summary, costs));
  for (Content content : kContents)
    html << "<h2>" << content_name(content) << " scenes</h2>\n" << as_html(content_table(table, content, costs));
  html << "<h2>Images</h2>\n<p>Columns: " << html_escape(fmt::format("{}", fmt::join(columns, ", ")))
       << ". Top: images; bottom: tonemapped difference from the ground truth (red brighter, blue darker, full colour at 0.25).</p>\n";
  for (const std::string& sheet : sheets) html << "<h3>" << sheet << "</h3>\n<img src=\"" << sheet << "\" alt=\"" << sheet << "\">\n";
  html << "<h2>Every case</h2>\n" << as_html(cases_table(table));
  // A page check a headless browser can read from the DOM: how many images decoded.
  html << "<p id=\"image-check\">images: not checked</p>\n<script>\nwindow.addEventListener('load', function () {\n"
          "  var images = Array.from(document.images);\n"
          "  var loaded = images.filter(function (image) { return image.complete && image.naturalWidth > 0; }).length;\n"
          "  document.getElementById('image-check').textContent = 'images loaded: ' + loaded + '/' + images.length;\n"
          "});\n</script>\n</body></html>\n";
  return html.str();
}

}  // namespace

const VariantCost* CostTable::find(std::string_view variant) const {
  for (const VariantCost& row : rows) {
    if (row.variant == variant) return &row;
  }
  return nullptr;
}

std::string CostTable::describe() const {
  std::vector<std::string> models;
  if (!isa_family.empty())
    models.push_back(fmt::format("ISA inv.thr: ACO inverse-throughput ratio on RADV {} (null hardware, `saagen bench --isa`)", isa_family));
  if (!source.empty()) models.push_back(fmt::format("time ratio and dSPIR-V: {} ({})", source, device));
  return models.empty() ? std::string("no cost model") : fmt::format("{}", fmt::join(models, "; "));
}

void add_isa_costs(CostTable& table, const std::string& family, const std::vector<std::pair<std::string, double>>& ratios) {
  table.isa_family = family;
  for (const auto& variant_ratio : ratios) {  // not a structured binding: clang 14 cannot capture one in a lambda
    const std::string& variant = variant_ratio.first;
    const double ratio = variant_ratio.second;
    auto found = std::find_if(table.rows.begin(), table.rows.end(), [&](const VariantCost& row) { return row.variant == variant; });
    if (found == table.rows.end()) found = table.rows.insert(table.rows.end(), VariantCost{variant, {}, {}, {}});
    found->isa_ratio = ratio;
  }
}

CostTable load_cost_table(const fs::path& path) {
  const std::string text = read_input_file(path, table_size_limit, fmt::format("the file `bench_shading --json {}` writes", path.string()));
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& error) {
    throw Error(fmt::format("{}: not valid JSON (byte {}); pass the file `bench_shading --json` writes", path.string(), error.byte));
  } catch (const nlohmann::json::exception&) {  // out_of_range.406: a number such as 1e999
    throw Error(fmt::format("{}: holds a number beyond a double's range; pass the file `bench_shading --json` writes", path.string()));
  }
  if (!document.is_object() || !document.contains("rows") || !document["rows"].is_array()) {
    throw Error(fmt::format("{}: no \"rows\" array; pass the file `bench_shading --json` writes", path.string()));
  }
  CostTable table;
  table.source = path.string();
  table.device = document.value("device", std::string("unknown device"));
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> by_variant;
  std::vector<std::string> order;
  for (const auto& row : document["rows"]) {
    if (!row.is_object() || !row.contains("variant") || !row["variant"].is_string()) {
      throw Error(fmt::format("{}: every row needs a string \"variant\"", path.string()));
    }
    const std::string variant = row["variant"].get<std::string>();
    if (!by_variant.count(variant)) order.push_back(variant);
    auto& [ratios, deltas] = by_variant[variant];
    if (row.contains("ratio_median") && row["ratio_median"].is_number()) ratios.push_back(row["ratio_median"].get<double>());
    if (row.contains("delta_spirv_instructions") && row["delta_spirv_instructions"].is_number()) {
      deltas.push_back(row["delta_spirv_instructions"].get<double>());
    }
  }
  for (const std::string& variant : order) {
    const auto& [ratios, deltas] = by_variant[variant];
    VariantCost cost{variant, {}, {}, {}};
    if (!ratios.empty()) cost.time_ratio = mean(ratios);
    if (!deltas.empty()) cost.delta_instructions = mean(deltas);
    table.rows.push_back(cost);
  }
  return table;
}

std::vector<VariantSummary> summarize(const render::TradeTable& table) {
  std::vector<std::string> order;
  std::map<std::string, std::vector<const render::TradeRow*>> by_configuration;
  for (const render::TradeRow& row : table.rows) {
    if (row.fresnel) continue;
    const std::string id = render::configuration_id(row);
    if (!by_configuration.count(id)) order.push_back(id);
    by_configuration[id].push_back(&row);
  }
  std::vector<VariantSummary> summary;
  for (const std::string& id : order) {
    VariantSummary entry{id};
    std::vector<double> linear, tonemapped, flicker, flicker_display, flip_ldr, flip_hdr, tde, excess, lost;
    for (const render::TradeRow* row : by_configuration[id]) {
      tde.push_back(row->tde);
      excess.push_back(row->tde_excess_flicker);
      lost.push_back(row->tde_lost_motion);
      flip_ldr.push_back(row->flip_ldr);
      flip_hdr.push_back(row->flip_hdr);
      linear.push_back(row->rmse_linear);
      tonemapped.push_back(row->rmse_tonemapped);
      flicker.push_back(row->flicker);
      flicker_display.push_back(row->flicker_display);
      entry.max_error = std::max(entry.max_error, row->max_error);
    }
    entry.cases = linear.size();
    entry.rmse_linear = mean(linear);
    entry.rmse_tonemapped = mean(tonemapped);
    entry.tde = mean(tde);
    entry.tde_excess_flicker = mean(excess);
    entry.tde_lost_motion = mean(lost);
    entry.flicker = mean(flicker);
    entry.flicker_display = mean(flicker_display);
    entry.flip_ldr = mean(flip_ldr);
    entry.flip_hdr = mean(flip_hdr);
    summary.push_back(entry);
  }
  return summary;
}

render::TradeConfig preset_config(std::string_view preset) {
  render::TradeConfig config;
  // Every scene: the analytic ones and the real-content ones (normal maps with MIPs, a mesh),
  // and low roughness down to perceptual 0.05 (alpha 0.0025) and 0.08 (alpha 0.0064).
  config.scenes.assign(render::all_scenes().begin(), render::all_scenes().end());
  config.scenes.insert(config.scenes.end(), render::content_scenes().begin(), render::content_scenes().end());
  config.alphas = {0.0025, 0.0064, 0.01, 0.05, 0.1, 0.3};
  if (preset == "full") return config;
  if (preset == "medium") {
    // Every scene and alpha at a quarter of the pixels and samples, without Fresnel: minutes,
    // not tens of minutes, for trying a configuration.
    config.width = config.height = 128;
    config.strata = 16;
    config.flicker_width = config.flicker_height = 64;
    config.flicker_strata = 8;
    config.frames = 16;
    config.rotation_degrees_per_frame = 0.5;
    config.fresnel_modes = {false};
    return config;
  }
  if (preset == "quick") {
    config.width = config.height = 64;
    config.strata = 8;
    config.flicker_width = config.flicker_height = 32;
    config.flicker_strata = 4;
    config.frames = 4;
    config.scenes.assign(render::all_scenes().begin(), render::all_scenes().end());
    config.alphas = {0.01, 0.1};
    config.fresnel_modes = {false};
    return config;
  }
  throw Error(fmt::format("unknown preset '{}'; choose full, medium or quick", preset));
}

constexpr int kMinAssetAnimationSize = 64;

void size_preset_assets(std::string_view preset, render::TradeConfig& config) {
  if (preset != "medium" && preset != "full") return;
  // The animation keeps the preset's size: at 32 x 32 a large asset's highlights fall between
  // the pixels, the ground truth's two seeds differ as much as a frozen clip does, and the
  // sanity suite cannot tell a delayed clip from another seed (2CylinderEngine, medium preset).
  const int width = config.width / 2, flicker_width = std::max(config.flicker_width / 2, kMinAssetAnimationSize);
  for (const render::SceneId id : config.scenes) {
    if (!render::is_preset_asset_scene(id)) continue;
    config.scene_sizes.push_back({id, width, width, config.strata, flicker_width, flicker_width, config.flicker_strata});
  }
}

void add_preset_assets(std::string_view preset, render::TradeConfig& config) {
  if (preset != "medium" && preset != "full") return;
  std::vector<render::SceneId> assets;
  try {
    assets = render::register_preset_assets();
  } catch (const render::AssetMissing& missing) {
    throw Error(fmt::format("preset {}: {}", preset, missing.what()));
  } catch (const std::exception& bad) {  // GltfError, AssetError: "PATH: what is wrong"
    throw Error(fmt::format("preset {}: {}", preset, bad.what()));
  }
  for (const render::SceneId id : assets)
    if (std::find(config.scenes.begin(), config.scenes.end(), id) == config.scenes.end()) config.scenes.push_back(id);
  size_preset_assets(preset, config);
}

std::string format_summary(const std::vector<VariantSummary>& summary, const CostTable* costs) {
  return as_text(summary_table(summary, costs));
}

std::string format_findings(const render::TradeTable& table, const CostTable* costs) {
  std::string text;
  for_each_finding(table, costs, [&](const std::string& title, const TextTable& t) { text += "\n" + title + ":\n" + as_text(t); });
  return text;
}

std::string format_verdict(const render::TradeTable& table) {
  std::string text = fmt::format("{}\n({}):\n", kVerdictTitle, kVerdictNote);
  for (const Verdict& v : ordered_verdicts(table)) {
    const std::vector<std::string> lines = verdict_lines(v);
    text += "  " + lines.front() + "\n";
    for (std::size_t i = 1; i < lines.size(); ++i) text += "      " + lines[i] + "\n";
  }
  return text;
}

namespace {

nlohmann::json difference_json(const decision::Difference& d) { return {{"mean", d.mean}, {"low", d.low}, {"high", d.high}}; }

nlohmann::json comparison_json(const decision::Comparison& c) {
  return {{"image", difference_json(c.image)}, {"temporal", difference_json(c.temporal)}, {"lag", difference_json(c.lag)}};
}

}  // namespace

// saagen's decision (findings.hpp, decide_on) as the JSON carries it, for the scripts to read
// instead of deciding again: the chosen configuration ("none": no filter), the reason, and every
// candidate's comparison with no SAA and outcome; per_scene adds the chosen configuration's
// outcome against each engine's form on that scene.
nlohmann::json decision_json(const MaterialDecision& made) {
  nlohmann::json candidates = nlohmann::json::array();
  for (std::size_t i = 0; i < made.candidates.size(); ++i) {
    const decision::Candidate& c = made.candidates[i];
    candidates.push_back({{"configuration", c.configuration},
                          {"usable", c.usable},
                          {"outcome", std::string(decision::name(made.decision.outcomes[i]))},
                          {"image", difference_json(c.against_none.image)},
                          {"temporal", difference_json(c.against_none.temporal)},
                          {"cost_ratio", c.cost_ratio ? nlohmann::json(*c.cost_ratio) : nlohmann::json()}});
  }
  return {{"chosen", made.decision.chosen ? made.candidates[*made.decision.chosen].configuration : "none"},
          {"reason", made.decision.reason},
          {"candidates", candidates}};
}

// The chosen configuration against an engine's form on a scene, paired with intervals.
nlohmann::json engine_comparison_json(const decision::Comparison& c) {
  return {{"outcome", std::string(decision::name(decision::outcome(c)))},
          {"image", difference_json(c.image)},
          {"temporal", difference_json(c.temporal)}};
}

namespace {

// Per content type and path: saagen's decision on each content's rows (`rows_of`) against
// `baseline`, as the JSON carries it.
template <class RowsOf>
nlohmann::json content_decisions_json(RowsOf rows_of, std::string_view baseline) {
  nlohmann::json out = nlohmann::json::array();
  for (Content content : kContents) {
    const std::vector<ContentRow> rows = rows_of(content);
    if (rows.empty()) continue;
    for (Path path : {Path::forward, Path::deferred}) {
      nlohmann::json entry = decision_json(decide_on(rows, path, content, false, baseline));
      entry["content"] = std::string(content_name(content)), entry["path"] = std::string(path_name(path));
      out.push_back(entry);
    }
  }
  return out;
}

}  // namespace

// Under TAA, per content type and path: saagen's decision on the content's +taa rows against
// none+taa (findings.hpp, measured_taa_rows), what `saagen plan` gives with taa = true.
nlohmann::json taa_decisions_json(const render::TradeTable& table) {
  return content_decisions_json([&](Content content) { return measured_taa_rows(table, content); }, "none+taa");
}

// Under TAA, per content type: every configuration's means and its pairing with none+taa
// (measured_taa_rows), in by_content's form; `saagen plan --trade-table` reads it with taa = true.
nlohmann::json taa_by_content_json(const render::TradeTable& table) {
  nlohmann::json out = nlohmann::json::array();
  const std::string temporal = has_video_metric(table) ? "video_error" : "flicker_error";
  for (Content content : kContents)
    for (const ContentRow& row : measured_taa_rows(table, content)) {
      nlohmann::json entry = {{"content", row.content}, {"configuration", row.configuration}, {"baseline", "none+taa"},
                              {"error", row.error},     {"image_error", row.error},           {temporal, row.tde.value_or(0.0)}};
      if (row.against_none) entry["against_none"] = comparison_json(*row.against_none);
      out.push_back(entry);
    }
  return out;
}

nlohmann::json decisions_json(const render::TradeTable& table) {
  const nlohmann::json by_content = content_decisions_json(
      [&](Content content) {
        const RowFilter keep = [content](const render::TradeRow& row) { return !row.taa && content_of(row.scene) == content; };
        return measured_rows(table, keep, content_name(content));
      },
      "no SAA");
  nlohmann::json per_scene = nlohmann::json::array();
  for (render::SceneId scene : table.config.scenes) {
    const RowFilter keep = [scene](const render::TradeRow& row) { return !row.taa && row.scene == scene; };
    const std::vector<ContentRow> rows = measured_rows(table, keep, render::scene_name(scene));
    for (Path path : {Path::forward, Path::deferred}) {
      const MaterialDecision made = decide_on(rows, path, content_of(scene));
      nlohmann::json entry = decision_json(made);
      entry["scene"] = std::string(render::scene_name(scene)), entry["path"] = std::string(path_name(path));
      entry["content"] = std::string(content_name(content_of(scene)));
      nlohmann::json engines = nlohmann::json::object();
      const std::string chosen = chosen_configuration(made);
      const auto chosen_row = std::find_if(rows.begin(), rows.end(), [&](const ContentRow& r) { return r.configuration == chosen; });
      for (const ContentRow& row : rows)
        if (is_engine_configuration(row.configuration) && chosen_row != rows.end())
          engines[row.configuration] = engine_comparison_json(to_decision(compare_configurations(table, chosen, row.configuration, keep)));
      entry["against_engines"] = engines;
      per_scene.push_back(entry);
    }
  }
  return {{"rule",
           "only what beats no SAA (no metric worse beyond its interval, one better) and is not late is chosen; "
           "accuracy: the largest gain in the temporal metric, the image metric as tie-break; none where nothing "
           "beats no SAA (saagen/decision.hpp)"},
          {"image_metric", "image error (LDR-FLIP of every animation frame)"},
          {"temporal_metric", has_video_metric(table)
                                  ? "video error (10 - ColorVideoVDP's JOD of the animation clip against the ground truth's)"
                                  : "flicker error (pooled frame-to-frame change against the ground truth's)"},
          {"by_content", by_content},
          {"per_scene", per_scene}};
}

namespace {

// The clip's JOD against the first ground-truth seed (the clip `--frames` writes as the ground
// truth); 10 without the video metric.
double first_seed_jod(const render::TradeRow& row) {
  const std::vector<double>& losses = row.series.video[0];
  return losses.empty() ? 10.0 : 10.0 - render::mean_interval(losses, 0.0).mean;
}

}  // namespace

nlohmann::json interval_json(const render::Interval& interval) {
  return {{"mean", interval.mean}, {"low", interval.low}, {"high", interval.high}};
}

nlohmann::json difference_json(const MetricDifference& d) {
  nlohmann::json out = interval_json(d.difference);
  out["ground_truth_sd"] = d.ground_truth_sd;
  out["ground_truth_limited"] = d.ground_truth_limited;
  out["outcome"] = std::string(metric_outcome_name(outcome_of(d)));
  return out;
}

nlohmann::json trade_json(const render::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs) {
  nlohmann::json rows = nlohmann::json::array();
  for (const VariantSummary& row : summary) {
    nlohmann::json entry = {{"variant", row.variant},
                            {"error", row.flip_ldr},
                            {"rmse_tonemapped", row.rmse_tonemapped},
                            {"rmse_linear", row.rmse_linear},
                            {"flip_hdr", row.flip_hdr},
                            {"tde", row.tde},
                            {"tde_excess_flicker", row.tde_excess_flicker},
                            {"tde_lost_motion", row.tde_lost_motion},
                            {"flicker", row.flicker},
                            {"flicker_display", row.flicker_display}};
    if (const auto ratio = configuration_isa_cost(costs, row.variant); ratio && costs && !costs->isa_family.empty()) {
      entry["isa_inverse_throughput_ratio"] = *ratio;
      entry["isa_family"] = costs->isa_family;
    }
    if (const auto ratio = configuration_cost(costs, row.variant, true)) entry["ratio_median"] = *ratio;
    if (const auto delta = configuration_cost(costs, row.variant, false)) entry["delta_spirv_instructions"] = *delta;
    rows.push_back(entry);
  }
  nlohmann::json cases = nlohmann::json::array();
  for (const render::TradeRow& row : table.rows) {
    cases.push_back({{"scene", std::string(render::scene_name(row.scene))},
                     {"alpha", row.alpha},
                     {"fresnel", row.fresnel},
                     {"variant", id_of(row.variant)},
                     {"feed", std::string(render::feed_name(row.feed))},
                     {"configuration", render::configuration_id(row)},
                     {"rmse_linear", row.rmse_linear},
                     {"rmse_tonemapped", row.rmse_tonemapped},
                     {"max_error", row.max_error},
                     {"flip_ldr", row.flip_ldr},
                     {"flip_hdr", row.flip_hdr},
                     {"tde", row.tde},
                     {"tde_excess_flicker", row.tde_excess_flicker},
                     {"tde_lost_motion", row.tde_lost_motion},
                     {"flicker", row.flicker},
                     {"flicker_display", row.flicker_display},
                     {"image_error", interval_json(row.image_error)},
                     {"flicker_error", interval_json(row.flicker_error)},
                     {"video_error", interval_json(row.video_error)},
                     {"jod", first_seed_jod(row)},
                     {"lag", interval_json(row.lag)},
                     {"flicker_excess", row.flicker_excess},
                     {"flicker_missing", row.flicker_missing}});
  }
  nlohmann::json sanity = nlohmann::json::array();
  for (const render::SanityRow& row : table.sanity)
    sanity.push_back({{"scene", std::string(render::scene_name(row.scene))},
                      {"alpha", row.alpha},
                      {"fresnel", row.fresnel},
                      {"result", std::string(render::sanity_name(row.result))},
                      {"image_error", row.image_error},
                      {"flicker_error", row.flicker_error},
                      {"video_error", row.video_error},
                      {"jod", 10.0 - row.video_error},
                      {"lag", row.lag}});
  // Per content type, the same means: the planner's advice for a material with or without normal maps.
  nlohmann::json by_content = nlohmann::json::array();
  for (Content content : kContents) {
    const RowFilter keep = [content](const render::TradeRow& row) { return content_of(row.scene) == content; };
    for (const std::string& id : configurations(table)) {
      const Metrics m = mean_metrics(table, id, keep);
      if (!m.cases || is_measurement_configuration(id)) continue;
      by_content.push_back({{"content", std::string(content_name(content))},
                            {"configuration", id},
                            {"error", m.flip_ldr},
                            {"rmse_tonemapped", m.rmse_tonemapped},
                            {"flip_hdr", m.flip_hdr},
                            {"tde", m.tde},
                            {"tde_excess_flicker", m.tde_excess_flicker},
                            {"tde_lost_motion", m.tde_lost_motion},
                            {"flicker_display", m.flicker_display},
                            {"image_error", m.image_error},
                            {"flicker_error", m.flicker_error},
                            {"video_error", m.video_error}});
      if (id == "none") continue;
      const PairedComparison against_none = compare_configurations(table, id, "none", keep);
      if (against_none.cells == 0) continue;
      by_content.back()["against_none"] = comparison_json(to_decision(against_none));
    }
  }
  // Every configuration against no SAA, paired, with 95 % intervals (comparison.hpp): per content
  // type and per scene; the verdicts, the planner and the scripts read these.
  nlohmann::json comparisons = nlohmann::json::array();
  const auto add_comparisons = [&](std::string_view scope, const std::string& name, const CellFilter& keep) {
    for (const std::string& id : configurations(table)) {
      if (id == "none" || is_measurement_configuration(id)) continue;
      const PairedComparison c = compare_configurations(table, id, "none", keep);
      if (c.cells == 0) continue;
      comparisons.push_back({{"scope", scope},
                             {"name", name},
                             {"configuration", id},
                             {"baseline", "none"},
                             {"cells", c.cells},
                             {"image_error", difference_json(c.image)},
                             {"flicker_error", difference_json(c.flicker)},
                             {"lag", difference_json(c.lag)},
                             {"outcome", std::string(comparison_outcome_name(c))}});
      if (c.video) comparisons.back()["video_error"] = difference_json(*c.video);
    }
  };
  for (Content content : kContents)
    add_comparisons("content", std::string(content_name(content)),
                    [content](const render::TradeRow& row) { return content_of(row.scene) == content; });
  for (const render::SceneId scene : table.config.scenes)
    add_comparisons("scene", std::string(render::scene_name(scene)), [scene](const render::TradeRow& row) { return row.scene == scene; });
  return {{"generator", std::string(output_tag) + " saagen bench"},
          {"decisions", decisions_json(table)},
          {"error_metric", "mean LDR-FLIP of the tonemapped images over scenes and alphas, no Fresnel"},
          {"motion_metric", "tde: mean temporal difference error of the display-value animation against the ground truth's"},
          {"config", config_line(table)},
          {"rows", rows},
          {"by_content", by_content},
          {"cases", cases},
          {"sanity", sanity},
          {"comparisons", comparisons}};
}

std::vector<fs::path> report_paths(const render::TradeConfig& config, const fs::path& dir) {
  std::vector<fs::path> paths = {dir / "index.html", dir / "report.md"};
  std::vector<Content> contents;
  for (const render::SceneId scene : config.scenes)
    if (std::find(contents.begin(), contents.end(), content_of(scene)) == contents.end()) contents.push_back(content_of(scene));
  for (const Content content : contents)
    for (const Path path : {Path::forward, Path::deferred}) paths.push_back(dir / trade_plot_name(content, path));
  for (const render::SceneId scene : config.scenes) {
    paths.push_back(dir / strip_name(scene));
    if (config.taa) paths.push_back(dir / taa_strip_name(scene));
    for (const double alpha : config.alphas) {
      render::ImageSet set;
      set.scene = scene;
      set.material.alpha = alpha;
      paths.push_back(dir / sheet_name(set));
    }
  }
  return paths;
}

std::vector<std::string> write_report(const render::TradeTable& table, const CostTable* costs, const fs::path& dir, bool force,
                                      const render::TradeTable* taa) {
  ReportFiles files = report_files(table, costs, dir, taa);
  write_outputs(files.outputs, force);
  return files.images;
}

ReportFiles report_files(const render::TradeTable& table, const CostTable* costs, const fs::path& dir, const render::TradeTable* taa) {
  if (table.images.empty()) throw Error("the trade table holds no images; compute it with keep_images");
  std::vector<OutputFile> outputs;
  std::vector<std::string> sheets;
  for (const render::ImageSet& set : table.images) {
    if (set.material.fresnel) continue;  // the Fresnel images differ by a dim factor only
    sheets.push_back(sheet_name(set));
    outputs.push_back({dir / sheets.back(), sheet_png(set)});
  }
  std::vector<std::string> columns{"ground truth"};
  for (const auto& rendered : table.images.front().variants) columns.push_back(configuration_of(rendered));

  const std::vector<Strip> image_strips = strips(table, ordered_verdicts(table));
  for (const Strip& strip : image_strips) outputs.push_back({dir / strip.file, strip.png});
  std::optional<TaaSection> taa_part;
  if (taa) taa_part = taa_section(*taa);
  if (taa_part)
    for (const Strip& strip : taa_part->strips) outputs.push_back({dir / strip.file, strip.png});

  const auto summary = summarize(table);
  std::vector<std::string> plots;
  for (const ContentTrade& trade : content_trades(table)) {
    plots.push_back(trade_plot_name(trade));
    outputs.push_back({dir / plots.back(), trade_plot_svg(trade)});
  }
  const TaaSection* taa_section_written = taa_part ? &*taa_part : nullptr;
  outputs.push_back({dir / "report.md", markdown_report(table, summary, costs, sheets, plots, image_strips, taa_section_written)});
  outputs.push_back({dir / "index.html", html_report(table, summary, costs, sheets, plots, columns, image_strips, taa_section_written)});
  std::vector<std::string> images;
  for (const Strip& strip : image_strips) images.push_back(strip.file);
  if (taa_part)
    for (const Strip& strip : taa_part->strips) images.push_back(strip.file);
  images.insert(images.end(), sheets.begin(), sheets.end());
  images.insert(images.end(), plots.begin(), plots.end());
  return {std::move(outputs), std::move(images)};
}

render::TradeProgressFn progress_bar() {
  // On a terminal, one redrawn line; in a log (stderr not a terminal), one line per stage.
  if (!::isatty(STDERR_FILENO)) {
    return [last_stage = std::string()](const render::TradeProgress& progress) mutable {
      if (progress.stage == last_stage) return;
      last_stage = progress.stage;
      const double fraction = progress.total ? static_cast<double>(progress.done) / static_cast<double>(progress.total) : 0.0;
      std::cerr << fmt::format("[{:3.0f}%] {}\n", fraction * 100.0, progress.stage) << std::flush;
    };
  }
  return [](const render::TradeProgress& progress) {
    const double fraction = progress.total ? static_cast<double>(progress.done) / static_cast<double>(progress.total) : 0.0;
    const int filled = static_cast<int>(fraction * 30.0);
    std::cerr << fmt::format("\r[{:<30}] {:3.0f}%  {:<40}", std::string(static_cast<std::size_t>(filled), '#'), fraction * 100.0,
                             progress.stage.substr(0, 40))
              << std::flush;
    if (progress.total && progress.done >= progress.total) std::cerr << "\n";
  };
}

}  // namespace saagen::report

namespace saagen::report {

std::string encode_tagged_png(int width, int height, int channels, const std::vector<std::uint8_t>& pixels, std::string_view what) {
  std::string png;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &png, width, height, channels, pixels.data(), width * channels)) throw Error("cannot encode a PNG");
  return with_text_chunk(png, "Software", std::string(output_tag) + " " + std::string(what));
}

}  // namespace saagen::report

#include "saagen/report/report.hpp"

#include "saagen/error.hpp"
#include "saagen/input.hpp"
#include "saagen/output.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
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

std::uint8_t to_byte(double value) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 1.0) * 255.0));
}

double srgb_encode(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

Rgb display(double radiance) {
  const std::uint8_t v = to_byte(srgb_encode(render::tonemap(radiance)));
  return {v, v, v};
}

Rgb difference_colour(double radiance, double reference) {
  const double d = (render::tonemap(radiance) - render::tonemap(reference)) / difference_full_scale;
  const double m = srgb_encode(std::min(std::fabs(d), 1.0));
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

// One sheet: row 0 the ground truth then each variant, row 1 an empty cell then the difference
// maps; a 2-pixel grey gutter between tiles.
std::string sheet_png(const render::ImageSet& set) {
  const int scale = display_scale(set.reference);
  const int tile_w = set.reference.width / scale, tile_h = set.reference.height / scale, gutter = 2;
  const int columns = 1 + static_cast<int>(set.variants.size());
  const int width = columns * tile_w + (columns - 1) * gutter, height = 2 * tile_h + gutter;
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width) * height * 3, 96);
  const auto put = [&](int column, int row, int x, int y, Rgb colour) {
    const std::size_t index = (static_cast<std::size_t>(row * (tile_h + gutter) + y) * width + column * (tile_w + gutter) + x) * 3;
    pixels[index] = colour.r, pixels[index + 1] = colour.g, pixels[index + 2] = colour.b;
  };
  for (int y = 0; y < tile_h; ++y) {
    for (int x = 0; x < tile_w; ++x) {
      const double reference = box(set.reference, x, y, scale);
      put(0, 0, x, y, display(reference));
      put(0, 1, x, y, {0, 0, 0});
      for (std::size_t k = 0; k < set.variants.size(); ++k) {
        const double value = box(set.variants[k].second, x, y, scale);
        put(static_cast<int>(k) + 1, 0, x, y, display(value));
        put(static_cast<int>(k) + 1, 1, x, y, difference_colour(value, reference));
      }
    }
  }
  std::string png;
  const auto append = [](void* context, void* data, int size) { static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size)); };
  if (!stbi_write_png_to_func(append, &png, width, height, 3, pixels.data(), width * 3)) throw Error("cannot encode a PNG sheet");
  return with_text_chunk(png, "Software", std::string(output_tag) + " report");
}

std::string sheet_name(const render::ImageSet& set) {
  return fmt::format("sheet_{}_alpha{:.2f}.png", render::scene_name(set.scene), set.material.alpha);
}

// ---------------------------------------------------------------------------------------------
// The cost-vs-error plot (SVG): x = lavapipe time ratio when measured, else the SPIR-V delta;
// y = mean tonemapped RMSE.

std::optional<double> cost_of(const CostTable* costs, const std::string& variant, bool time) {
  if (variant == "none") return time ? std::optional<double>(1.0) : std::optional<double>(0.0);
  if (!costs) return std::nullopt;
  const VariantCost* cost = costs->find(variant);
  if (!cost) return std::nullopt;
  return time ? cost->time_ratio : cost->delta_instructions;
}

std::string plot_svg(const std::vector<VariantSummary>& summary, const CostTable* costs) {
  const bool time = costs && std::any_of(costs->rows.begin(), costs->rows.end(), [](const VariantCost& c) { return c.time_ratio.has_value(); });
  std::vector<std::tuple<std::string, double, double>> points;
  for (const VariantSummary& row : summary) {
    if (const auto cost = cost_of(costs, row.variant, time)) points.emplace_back(row.variant, *cost, row.rmse_tonemapped);
  }
  const double width = 720, height = 480, left = 70, right = 200, top = 30, bottom = 60;
  double x_min = 1e300, x_max = -1e300, y_max = 0.0;
  for (const auto& [name, x, y] : points) x_min = std::min(x_min, x), x_max = std::max(x_max, x), y_max = std::max(y_max, y);
  if (points.empty()) x_min = 0.0, x_max = 1.0, y_max = 1.0;
  const double x_pad = std::max((x_max - x_min) * 0.08, 1e-3);
  x_min -= x_pad, x_max += x_pad, y_max *= 1.1;
  const auto sx = [&](double x) { return left + (x - x_min) / (x_max - x_min) * (width - left - right); };
  const auto sy = [&](double y) { return height - bottom - y / y_max * (height - top - bottom); };
  std::ostringstream svg;
  svg << fmt::format(R"s(<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" font-family="sans-serif" font-size="12">)s", width, height) << "\n";
  svg << "<!-- " << output_tag << " report -->\n";
  svg << fmt::format(R"s(<rect width="{}" height="{}" fill="white"/>)s", width, height) << "\n";
  svg << fmt::format(R"s(<line x1="{0}" y1="{1}" x2="{2}" y2="{1}" stroke="black"/><line x1="{0}" y1="{1}" x2="{0}" y2="{3}" stroke="black"/>)s",
                     left, height - bottom, width - right, top) << "\n";
  for (int tick = 0; tick <= 4; ++tick) {
    const double x = x_min + (x_max - x_min) * tick / 4.0, y = y_max * tick / 4.0;
    svg << fmt::format(R"s(<text x="{}" y="{}" text-anchor="middle">{:.3g}</text>)s", sx(x), height - bottom + 18, x) << "\n";
    svg << fmt::format(R"s(<text x="{}" y="{}" text-anchor="end">{:.3g}</text>)s", left - 6, sy(y) + 4, y) << "\n";
  }
  svg << fmt::format(R"s(<text x="{}" y="{}" text-anchor="middle">{}</text>)s", (left + width - right) / 2, height - 15,
                     time ? "cost: GPU time with SAA / without (lavapipe)" : "cost: optimized SPIR-V instructions added") << "\n";
  svg << fmt::format(R"s(<text x="16" y="{}" transform="rotate(-90 16 {})" text-anchor="middle">error: mean tonemapped RMSE</text>)s",
                     (top + height - bottom) / 2, (top + height - bottom) / 2) << "\n";
  for (const auto& [name, x, y] : points) {
    const std::string colour = name.rfind("forward", 0) == 0 ? "#c0392b" : name.rfind("deferred", 0) == 0 ? "#2471a3" : "#555555";
    svg << fmt::format(R"s(<circle cx="{:.1f}" cy="{:.1f}" r="5" fill="{}"/><text x="{:.1f}" y="{:.1f}">{}</text>)s", sx(x), sy(y),
                       colour, sx(x) + 8, sy(y) + 4, name) << "\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

// ---------------------------------------------------------------------------------------------
// Tables.

std::string optional_number(const std::optional<double>& value, const char* format) {
  return value ? fmt::format(fmt::runtime(format), *value) : std::string("-");
}

struct SummaryColumns {
  std::string variant, rmse_linear, rmse_tonemapped, max_error, flicker, time_ratio, delta_spirv;
};

std::vector<SummaryColumns> summary_columns(const std::vector<VariantSummary>& summary, const CostTable* costs) {
  std::vector<SummaryColumns> rows;
  for (const VariantSummary& row : summary) {
    rows.push_back({row.variant, fmt::format("{:.4g}", row.rmse_linear), fmt::format("{:.4g}", row.rmse_tonemapped),
                    fmt::format("{:.4g}", row.max_error), fmt::format("{:+.4f}", row.flicker),
                    optional_number(cost_of(costs, row.variant, true), "{:.3f}"),
                    optional_number(cost_of(costs, row.variant, false), "{:+.0f}")});
  }
  return rows;
}

std::string html_escape(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}

std::string config_line(const render::TradeTable& table) {
  const render::TradeConfig& c = table.config;
  return fmt::format("{}x{} px, {} spp ground truth (Gaussian pixel filter, sigma^2 = 0.25 px^2); flicker over {} frames at "
                     "{} deg/frame ({}x{} px, {} spp); sigma^2 = {}, kappa = {}; {} derivatives; ground truth {:.1f} s "
                     "({} cache hits, {} misses)",
                     c.width, c.height, c.strata * c.strata, c.frames, c.rotation_degrees_per_frame, c.flicker_width,
                     c.flicker_height, c.flicker_strata * c.flicker_strata, c.params.sigma2, c.params.kappa,
                     c.derivative == ref::Derivative::coarse ? "coarse" : "fine", table.ground_truth_seconds, table.cache_hits,
                     table.cache_misses);
}

std::string markdown_report(const render::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs,
                            const std::vector<std::string>& sheets) {
  std::ostringstream md;
  md << "<!-- " << output_tag << " report -->\n# saagen speed/accuracy trade report\n\n" << config_line(table) << ".\n\n";
  if (costs) md << "Cost from `" << costs->source << "` (" << costs->device << ").\n\n";
  md << "## Summary (means over scenes and alphas, no Fresnel)\n\n";
  md << "| variant | RMSE linear | RMSE tonemapped | max error | flicker | time ratio | dSPIR-V |\n|---|---|---|---|---|---|---|\n";
  for (const auto& c : summary_columns(summary, costs)) {
    md << fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", c.variant, c.rmse_linear, c.rmse_tonemapped, c.max_error, c.flicker,
                      c.time_ratio, c.delta_spirv);
  }
  md << "\n![cost vs error](cost_vs_error.svg)\n\n## Every case\n\n";
  md << "| scene | alpha | Fresnel | variant | RMSE linear | RMSE tonemapped | max error | flicker |\n|---|---|---|---|---|---|---|---|\n";
  for (const render::TradeRow& row : table.rows) {
    md << fmt::format("| {} | {} | {} | {} | {:.4g} | {:.4g} | {:.4g} | {:+.4f} |\n", render::scene_name(row.scene), row.alpha,
                      row.fresnel ? "yes" : "no", id_of(row.variant), row.rmse_linear, row.rmse_tonemapped, row.max_error, row.flicker);
  }
  md << "\n## Images\n\nEach sheet: the ground truth, then every variant's 1-spp image (top); their tonemapped differences "
        "from the ground truth, red brighter, blue darker, full colour at 0.25 (bottom).\n\n";
  for (const std::string& sheet : sheets) md << "![" << sheet << "](" << sheet << ")\n\n";
  return md.str();
}

std::string html_report(const render::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs,
                        const std::vector<std::string>& sheets, const std::vector<std::string>& columns) {
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<!-- " << output_tag << " report -->\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>saagen trade report</title>\n"
          "<style>body{font-family:sans-serif;margin:2em;max-width:1500px}table{border-collapse:collapse}"
          "td,th{border:1px solid #bbb;padding:2px 8px;text-align:right}th{background:#eee}img{max-width:100%}</style>\n"
          "</head><body>\n<h1>saagen speed/accuracy trade report</h1>\n<p>" << html_escape(config_line(table)) << "</p>\n";
  if (costs) html << "<p>Cost from <code>" << html_escape(costs->source) << "</code> (" << html_escape(costs->device) << ").</p>\n";
  html << "<h2>Summary (means over scenes and alphas, no Fresnel)</h2>\n<table><tr><th>variant</th><th>RMSE linear</th>"
          "<th>RMSE tonemapped</th><th>max error</th><th>flicker</th><th>time ratio</th><th>dSPIR-V</th></tr>\n";
  for (const auto& c : summary_columns(summary, costs)) {
    html << fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n", c.variant,
                        c.rmse_linear, c.rmse_tonemapped, c.max_error, c.flicker, c.time_ratio, c.delta_spirv);
  }
  html << "</table>\n<h2>Cost against error</h2>\n<img src=\"cost_vs_error.svg\" alt=\"cost against error\">\n";
  html << "<h2>Images</h2>\n<p>Columns: " << html_escape(fmt::format("{}", fmt::join(columns, ", ")))
       << ". Top: images; bottom: tonemapped difference from the ground truth (red brighter, blue darker, full colour at 0.25).</p>\n";
  for (const std::string& sheet : sheets) html << "<h3>" << sheet << "</h3>\n<img src=\"" << sheet << "\" alt=\"" << sheet << "\">\n";
  html << "<h2>Every case</h2>\n<table><tr><th>scene</th><th>alpha</th><th>Fresnel</th><th>variant</th><th>RMSE linear</th>"
          "<th>RMSE tonemapped</th><th>max error</th><th>flicker</th></tr>\n";
  for (const render::TradeRow& row : table.rows) {
    html << fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.4g}</td><td>{:.4g}</td><td>{:.4g}</td><td>{:+.4f}</td></tr>\n",
                        render::scene_name(row.scene), row.alpha, row.fresnel ? "yes" : "no", id_of(row.variant), row.rmse_linear,
                        row.rmse_tonemapped, row.max_error, row.flicker);
  }
  // A page check a headless browser can read from the DOM: how many images decoded.
  html << "</table>\n<p id=\"image-check\">images: not checked</p>\n<script>\nwindow.addEventListener('load', function () {\n"
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

CostTable load_cost_table(const fs::path& path) {
  const std::string text = read_input_file(path, table_size_limit, fmt::format("the file `bench_shading --json {}` writes", path.string()));
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& error) {
    throw Error(fmt::format("{}: not valid JSON (byte {}); pass the file `bench_shading --json` writes", path.string(), error.byte));
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
    VariantCost cost{variant, {}, {}};
    if (!ratios.empty()) cost.time_ratio = mean(ratios);
    if (!deltas.empty()) cost.delta_instructions = mean(deltas);
    table.rows.push_back(cost);
  }
  return table;
}

std::vector<VariantSummary> summarize(const render::TradeTable& table) {
  std::vector<VariantSummary> summary;
  for (Variant variant : table.config.variants) {
    VariantSummary row{id_of(variant)};
    std::vector<double> linear, tonemapped, flicker;
    for (const render::TradeRow& entry : table.rows) {
      if (entry.variant != variant || entry.fresnel) continue;
      linear.push_back(entry.rmse_linear);
      tonemapped.push_back(entry.rmse_tonemapped);
      flicker.push_back(entry.flicker);
      row.max_error = std::max(row.max_error, entry.max_error);
    }
    row.cases = linear.size();
    row.rmse_linear = mean(linear);
    row.rmse_tonemapped = mean(tonemapped);
    row.flicker = mean(flicker);
    summary.push_back(row);
  }
  return summary;
}

render::TradeConfig preset_config(std::string_view preset) {
  render::TradeConfig config;
  if (preset == "full") return config;
  if (preset == "quick") {
    config.width = config.height = 64;
    config.strata = 8;
    config.flicker_width = config.flicker_height = 32;
    config.flicker_strata = 4;
    config.frames = 4;
    config.alphas = {0.01, 0.1};
    config.fresnel_modes = {false};
    return config;
  }
  throw Error(fmt::format("unknown preset '{}'; choose full or quick", preset));
}

std::string format_summary(const std::vector<VariantSummary>& summary, const CostTable* costs) {
  std::string text = fmt::format("{:<27} {:>12} {:>15} {:>10} {:>9} {:>10} {:>8}\n", "variant", "RMSE linear", "RMSE tonemapped",
                                 "max error", "flicker", "time ratio", "dSPIR-V");
  for (const auto& c : summary_columns(summary, costs)) {
    text += fmt::format("{:<27} {:>12} {:>15} {:>10} {:>9} {:>10} {:>8}\n", c.variant, c.rmse_linear, c.rmse_tonemapped, c.max_error,
                        c.flicker, c.time_ratio, c.delta_spirv);
  }
  return text;
}

nlohmann::json trade_json(const render::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs) {
  nlohmann::json rows = nlohmann::json::array();
  for (const VariantSummary& row : summary) {
    nlohmann::json entry = {{"variant", row.variant}, {"error", row.rmse_tonemapped}, {"rmse_linear", row.rmse_linear},
                            {"flicker", row.flicker}};
    if (const auto ratio = cost_of(costs, row.variant, true)) entry["ratio_median"] = *ratio;
    if (const auto delta = cost_of(costs, row.variant, false)) entry["delta_spirv_instructions"] = *delta;
    rows.push_back(entry);
  }
  nlohmann::json cases = nlohmann::json::array();
  for (const render::TradeRow& row : table.rows) {
    cases.push_back({{"scene", std::string(render::scene_name(row.scene))}, {"alpha", row.alpha}, {"fresnel", row.fresnel},
                     {"variant", id_of(row.variant)}, {"rmse_linear", row.rmse_linear}, {"rmse_tonemapped", row.rmse_tonemapped},
                     {"max_error", row.max_error}, {"flicker", row.flicker}});
  }
  return {{"generator", std::string(output_tag) + " saagen bench"},
          {"error_metric", "mean tonemapped RMSE over scenes and alphas, no Fresnel"}, {"config", config_line(table)},
          {"rows", rows}, {"cases", cases}};
}

std::vector<fs::path> report_paths(const render::TradeConfig& config, const fs::path& dir) {
  std::vector<fs::path> paths = {dir / "index.html", dir / "report.md", dir / "cost_vs_error.svg"};
  for (const render::SceneId scene : config.scenes) {
    for (const double alpha : config.alphas) {
      render::ImageSet set;
      set.scene = scene;
      set.material.alpha = alpha;
      paths.push_back(dir / sheet_name(set));
    }
  }
  return paths;
}

std::vector<std::string> write_report(const render::TradeTable& table, const CostTable* costs, const fs::path& dir, bool force) {
  if (table.images.empty()) throw Error("the trade table holds no images; compute it with keep_images");
  std::vector<OutputFile> outputs;
  std::vector<std::string> sheets;
  for (const render::ImageSet& set : table.images) {
    if (set.material.fresnel) continue;  // the Fresnel images differ by a dim factor only
    sheets.push_back(sheet_name(set));
    outputs.push_back({dir / sheets.back(), sheet_png(set)});
  }
  std::vector<std::string> columns{"ground truth"};
  for (const auto& [variant, image] : table.images.front().variants) columns.push_back(id_of(variant));

  const auto summary = summarize(table);
  outputs.push_back({dir / "cost_vs_error.svg", plot_svg(summary, costs)});
  outputs.push_back({dir / "report.md", markdown_report(table, summary, costs, sheets)});
  outputs.push_back({dir / "index.html", html_report(table, summary, costs, sheets, columns)});
  write_outputs(outputs, force);
  std::vector<std::string> images = sheets;
  images.push_back("cost_vs_error.svg");
  return images;
}

render::TradeProgressFn progress_bar() {
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

// The report's directory (see report.hpp): every file of `saagen report -o DIR`, written in one
// commit through saagen's output layer.
#include "saagen/report/report.hpp"

#include "pages.hpp"
#include "sheets.hpp"
#include "strips.hpp"
#include "taa_strips.hpp"
#include "verdict_text.hpp"

#include "saagen/error.hpp"
#include "saagen/report/findings.hpp"
#include "saagen/report/plots.hpp"

#include <algorithm>
#include <optional>
#include <utility>

namespace saagen::report {

namespace fs = std::filesystem;

std::vector<fs::path> report_paths(const measure::TradeConfig& config, const fs::path& dir) {
  std::vector<fs::path> paths = {dir / "index.html", dir / "report.md"};
  std::vector<Content> contents;
  for (const measure::SceneId scene : config.scenes)
    if (std::find(contents.begin(), contents.end(), content_of(scene)) == contents.end()) contents.push_back(content_of(scene));
  for (const Content content : contents)
    for (const Path path : {Path::forward, Path::deferred}) paths.push_back(dir / trade_plot_name(content, path));
  for (const measure::SceneId scene : config.scenes) {
    paths.push_back(dir / strip_name(scene));
    if (config.taa) paths.push_back(dir / taa_strip_name(scene));
    for (const double alpha : config.alphas) {
      measure::ImageSet set;
      set.scene = scene;
      set.material.alpha = alpha;
      paths.push_back(dir / sheet_name(set));
    }
  }
  return paths;
}

std::vector<std::string> write_report(const measure::TradeTable& table, const CostTable* costs, const fs::path& dir, bool force,
                                      const measure::TradeTable* taa) {
  ReportFiles files = report_files(table, costs, dir, taa);
  write_outputs(files.outputs, force);
  return files.images;
}

ReportFiles report_files(const measure::TradeTable& table, const CostTable* costs, const fs::path& dir, const measure::TradeTable* taa) {
  if (table.images.empty()) throw Error("the trade table holds no images; compute it with keep_images");
  std::vector<OutputFile> outputs;
  std::vector<std::string> sheets;
  for (const measure::ImageSet& set : table.images) {
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

}  // namespace saagen::report

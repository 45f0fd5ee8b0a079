// The report's pages (see pages.hpp).
#include "pages.hpp"

#include "finding_tables.hpp"
#include "taa_strips.hpp"
#include "verdict_text.hpp"

#include "saagen/io/output.hpp"
#include "saagen/report/findings.hpp"
#include "saagen/report/taa_summary.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <optional>
#include <sstream>
#include <utility>

namespace saagen::report {
namespace {

constexpr const char* kTaaTitle = "With TAA: none+taa, the configuration the verdict takes under TAA and each engine form under TAA";
constexpr const char* kTaaImageNote =
    "Images: top, the crop of the animation's last frame; bottom, the tonemapped difference from the ground truth (red brighter, blue "
    "darker, full colour at 0.25).";

const char* kMetricNote =
    "Metrics against the supersampled ground truth: RMSE of linear radiance; RMSE after Reinhard's x/(1+x); mean LDR-FLIP of the "
    "tonemapped images (Andersson et al. 2020, 67 pixels per degree); mean HDR-FLIP of the linear images (Andersson et al. 2021); "
    "TDE = temporal difference error of the animation in display values (tonemapped, sRGB-encoded): mean over pixels and frame "
    "pairs of |(I_t - I_t-1) - (R_t - R_t-1)| against the ground truth R (the pixel-level tLP of Chu et al. 2020), split into "
    "excess flicker (changes the ground truth does not make) and lost motion (changes it makes that are missing); flicker tm "
    "ratio (secondary) = the mean per-pixel temporal std of the tonemapped frames divided by the ground truth's, which rewards "
    "a highlight blurred away. Engines cost what deferred-sum costs (same operations).";

// Per scene and path with losses: "scene, path, configuration" and each loss.
std::vector<std::pair<std::string, std::vector<std::string>>> loss_lists(const measure::TradeTable& table) {
  std::vector<std::pair<std::string, std::vector<std::string>>> lists;
  for (const SceneVerdict& v : scene_verdicts(table, recommend(table))) {
    if (v.losses.empty()) continue;
    std::vector<std::string> items;
    for (const Loss& loss : v.losses) items.push_back(describe(loss));
    lists.emplace_back(fmt::format("{}, {}: {}", measure::scene_name(v.scene), path_name(v.path), v.configuration), items);
  }
  return lists;
}

constexpr const char* kLossListTitle = "Where the recommendation loses, per scene (against none and every engine)";

constexpr const char* kTradeTitle = "The trade per content and render path";
constexpr const char* kTradeNote =
    "Each plot: the shading cost of every configuration the path can use (the planner's ratio to no SAA) against its image error "
    "minus no SAA's, lower is better. The labelled points are the frontier (nothing is both cheaper and lower in error), with 95 % "
    "intervals and each one's outcome against no SAA in both metrics (image and flicker error); saagen's choice is ringed.";

std::string html_head() {
  return std::string("<!DOCTYPE html>\n<!-- ") + std::string(output_tag) +
         " report -->\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>saagen trade report</title>\n"
         "<style>body{font-family:sans-serif;margin:2em;max-width:1500px}table{border-collapse:collapse}"
         "td,th{border:1px solid #bbb;padding:2px 8px;text-align:right}th{background:#eee}img{max-width:100%}"
         "ul.verdict li{margin-bottom:0.6em}figure{margin:1em 0}</style>\n"
         "</head><body>\n<h1>saagen speed/accuracy trade report</h1>\n";
}

// A page check a headless browser can read from the DOM: how many images decoded.
constexpr const char* kHtmlTail =
    "<p id=\"image-check\">images: not checked</p>\n<script>\nwindow.addEventListener('load', function () {\n"
    "  var images = Array.from(document.images);\n"
    "  var loaded = images.filter(function (image) { return image.complete && image.naturalWidth > 0; }).length;\n"
    "  document.getElementById('image-check').textContent = 'images loaded: ' + loaded + '/' + images.length;\n"
    "});\n</script>\n</body></html>\n";

std::string markdown_verdict(const measure::TradeTable& table) {
  std::ostringstream md;
  md << "## " << kVerdictTitle << "\n\n(" << verdict_note(table) << ")\n\n";
  for (const Verdict& v : ordered_verdicts(table)) {
    const std::vector<std::string> lines = verdict_lines(v);
    md << "- **" << lines.front() << "**\n";
    for (std::size_t i = 1; i < lines.size(); ++i) md << "  - " << lines[i] << "\n";
  }
  md << "\n### " << kByAlphaTitle << "\n\n(" << kByAlphaNote << ")\n\n";
  for (const std::string& line : by_alpha_lines(table)) md << "- " << line << "\n";
  return md.str();
}

std::string markdown_taa(const TaaSection& taa) {
  std::ostringstream md;
  md << "## " << kTaaTitle << "\n\n(" << taa.note << ")\n\n";
  for (const std::string& verdict : taa.verdicts) md << "- " << verdict << "\n";
  md << "\n" << as_markdown(taa.table) << "\n" << kTaaImageNote << "\n\n";
  for (const Strip& strip : taa.strips) md << "![" << strip.caption << "](" << strip.file << ")\n\n";
  return md.str();
}

std::string markdown_loss_lists(const measure::TradeTable& table) {
  std::ostringstream md;
  md << "## " << kLossListTitle << "\n\n";
  for (const auto& [heading, items] : loss_lists(table)) {
    md << "- " << heading << "\n";
    for (const std::string& item : items) md << "  - " << item << "\n";
  }
  return md.str();
}

std::string html_figure(const Strip& strip) {
  return "<figure><img src=\"" + strip.file + "\" alt=\"" + html_escape(strip.caption) + "\"><figcaption>" + html_escape(strip.caption) +
         "</figcaption></figure>\n";
}

std::string html_taa(const TaaSection& taa) {
  std::string html = "<h2>" + html_escape(kTaaTitle) + "</h2>\n<p>(" + html_escape(taa.note) + ")</p>\n<ul>\n";
  for (const std::string& verdict : taa.verdicts) html += "<li>" + html_escape(verdict) + "</li>\n";
  html += "</ul>\n" + as_html(taa.table) + "<p>" + html_escape(kTaaImageNote) + "</p>\n";
  for (const Strip& strip : taa.strips) html += html_figure(strip);
  return html;
}

std::string html_verdict(const measure::TradeTable& table) {
  std::string html =
      fmt::format("<h2>{}</h2>\n<p>({})</p>\n<ul class=\"verdict\">\n", html_escape(kVerdictTitle), html_escape(verdict_note(table)));
  for (const Verdict& v : ordered_verdicts(table)) {
    const std::vector<std::string> lines = verdict_lines(v);
    html += "<li><b>" + html_escape(lines.front()) + "</b>";
    for (std::size_t i = 1; i < lines.size(); ++i) html += "<br>" + html_escape(lines[i]);
    html += "</li>\n";
  }
  html += fmt::format("</ul>\n<h3>{}</h3>\n<p>({})</p>\n<ul>\n", html_escape(kByAlphaTitle), html_escape(kByAlphaNote));
  for (const std::string& line : by_alpha_lines(table)) html += "<li>" + html_escape(line) + "</li>\n";
  return html + "</ul>\n";
}

std::string html_loss_lists(const measure::TradeTable& table) {
  std::string html = fmt::format("<h2>{}</h2>\n<ul>\n", html_escape(kLossListTitle));
  for (const auto& [heading, items] : loss_lists(table)) {
    html += "<li>" + html_escape(heading) + "<ul>";
    for (const std::string& item : items) html += "<li>" + html_escape(item) + "</li>";
    html += "</ul></li>\n";
  }
  return html + "</ul>\n";
}

}  // namespace

TaaSection taa_section(const measure::TradeTable& taa) {
  TaaSection section;
  section.note = taa_note(taa);
  section.table.headers = taa_headers();
  section.table.headers.insert(section.table.headers.begin(), "scene");
  for (const TaaComparison& comparison : taa_comparisons(taa)) {
    for (const TaaComparisonRow& row : comparison.rows) {
      std::vector<std::string> columns = taa_columns(row);
      columns.insert(columns.begin(), std::string(measure::scene_name(comparison.scene)));
      section.table.rows.push_back(std::move(columns));
    }
    section.verdicts.push_back(std::string(measure::scene_name(comparison.scene)) + ": " + comparison.verdict);
    if (std::optional<Strip> strip = taa_strip(taa, comparison)) section.strips.push_back(std::move(*strip));
  }
  return section;
}

std::string markdown_report(const measure::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs,
                            const std::vector<std::string>& sheets, const std::vector<std::string>& plots,
                            const std::vector<Strip>& image_strips, const TaaSection* taa) {
  std::ostringstream md;
  md << "<!-- " << output_tag << " report -->\n# saagen speed/accuracy trade report\n\n" << markdown_verdict(table) << "\n";
  for (const Strip& strip : image_strips) md << "![" << strip.caption << "](" << strip.file << ")\n\n";
  md << "## " << kTradeTitle << "\n\n" << kTradeNote << "\n\n";
  for (const std::string& plot : plots) md << "![" << plot << "](" << plot << ")\n\n";
  if (taa) md << markdown_taa(*taa);
  md << config_line(table) << ".\n\n" << kMetricNote << "\n\n";
  if (costs) md << "Cost: " << costs->describe() << ".\n\n";
  for (const TitledTable& finding : finding_tables(table, costs))
    md << "## " << finding.title << "\n\n" << as_markdown(finding.table) << "\n";
  md << markdown_loss_lists(table);
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

std::string html_report(const measure::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs,
                        const std::vector<std::string>& sheets, const std::vector<std::string>& plots,
                        const std::vector<std::string>& columns, const std::vector<Strip>& image_strips, const TaaSection* taa) {
  std::ostringstream html;
  html << html_head() << html_verdict(table);
  html << "<h2>Per scene: ground truth, no SAA, best engine form, recommendation</h2>\n<p>Top: images; bottom: tonemapped difference "
          "from the ground truth (red brighter, blue darker, full colour at 0.25).</p>\n";
  for (const Strip& strip : image_strips) html << html_figure(strip);
  html << "<h2>" << html_escape(kTradeTitle) << "</h2>\n<p>" << html_escape(kTradeNote) << "</p>\n";
  for (const std::string& plot : plots) html << "<img src=\"" << plot << "\" alt=\"" << plot << "\">\n";
  if (taa) html << html_taa(*taa);
  html << "<p>" << html_escape(config_line(table)) << "</p>\n<p>" << html_escape(kMetricNote) << "</p>\n";
  if (costs) html << "<p>Cost: " << html_escape(costs->describe()) << ".</p>\n";
  for (const TitledTable& finding : finding_tables(table, costs))
    html << "<h2>" << html_escape(finding.title) << "</h2>\n" << as_html(finding.table);
  html << html_loss_lists(table);
  html << "<h2>Summary (means over every scene and alpha, no Fresnel)</h2>\n" << as_html(summary_table(summary, costs));
  for (Content content : kContents)
    html << "<h2>" << content_name(content) << " scenes</h2>\n" << as_html(content_table(table, content, costs));
  html << "<h2>Images</h2>\n<p>Columns: " << html_escape(fmt::format("{}", fmt::join(columns, ", ")))
       << ". Top: images; bottom: tonemapped difference from the ground truth (red brighter, blue darker, full colour at 0.25).</p>\n";
  for (const std::string& sheet : sheets) html << "<h3>" << sheet << "</h3>\n<img src=\"" << sheet << "\" alt=\"" << sheet << "\">\n";
  html << "<h2>Every case</h2>\n" << as_html(cases_table(table));
  html << kHtmlTail;
  return html.str();
}

}  // namespace saagen::report

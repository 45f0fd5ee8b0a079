// The report's pages: DIR/report.md and DIR/index.html, the verdict first, then the strips, the
// trade plots, the section under TAA, the findings and every table.
#pragma once

#include "strips.hpp"
#include "text_table.hpp"

#include "saagen/measure/trade.hpp"
#include "saagen/report/cost_table.hpp"
#include "saagen/report/summary.hpp"

#include <string>
#include <vector>

namespace saagen::report {

// The "With TAA" section (from the table with its +taa rows): what the figures are, the per-scene
// comparison (taa_comparisons) as a table, per scene the decision's reason and the strip.
struct TaaSection {
  std::string note;
  TextTable table;
  std::vector<std::string> verdicts;  // per scene, the decision's reason under TAA
  std::vector<Strip> strips;
};
TaaSection taa_section(const measure::TradeTable& taa);

// The pages linking the files written beside them: the sheets, the plots and the strips by file
// name; `columns` the sheets' column labels; `taa` the section under TAA, or nullptr.
std::string markdown_report(const measure::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs,
                            const std::vector<std::string>& sheets, const std::vector<std::string>& plots,
                            const std::vector<Strip>& image_strips, const TaaSection* taa);
std::string html_report(const measure::TradeTable& table, const std::vector<VariantSummary>& summary, const CostTable* costs,
                        const std::vector<std::string>& sheets, const std::vector<std::string>& plots,
                        const std::vector<std::string>& columns, const std::vector<Strip>& image_strips, const TaaSection* taa);

}  // namespace saagen::report

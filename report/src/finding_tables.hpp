// The findings (findings.hpp) and the summaries as tables (text_table.hpp), for the terminal and
// the report pages.
#pragma once

#include "text_table.hpp"

#include "saagen/measure/trade.hpp"
#include "saagen/report/cost_table.hpp"
#include "saagen/report/findings.hpp"
#include "saagen/report/summary.hpp"

#include <string>
#include <vector>

namespace saagen::report {

// One row per configuration (means), with the cost columns when known.
TextTable summary_table(const std::vector<VariantSummary>& summary, const CostTable* costs);
// One row per configuration measured on the content's scenes (means over them).
TextTable content_table(const measure::TradeTable& table, Content content, const CostTable* costs);
// One row per case (scene, alpha, Fresnel, configuration).
TextTable cases_table(const measure::TradeTable& table);

// A table with the heading it is printed under.
struct TitledTable {
  std::string title;
  TextTable table;
};
// The findings in order: the recommendation per path and content, the engine switches, the
// per-scene verdicts.
std::vector<TitledTable> finding_tables(const measure::TradeTable& table, const CostTable* costs);

}  // namespace saagen::report

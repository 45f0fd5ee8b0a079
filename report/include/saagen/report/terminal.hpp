// What `saagen bench` and `saagen report` print on the terminal: the summary, the findings and the
// short verdict as plain-text tables and lines.
#pragma once

#include "saagen/measure/trade.hpp"
#include "saagen/report/cost_table.hpp"
#include "saagen/report/summary.hpp"

#include <string>
#include <vector>

namespace saagen::report {

// Terminal table: one row per variant (means), with the cost columns when known.
std::string format_summary(const std::vector<VariantSummary>& summary, const CostTable* costs);

// The findings (findings.hpp) as terminal tables: recommendation per path and content, engine
// switches, per-scene verdicts.
std::string format_findings(const measure::TradeTable& table, const CostTable* costs);

// The short verdict (findings.hpp, verdicts()): per render path and content type, what to use,
// how much it beats no SAA and the best engine form in LDR-FLIP and TDE, and where it loses.
// Printed last by `saagen bench` and `saagen report`, and at the top of the report.
std::string format_verdict(const measure::TradeTable& table);

}  // namespace saagen::report

// The terminal's tables and verdict (see terminal.hpp).
#include "saagen/report/terminal.hpp"

#include "finding_tables.hpp"
#include "verdict_text.hpp"

#include <fmt/format.h>

namespace saagen::report {

std::string format_summary(const std::vector<VariantSummary>& summary, const CostTable* costs) {
  return as_text(summary_table(summary, costs));
}

std::string format_findings(const measure::TradeTable& table, const CostTable* costs) {
  std::string text;
  for (const TitledTable& finding : finding_tables(table, costs)) text += "\n" + finding.title + ":\n" + as_text(finding.table);
  return text;
}

std::string format_verdict(const measure::TradeTable& table) {
  std::string text = fmt::format("{}\n({}):\n", kVerdictTitle, verdict_note(table));
  for (const Verdict& v : ordered_verdicts(table)) {
    const std::vector<std::string> lines = verdict_lines(v);
    text += "  " + lines.front() + "\n";
    for (std::size_t i = 1; i < lines.size(); ++i) text += "      " + lines[i] + "\n";
  }
  text += fmt::format("\n{}\n({}):\n", kByAlphaTitle, kByAlphaNote);
  for (const std::string& line : by_alpha_lines(table)) text += "  " + line + "\n";
  return text;
}

}  // namespace saagen::report

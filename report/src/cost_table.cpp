// The measured costs the report joins with the trade table (see cost_table.hpp): bench_shading's
// --json file read, ACO's ratios added.
#include "saagen/report/cost_table.hpp"

#include "saagen/scene/cost_tables.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>

namespace saagen::report {
namespace {

namespace fs = std::filesystem;

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (double value : values) sum += value;
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
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

// bench_shading's rows are read by the planner's parser (saagen/scene/cost_tables.hpp), the one
// reader of the schema; the report keeps each variant's means over the targets.
CostTable load_cost_table(const fs::path& path) {
  const MeasuredTradeTable measured = load_trade_table(path);
  CostTable table;
  table.source = path.string();
  table.device = measured.device;
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> by_variant;
  std::vector<std::string> order;
  for (const MeasuredTradeRow& row : measured.rows) {
    if (!by_variant.count(row.variant)) order.push_back(row.variant);
    auto& [ratios, deltas] = by_variant[row.variant];
    if (row.cost_ratio) ratios.push_back(*row.cost_ratio);
    if (row.delta_instructions) deltas.push_back(*row.delta_instructions);
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

}  // namespace saagen::report

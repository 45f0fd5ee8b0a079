// The measured costs the report joins with the trade table (see cost_table.hpp): each variant's
// means read from the planner's two tables.
#include "saagen/report/cost_table.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <vector>

namespace saagen::report {

std::optional<VariantCost> CostTable::find(std::string_view variant) const {
  VariantCost cost{timing.mean(variant, &MeasuredTradeRow::cost_ratio), timing.mean(variant, &MeasuredTradeRow::delta_instructions),
                   std::nullopt};
  if (isa) cost.isa_ratio = isa->forward_ratio(isa_family, variant, {}, 1);
  if (!cost.time_ratio && !cost.delta_instructions && !cost.isa_ratio) return std::nullopt;
  return cost;
}

std::string CostTable::describe() const {
  std::vector<std::string> models;
  if (isa)
    models.push_back(fmt::format("ISA inv.thr: ACO inverse-throughput ratio on RADV {} (null hardware, `saagen bench --isa`)", isa_family));
  if (!source.empty()) models.push_back(fmt::format("time ratio and dSPIR-V: {} ({})", source, timing.device));
  return models.empty() ? std::string("no cost model") : fmt::format("{}", fmt::join(models, "; "));
}

std::shared_ptr<const MeasuredTradeTable> CostTable::decision_timing() const {
  if (!timing.is_device_timing() || timing.timed_on_cpu()) return nullptr;
  return std::make_shared<const MeasuredTradeTable>(timing);
}

CostTable load_cost_table(const std::filesystem::path& path) {
  CostTable table;
  table.source = path.string();
  table.timing = load_trade_table(path);
  return table;
}

}  // namespace saagen::report

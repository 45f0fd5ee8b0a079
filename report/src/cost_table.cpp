// The measured costs the report joins with the trade table (see cost_table.hpp): bench_shading's
// --json file read, ACO's ratios added.
#include "saagen/report/cost_table.hpp"

#include "saagen/error.hpp"
#include "saagen/io/input.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

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

}  // namespace saagen::report

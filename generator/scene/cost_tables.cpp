#include "saagen/scene/cost_tables.hpp"

#include "saagen/error.hpp"
#include "saagen/io/input.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>

namespace saagen {
namespace embedded {
const std::map<std::string, std::string_view>& files();
}

namespace {

std::optional<double> mean_of(const std::vector<MeasuredTradeRow>& rows, std::string_view variant,
                              std::optional<double> MeasuredTradeRow::*field) {
  double sum = 0.0;
  int count = 0;
  for (const MeasuredTradeRow& row : rows) {
    if (row.variant == variant && (row.*field)) {
      sum += *(row.*field);
      ++count;
    }
  }
  if (count == 0) return std::nullopt;
  return sum / count;
}

// A by_content row's "against_none": {"image": {"mean", "low", "high"}, "temporal": {...}} and,
// in tables that measured it, "lag": {...}; low <= mean <= high, finite.
decision::Comparison parse_comparison(const nlohmann::json& value, std::string_view key, std::string_view where) {
  const auto difference = [&](const char* metric) {
    const auto fail = [&] {
      throw Error(
          fmt::format("{}: \"{}\" needs \"{}\": {{\"mean\", \"low\", \"high\"}}, finite numbers, low <= mean <= high", where, key, metric));
    };
    if (!value.is_object() || !value.contains(metric) || !value[metric].is_object()) fail();
    decision::Difference d;
    for (auto [key, field] :
         {std::pair{"mean", &decision::Difference::mean}, {"low", &decision::Difference::low}, {"high", &decision::Difference::high}}) {
      const nlohmann::json& number = value[metric].contains(key) ? value[metric][key] : nlohmann::json();
      if (!number.is_number() || !std::isfinite(number.get<double>())) fail();
      d.*field = number.get<double>();
    }
    if (!(d.low <= d.mean && d.mean <= d.high)) fail();
    return d;
  };
  const decision::Difference lag = value.is_object() && value.contains("lag") ? difference("lag") : decision::exact(0.0);
  if (value.contains("unconverged") && !value["unconverged"].is_boolean())
    throw Error(fmt::format("{}: \"{}\": \"unconverged\" must be true or false", where, key));
  return {difference("image"), difference("temporal"), lag, value.value("unconverged", false)};
}

// A content row's list of names under `key` (`saagen bench --json`): "loses_on", the content's
// scenes where the configuration loses to no SAA beyond the interval; "not_worse_than", the
// configurations it ties with or beats. Absent: none known.
std::vector<std::string> parse_names(const nlohmann::json& row, std::string_view key, std::string_view what, std::string_view where) {
  std::vector<std::string> names;
  if (!row.is_object() || !row.contains(key)) return names;
  const nlohmann::json& value = row[key];
  const auto bad = [&] { return Error(fmt::format("{}: \"{}\" must be an array of {} names", where, key, what)); };
  if (!value.is_array()) throw bad();
  for (const nlohmann::json& name : value) {
    if (!name.is_string() || name.get<std::string>().empty()) throw bad();
    names.push_back(name.get<std::string>());
  }
  return names;
}

// A row's cells under `key` ("loses_at", "held_out_loses_at"): [{"scene": NAME, "alpha": A}], A a
// GGX alpha in (0, 1]. Absent: none known.
std::vector<CellLoss> parse_cells(const nlohmann::json& row, std::string_view key, std::string_view where) {
  std::vector<CellLoss> cells;
  if (!row.is_object() || !row.contains(key)) return cells;
  const auto bad = [&] {
    return Error(fmt::format("{}: \"{}\" must be an array of {{\"scene\": NAME, \"alpha\": A}}, A in (0, 1]", where, key));
  };
  const nlohmann::json& value = row[key];
  if (!value.is_array()) throw bad();
  for (const nlohmann::json& cell : value) {
    if (!cell.is_object() || !cell.contains("scene") || !cell["scene"].is_string() || cell["scene"].get<std::string>().empty() ||
        !cell.contains("alpha") || !cell["alpha"].is_number())
      throw bad();
    const double alpha = cell["alpha"].get<double>();
    if (!(alpha > 0.0 && alpha <= 1.0)) throw bad();
    cells.push_back({cell["scene"].get<std::string>(), alpha});
  }
  return cells;
}

// A content row's "loses_on", "not_worse_than" and "loses_at" (ContentRow).
void parse_pairings(const nlohmann::json& row, ContentRow& out, std::string_view where) {
  out.loses_on = parse_names(row, "loses_on", "scene", where);
  out.not_worse_than = parse_names(row, "not_worse_than", "configuration", where);
  out.loses_at = parse_cells(row, "loses_at", where);
}

// A document's "alphas": the GGX alphas it measured, ascending, each in (0, 1]. Absent: none given.
std::vector<double> parse_alphas(const nlohmann::json& document, std::string_view where) {
  std::vector<double> alphas;
  if (!document.is_object() || !document.contains("alphas")) return alphas;
  const auto bad = [&] { return Error(fmt::format("{}: \"alphas\" must be an ascending array of GGX alphas in (0, 1]", where)); };
  if (!document["alphas"].is_array()) throw bad();
  for (const nlohmann::json& alpha : document["alphas"]) {
    if (!alpha.is_number() || !(alpha.get<double>() > 0.0 && alpha.get<double>() <= 1.0)) throw bad();
    if (!alphas.empty() && alpha.get<double>() <= alphas.back()) throw bad();
    alphas.push_back(alpha.get<double>());
  }
  return alphas;
}

// One content row in the schema every writer of one uses (a trade table's "by_content" and
// "taa_by_content", the advice's "rows"; ContentRow): "configuration"; the image error
// "image_error" (the verdict's: LDR-FLIP per frame; tables written before it: "error"); the
// temporal error "video_error" (10 - ColorVideoVDP's JOD), else "flicker_error" (tables without
// the video metric), else "tde" (tables written before either); "against_none" with its
// intervals; "loses_on", "not_worse_than" and "loses_at". `content`: the row's own "content" when
// empty (the advice names it once per entry). `where` names the row in messages.
ContentRow parse_content_row(const nlohmann::json& row, std::string_view where, std::string content = {}) {
  if (!row.is_object()) throw Error(fmt::format("{}: must be an object", where));
  const auto text = [&](const char* key) {
    if (!row.contains(key) || !row[key].is_string()) throw Error(fmt::format("{}: needs a string \"{}\"", where, key));
    return row[key].get<std::string>();
  };
  const auto number = [&](const char* key) -> std::optional<double> {
    if (!row.contains(key)) return std::nullopt;
    if (!row[key].is_number() || !std::isfinite(row[key].get<double>()))
      throw Error(fmt::format("{}: \"{}\" must be a finite number", where, key));
    return row[key].get<double>();
  };
  if (content.empty()) content = text("content");
  ContentRow entry{std::move(content), text("configuration"), 0.0, std::nullopt, std::nullopt};
  const std::optional<double> image = row.contains("image_error") ? number("image_error") : number("error");
  if (!image) throw Error(fmt::format("{}: needs a number \"image_error\" (tables written before it: \"error\")", where));
  entry.error = *image;
  entry.temporal = row.contains("video_error")     ? number("video_error")
                   : row.contains("flicker_error") ? number("flicker_error")
                                                   : number("tde");
  if (row.contains("against_none")) entry.against_none = parse_comparison(row["against_none"], "against_none", where);
  parse_pairings(row, entry, where);
  return entry;
}

// A "lights" value of the ISA table's rows or of bench_shading's table: an integer from 1 to
// kMaxLights, else nullopt (each caller says what its "lights" counts).
std::optional<int> read_light_count(const nlohmann::json& lights) {
  if (!lights.is_number_integer() || lights.get<std::int64_t>() < 1 || lights.get<std::int64_t>() > kMaxLights) return std::nullopt;
  return static_cast<int>(lights.get<std::int64_t>());
}

// A cost table row's shared keys (cost_tables.hpp, "The cost table").
struct CostRowKeys {
  std::string device;  // "" where absent
  std::string shader;  // "" where absent
  OutputTarget target;
  std::string variant;
  int lights = 1;
  std::optional<double> cost_ratio;
};

// The keys every cost table row shares (cost_tables.hpp, "The cost table"), each checked; `fail`
// throws with the row's place. Absent keys stay empty (lights: 1), for the caller to require.
CostRowKeys read_cost_row(const nlohmann::json& row, const std::function<void(std::string_view)>& fail) {
  if (!row.is_object()) fail("must be an object");
  const auto text = [&](const char* key) -> std::string {
    if (!row.contains(key)) return {};
    if (!row[key].is_string()) fail(fmt::format("\"{}\" must be a string", key));
    return row[key].get<std::string>();
  };
  CostRowKeys keys;
  keys.variant = text("variant");
  if (keys.variant.empty()) fail("needs a string \"variant\"");
  keys.device = text("device");
  keys.shader = text("shader");
  if (row.contains("target")) keys.target = OutputTarget::named(text("target"));
  if (row.contains("lights")) {
    const auto lights = read_light_count(row["lights"]);
    if (!lights) fail(fmt::format("\"lights\" must be an integer from 1 to {} (absent: one light)", kMaxLights));
    keys.lights = *lights;
  }
  if (row.contains("cost_ratio")) {
    const nlohmann::json& ratio = row["cost_ratio"];
    if (!ratio.is_number() || !std::isfinite(ratio.get<double>()) || ratio.get<double>() <= 0.0)
      fail("\"cost_ratio\" must be a positive finite number");
    keys.cost_ratio = ratio.get<double>();
  }
  return keys;
}

}  // namespace

std::vector<double> bracketing_alphas(const std::vector<double>& measured, AlphaRange range) {
  const auto matches = [](double alpha, double end) { return std::fabs(alpha - end) <= kAlphaMatch * end; };
  const auto matched = [&](double end) { return std::any_of(measured.begin(), measured.end(), [&](double m) { return matches(m, end); }); };
  const bool low_matched = matched(range.low), high_matched = matched(range.high);
  std::vector<double> judged;
  for (std::size_t i = 0; i < measured.size(); ++i) {
    const double m = measured[i];
    const bool inside = (m >= range.low && m <= range.high) || matches(m, range.low) || matches(m, range.high);
    // Where an end lies between two measured alphas: the nearest measured one beyond it (the
    // largest below the range, the smallest above it; the end one when all lie on one side).
    const bool below = !low_matched && m < range.low && (i + 1 == measured.size() || measured[i + 1] > range.low);
    const bool above = !high_matched && m > range.high && (i == 0 || measured[i - 1] < range.high);
    if (inside || below || above) judged.push_back(m);
  }
  return judged;
}

std::vector<std::string> cells_lost_at(const std::vector<CellLoss>& losses, const std::vector<double>& alphas) {
  std::vector<std::string> lost;
  for (const CellLoss& cell : losses)
    if (std::find(alphas.begin(), alphas.end(), cell.alpha) != alphas.end())
      lost.push_back(fmt::format("{} at alpha {:g}", cell.scene, cell.alpha));
  return lost;
}

void add_cell_losses(ContentRow& row, const std::vector<double>& alphas) {
  for (std::string& cell : cells_lost_at(row.loses_at, alphas)) row.loses_on.push_back(std::move(cell));
}

std::optional<double> MeasuredTradeTable::mean(std::string_view variant, std::optional<double> MeasuredTradeRow::*figure) const {
  return mean_of(rows, variant, figure);
}

std::optional<double> MeasuredTradeTable::cost(std::string_view variant) const {
  const bool any_ratio = std::any_of(rows.begin(), rows.end(), [](const MeasuredTradeRow& row) { return row.cost_ratio.has_value(); });
  return mean_of(rows, variant, any_ratio ? &MeasuredTradeRow::cost_ratio : &MeasuredTradeRow::delta_instructions);
}

std::optional<double> MeasuredTradeTable::error(std::string_view variant) const { return mean_of(rows, variant, &MeasuredTradeRow::error); }

std::optional<double> MeasuredTradeTable::device_time_ratio(std::string_view variant) const {
  if (!device_timing) return std::nullopt;
  return mean_of(rows, variant, &MeasuredTradeRow::cost_ratio);
}

std::optional<double> MeasuredTradeTable::isa_cost(std::string_view variant, std::string_view family) const {
  std::vector<MeasuredTradeRow> of_family;
  for (const MeasuredTradeRow& row : rows) {
    if (row.isa_family == family) of_family.push_back(row);
  }
  return mean_of(of_family, variant, &MeasuredTradeRow::isa_ratio);
}

std::vector<int> IsaTable::light_counts(std::string_view family) const {
  std::vector<int> counts;
  for (const IsaRow& row : rows)
    if (row.family == family && row.shader == "forward" && std::find(counts.begin(), counts.end(), row.lights) == counts.end())
      counts.push_back(row.lights);
  std::sort(counts.begin(), counts.end());
  return counts;
}

int IsaTable::cost_light_count(std::string_view family, int lights) const {
  const std::vector<int> counts = light_counts(family);
  if (counts.empty()) return lights;
  int chosen = counts.front();
  for (const int count : counts)
    if (count <= lights) chosen = count;
  return chosen;
}

std::optional<double> IsaTable::forward_ratio(std::string_view family, std::string_view variant, const std::vector<OutputTarget>& targets,
                                              int lights) const {
  const int measured = cost_light_count(family, lights);
  double sum = 0.0;
  int count = 0;
  for (const IsaRow& row : rows) {
    if (row.family != family || row.shader != "forward" || row.variant != variant || row.lights != measured) continue;
    if (!targets.empty() && std::find(targets.begin(), targets.end(), row.target) == targets.end()) continue;
    sum += row.inverse_throughput_ratio;
    ++count;
  }
  if (count == 0) return std::nullopt;
  return sum / count;
}

IsaTable parse_isa_table(std::string_view json_text, std::string_view source_name) {
  IsaTable table;
  table.source_name = std::string(source_name);
  const auto fail = [&](std::string_view what) {
    throw Error(
        fmt::format("{}: {}; regenerate it with `saagen bench --isa vega10,navi21 --isa-only --isa-table FILE`", source_name, what));
  };
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::parse_error& error) {
    fail(fmt::format("not valid JSON (byte {})", error.byte));
  } catch (const nlohmann::json::exception&) {  // out_of_range.406: a number such as 1e999
    fail("holds a number beyond a double's range");
  }
  if (!document.is_object() || !document.contains("rows") || !document["rows"].is_array() || !document.contains("families") ||
      !document["families"].is_array()) {
    fail("needs \"families\" and \"rows\" arrays");
  }
  table.driver = document.value("driver", std::string());
  for (const auto& family : document["families"]) {
    if (!family.is_string()) fail("\"families\" must hold strings");
    table.families.push_back(family.get<std::string>());
  }
  if (document.contains("devices")) {
    const nlohmann::json& devices = document["devices"];
    if (!devices.is_object()) fail("\"devices\" must be an object of strings");
    for (const auto& [family, device] : devices.items()) {
      if (!device.is_string()) fail("\"devices\" must be an object of strings");
      table.devices[family] = device.get<std::string>();
    }
  }
  for (std::size_t index = 0; index < document["rows"].size(); ++index) {
    const nlohmann::json& row = document["rows"][index];
    const auto row_fail = [&](std::string_view what) { fail(fmt::format("rows[{}]: {}", index, what)); };
    const CostRowKeys keys = read_cost_row(row, row_fail);
    if (keys.device.empty() || keys.shader.empty() || !row.contains("target") || !keys.cost_ratio)
      row_fail("needs the cost table's \"device\", \"shader\", \"target\" and \"cost_ratio\"");
    const auto number = [&](const char* key) {
      if (!row.contains(key) || !row[key].is_number() || !std::isfinite(row[key].get<double>()))
        row_fail(fmt::format("needs a finite \"{}\"", key));
      return row[key].get<double>();
    };
    IsaRow entry{keys.device, keys.shader, keys.target, keys.variant};
    entry.instructions = number("instructions");
    entry.vgprs = number("vgprs");
    entry.sgprs = number("sgprs");
    entry.subgroups_per_simd = number("subgroups_per_simd");
    entry.latency = number("latency");
    entry.inverse_throughput = number("inverse_throughput");
    entry.inverse_throughput_ratio = *keys.cost_ratio;
    if (row.contains("instructions_ratio")) entry.instructions_ratio = number("instructions_ratio");
    if (row.contains("latency_ratio")) entry.latency_ratio = number("latency_ratio");
    entry.lights = keys.lights;
    table.rows.push_back(std::move(entry));
  }
  return table;
}

namespace {

// The text of a file embedded in the library (generator/CMakeLists.txt: saagen_embed_files).
std::string_view embedded_file(const char* name) {
  const auto& files = embedded::files();
  const auto found = files.find(name);
  if (found == files.end()) throw Error(fmt::format("internal error: {} is not embedded", name));
  return found->second;
}

}  // namespace

const IsaTable& committed_isa_costs() {
  static const IsaTable table = parse_isa_table(embedded_file("generator/data/isa_cost.json"), "generator/data/isa_cost.json");
  return table;
}

decision::Comparison comparison_against(const ContentRow& row, const ContentRow& baseline) {
  if (baseline.configuration == "none" && row.against_none) return *row.against_none;
  const double temporal = row.temporal && baseline.temporal ? *row.temporal - *baseline.temporal : 0.0;
  return {decision::exact(row.error - baseline.error), decision::exact(temporal), decision::exact(0.0)};
}

bool MeasuredTradeTable::has_errors() const {
  return std::any_of(rows.begin(), rows.end(), [](const MeasuredTradeRow& row) { return row.error.has_value(); });
}

namespace {

// One row of a cost table (bench_shading's; cost_tables.hpp, "The cost table") or of a trade
// table's "rows" (the same keys without device, shader and lights, with the trade's error and ISA
// ratio): each figure checked.
MeasuredTradeRow parse_cost_row(const nlohmann::json& row, std::size_t index, std::string_view source_name) {
  const auto fail = [&](std::string_view what) {
    throw Error(
        fmt::format("{}: rows[{}]: {}; allowed: {{\"variant\": ID, \"target\": NAME, \"device\": NAME, \"shader\": NAME, "
                    "\"lights\": N, \"cost_ratio\": number, \"delta_spirv_instructions\": number, \"error\": number}}",
                    source_name, index, what));
  };
  const auto number = [&](const char* key) -> std::optional<double> {
    if (!row.contains(key)) return std::nullopt;
    if (!row[key].is_number()) fail(fmt::format("\"{}\" must be a number", key));
    const double value = row[key].get<double>();
    if (!std::isfinite(value)) fail(fmt::format("\"{}\" must be finite", key));
    return value;
  };
  const CostRowKeys keys = read_cost_row(row, fail);
  MeasuredTradeRow entry;
  entry.variant = keys.variant;
  entry.target = keys.target;
  entry.cost_ratio = keys.cost_ratio;
  entry.delta_instructions = number("delta_spirv_instructions");
  entry.error = number("error");
  entry.isa_ratio = number("isa_inverse_throughput_ratio");
  if (entry.isa_ratio) {
    if (!row.contains("isa_family") || !row["isa_family"].is_string())
      fail("\"isa_inverse_throughput_ratio\" needs a string \"isa_family\"");
    entry.isa_family = row["isa_family"].get<std::string>();
    if (*entry.isa_ratio <= 0.0) fail("\"isa_inverse_throughput_ratio\" must be positive");
  }
  if (entry.error && *entry.error < 0.0) fail("\"error\" must not be negative");
  return entry;
}

// A table's content rows of `section`: "by_content" (against no SAA) or, under TAA,
// "taa_by_content" (against none+taa, named without "+taa"); the same form.
std::vector<ContentRow> parse_content_rows(const nlohmann::json& document, const char* section, std::string_view source_name) {
  std::vector<ContentRow> out;
  if (!document.contains(section)) return out;
  const nlohmann::json& content_rows = document[section];
  if (!content_rows.is_array()) throw Error(fmt::format("{}: \"{}\" must be an array", source_name, section));
  for (std::size_t index = 0; index < content_rows.size(); ++index)
    out.push_back(parse_content_row(content_rows[index], fmt::format("{}: {}[{}]", source_name, section, index)));
  return out;
}

// bench_shading's "lights" (1 where not given).
int parse_timed_lights(const nlohmann::json& document, std::string_view source_name) {
  if (!document.contains("lights")) return 1;
  const auto lights = read_light_count(document["lights"]);
  if (!lights)
    throw Error(
        fmt::format("{}: \"lights\" must be an integer from 1 to {} (the lights bench_shading --lights timed)", source_name, kMaxLights));
  return *lights;
}

// A bench table's "device_timing" (MeasuredTradeTable::decision_timing): bench_shading's table,
// under the name of the file it was read from ("source").
std::shared_ptr<const MeasuredTradeTable> parse_decision_timing(const nlohmann::json& document, std::string_view source_name) {
  if (!document.contains("device_timing")) return nullptr;
  const nlohmann::json& timing = document["device_timing"];
  const std::string where = fmt::format("{}: \"device_timing\"", source_name);
  // bench_shading's table has no "device_timing" of its own: one level, however the file nests.
  if (!timing.is_object() || !timing.contains("source") || !timing["source"].is_string() || timing.contains("device_timing"))
    throw Error(where + " must be an object with a string \"source\" (as `saagen bench --cost FILE --json` writes it)");
  auto table = std::make_shared<MeasuredTradeTable>(parse_trade_table(timing.dump(), where));
  if (!table->is_device_timing() || table->timed_on_cpu())
    throw Error(where + fmt::format(": not a GPU's timings (no \"{}\" row with a \"cost_ratio\", or a CPU device); "
                                    "pass the file `saagen bench --cost FILE --json` writes",
                                    kCostBaselineId));
  table->source_name = timing["source"].get<std::string>();
  return table;
}

// Whether `key` names the transported frame: "transported" or "tangent", absent being tangent (the
// frame of the tables and advice written before the key); nullopt for anything else.
std::optional<bool> names_transported_frame(const nlohmann::json& document, const char* key) {
  if (!document.contains(key)) return false;
  const nlohmann::json& frame = document[key];
  if (frame == "transported") return true;
  if (frame == "tangent") return false;
  return std::nullopt;
}

}  // namespace

MeasuredTradeTable parse_trade_table(std::string_view json_text, std::string_view source_name) {
  MeasuredTradeTable table;
  table.source_name = std::string(source_name);
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::parse_error& error) {
    throw Error(fmt::format("{}: not valid JSON (byte {}); pass the file `bench_shading --json` writes", source_name, error.byte));
  } catch (const nlohmann::json::exception&) {  // out_of_range.406: a number such as 1e999
    throw Error(fmt::format("{}: holds a number beyond a double's range; pass the file `bench_shading --json` writes", source_name));
  }
  if (!document.is_object() || !document.contains("rows") || !document["rows"].is_array()) {
    throw Error(fmt::format("{}: no \"rows\" array; pass the file `bench_shading --json` writes", source_name));
  }
  if (document.contains("device") && document["device"].is_string()) table.device = document["device"].get<std::string>();
  table.lights = parse_timed_lights(document, source_name);
  const nlohmann::json& rows = document["rows"];
  for (std::size_t index = 0; index < rows.size(); ++index) table.rows.push_back(parse_cost_row(rows[index], index, source_name));
  table.device_timing = std::any_of(table.rows.begin(), table.rows.end(),
                                    [](const MeasuredTradeRow& row) { return row.variant == kCostBaselineId && row.cost_ratio; });
  table.content_rows = parse_content_rows(document, "by_content", source_name);
  table.alphas = parse_alphas(document, source_name);
  table.taa_content_rows = parse_content_rows(document, "taa_by_content", source_name);
  const auto transported = names_transported_frame(document, "half_vector_frame");
  if (!transported)
    throw Error(fmt::format("{}: \"half_vector_frame\" must be \"tangent\" or \"transported\"; pass the file `saagen bench --json` writes",
                            source_name));
  table.forward_transported = *transported;
  table.decision_timing = parse_decision_timing(document, source_name);
  return table;
}

std::optional<decision::Comparison> AdviceMeasurement::held_out(std::string_view configuration) const {
  for (const auto& [name, comparison] : held_out_rows)
    if (name == configuration) return comparison;
  return std::nullopt;
}

std::vector<std::string> AdviceMeasurement::held_out_loses_on(std::string_view configuration) const {
  for (const auto& [name, scenes] : held_out_losses)
    if (name == configuration) return scenes;
  return {};
}

const AdviceMeasurement* AdviceTable::find(std::string_view content, bool taa, int map_lod) const {
  const AdviceMeasurement* found = nullptr;
  for (const AdviceMeasurement& entry : contents)
    if (entry.content == content && entry.taa == taa && entry.map_lod_min <= map_lod && (!found || entry.map_lod_min > found->map_lod_min))
      found = &entry;
  return found;
}

AdviceTable parse_advice_table(std::string_view json_text, std::string_view source_name) {
  const auto fail = [&](std::string_view what) {
    throw Error(fmt::format("{}: {}; regenerate it with scripts/advice_data.py", source_name, what));
  };
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::exception&) {
    fail("not valid JSON");
  }
  if (!document.is_object() || document.value("schema", "") != "saagen advice 1" || !document.contains("content") ||
      !document["content"].is_array())
    fail("not a \"saagen advice 1\" document with a \"content\" array");
  AdviceTable table;
  table.source_name = std::string(source_name);
  const auto described = [&](const char* key) {
    const nlohmann::json& from = document.value(key, nlohmann::json::object());
    return fmt::format("{} ({})", from.value("table", std::string("?")), from.value("config", std::string("?")));
  };
  table.derived_from = described("derived_from");
  table.held_out_from = described("held_out");
  const auto transported = names_transported_frame(document, "forward_half_vector_frame");
  if (!transported) fail("\"forward_half_vector_frame\" must be \"tangent\" or \"transported\"");
  table.forward_transported = *transported;
  const auto names = [&](const nlohmann::json& entry, const char* key) {
    std::vector<std::string> out;
    for (const nlohmann::json& name : entry.value(key, nlohmann::json::array()))
      if (name.is_string()) out.push_back(name.get<std::string>());
    return out;
  };
  for (std::size_t index = 0; index < document["content"].size(); ++index) {
    const nlohmann::json& entry = document["content"][index];
    if (!entry.is_object() || !entry.contains("content") || !entry["content"].is_string() || !entry.contains("rows") ||
        !entry["rows"].is_array())
      fail(fmt::format("content[{}] needs a string \"content\" and a \"rows\" array", index));
    AdviceMeasurement measured;
    measured.content = entry["content"].get<std::string>();
    if (entry.contains("taa") && !entry["taa"].is_boolean()) fail(fmt::format("content[{}]: \"taa\" must be true or false", index));
    if (entry.contains("baseline") && !entry["baseline"].is_string())
      fail(fmt::format("content[{}]: \"baseline\" must be a string", index));
    if (entry.contains("map_lod_min") && !(entry["map_lod_min"].is_number_unsigned() && entry["map_lod_min"].get<unsigned>() <= kMaxMapLod))
      fail(fmt::format("content[{}]: \"map_lod_min\" must be an integer from 0 to {}", index, kMaxMapLod));
    measured.taa = entry.value("taa", false);
    measured.map_lod_min = entry.value("map_lod_min", 0);
    measured.baseline = entry.value("baseline", measured.baseline);
    measured.scenes = names(entry, "scenes");
    measured.held_out_scenes = names(entry, "held_out_scenes");
    measured.alphas = parse_alphas(entry, fmt::format("{}: content[{}]", source_name, index));
    for (std::size_t row_index = 0; row_index < entry["rows"].size(); ++row_index) {
      const nlohmann::json& row = entry["rows"][row_index];
      const std::string where = fmt::format("{}: content[{}].rows[{}]", source_name, index, row_index);
      ContentRow kept = parse_content_row(row, where, measured.content);
      if (row.contains("held_out"))
        measured.held_out_rows.emplace_back(kept.configuration, parse_comparison(row["held_out"], "held_out", where));
      if (row.contains("held_out_loses_on"))
        measured.held_out_losses.emplace_back(kept.configuration, parse_names(row, "held_out_loses_on", "scene", where));
      if (row.contains("held_out_loses_at"))
        measured.held_out_cell_losses.emplace_back(kept.configuration, parse_cells(row, "held_out_loses_at", where));
      measured.rows.push_back(std::move(kept));
    }
    table.contents.push_back(std::move(measured));
  }
  return table;
}

const AdviceTable& committed_advice() {
  static const AdviceTable table = parse_advice_table(embedded_file("generator/data/advice.json"), "generator/data/advice.json");
  return table;
}

MeasuredTradeTable load_trade_table(const std::filesystem::path& path) {
  return parse_trade_table(read_input_file(path, table_size_limit, "the file `bench_shading --json` writes"), path.string());
}

}  // namespace saagen

#include "saagen/report/isa_cost.hpp"

#include "saagen/emit/emitter.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/io/output.hpp"
#include "saagen/products/deferred_pass.hpp"
#include "saagen/report/shading_scene.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/compiler.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <saagen/harness/isa.hpp>

namespace saagen::report {
namespace {

namespace hx = saagen::harness;

// The framebuffer size baked into the scene's literals; it changes no instruction.
constexpr std::uint32_t scene_size = 1024;

const char* const cost_model_name =
    "ISA statistics of Mesa's ACO compiler (RADV null-hardware device, RADV_FORCE_FAMILY): instructions, VGPRs, SGPRs, "
    "subgroups per SIMD, latency and inverse throughput estimates in cycles";

hx::IsaLayout scene_layout() { return {{hx::IsaBinding::storage_buffer(0), hx::IsaBinding::storage_buffer(1)}, 0, {VK_FORMAT_R32_SFLOAT}}; }

hx::IsaLayout pass_layout(bool tangents) {
  namespace abi = deferred_pass_abi;
  hx::IsaLayout layout;
  layout.bindings = {{abi::binding_normal, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE},
                     {abi::binding_roughness, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE},
                     {abi::binding_output, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}};
  if (tangents) layout.bindings.push_back({abi::binding_tangent, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE});
  layout.push_constant_bytes = sizeof(DeferredPassConstants);
  return layout;
}

std::vector<std::uint32_t> compute_spirv(const std::string& target, const std::string& name, const std::string& source) {
  CompileRequest request;
  request.language = builtin_target(target).language;
  request.stage = ShaderStage::compute;
  request.sources = {{name, source}};
  const CompileResult compiled = compile_to_spirv(request);
  if (!compiled.ok) throw Error(fmt::format("{} {}: does not compile: {}", target, name, compiled.log.substr(0, compiled.log.find('\n'))));
  std::vector<std::uint32_t> optimized = optimize_spirv(compiled.spirv, ClientApi::vulkan);
  if (optimized.empty()) throw Error(fmt::format("{} {}: spirv-opt failed", target, name));
  return optimized;
}

const EmittedFile& file_of(const std::vector<EmittedFile>& files, const std::string& variant) {
  for (const EmittedFile& file : files) {
    if (file.marker.variants.size() == 1 && file.marker.variants.front() == variant) return file;
  }
  throw Error(fmt::format("no emitted file for variant {}", variant));
}

// What the forward shader is measured with: bench_shading's variant cases (the projected forward
// forms' transported wrappers among them), plus the tangent-free form of deferred-max (with either
// lobe), which the trade measures as a configuration of its own.
struct ForwardCase {
  std::string id;
  std::string file_variant;  // the catalogue variant whose emitted file defines the wrapper
  SceneShading shading;
};

std::vector<ForwardCase> forward_cases() {
  std::vector<ForwardCase> cases;
  for (const VariantCase& variant : variant_cases()) cases.push_back({variant.id, catalogue_variant(variant), variant.shading});
  const std::string tangent_free = "    real filtered = deferred_max_tangent_free_fragment(alpha2_material, normal);\n";
  cases.push_back({"deferred-max-tangent-free", "deferred-max", deferred_lobe_shading(tangent_free, false)});
  cases.push_back({"deferred-max-tangent-free/tail", "deferred-max", deferred_lobe_shading(tangent_free, true)});
  return cases;
}

// One shader to measure: its SPIR-V, which is the same on every family, and its pipeline layout.
struct IsaShader {
  std::string variant;
  std::vector<std::uint32_t> spirv;
  hx::IsaLayout layout;
};

// The shaders measured against one baseline: one target's forward-shading shaders at one light
// count (against no SAA at that count), or one target's deferred passes (against the copy pass).
struct IsaGroup {
  const char* shader = isa_forward_shader;
  std::string target;
  std::uint32_t lights = 1;
  IsaShader baseline;
  std::vector<IsaShader> shaders;
};

// The forward-shading shaders of one target at one light count: the no-SAA baseline, then every
// variant.
IsaGroup forward_group(const std::string& target, std::uint32_t lights) {
  EmitOptions emit;
  emit.target = target;
  const std::vector<EmittedFile> files = emit_variants(Catalogue::builtin(), emit);
  const EmittedFile& brdf = file_of(files, "brdf-ggx");
  IsaGroup group{isa_forward_shader, target, lights, {}, {}};
  group.baseline = {
      isa_baseline,
      scene_shader_spirv(target, brdf.file_name, brdf.content, body_with(baseline_shading, scene_size, scene_size, lights), scene_size),
      scene_layout()};
  for (const ForwardCase& item : forward_cases()) {
    const EmittedFile& file = file_of(files, item.file_variant);
    group.shaders.push_back({item.id,
                             scene_shader_spirv(target, file.file_name, file.content + "\n" + brdf.content,
                                                body_with(item.shading, scene_size, scene_size, lights), scene_size),
                             scene_layout()});
  }
  return group;
}

// The deferred passes of one target: the copy baseline, then every pass.
IsaGroup deferred_group(const std::string& target, const std::vector<DeferredPass>& passes) {
  IsaGroup group{isa_deferred_shader, target, 1, {}, {}};
  group.baseline = {isa_baseline, compute_spirv(target, "deferred_copy", deferred_copy_source(target)), pass_layout(false)};
  for (const DeferredPass& pass : passes) {
    group.shaders.push_back({pass.kind.id, compute_spirv(target, pass.stem, pass.source(target)), pass_layout(pass.kind.tangents)});
  }
  return group;
}

// Every group: the forward shaders of each target at each light count, then the deferred passes
// of each target (the order of the table's rows within a family).
std::vector<IsaGroup> isa_groups() {
  const std::vector<DeferredPass> passes = emit_deferred_passes(Catalogue::builtin(), {});
  std::vector<IsaGroup> groups;
  for (const TargetSyntax* target : vulkan_targets())
    for (const std::uint32_t lights : kMeasuredLightCounts) groups.push_back(forward_group(target->name, lights));
  for (const TargetSyntax* target : vulkan_targets()) groups.push_back(deferred_group(target->name, passes));
  return groups;
}

// A measured shader's row: its statistics and their ratios to its group's baseline.
IsaRow isa_row(const std::string& family, const IsaGroup& group, const std::string& variant, const hx::IsaStatistics& statistics,
               const hx::IsaStatistics& baseline) {
  IsaRow row{family, group.shader, OutputTarget::named(group.target), variant};
  row.instructions = statistics.instructions;
  row.vgprs = statistics.vgprs;
  row.sgprs = statistics.sgprs;
  row.subgroups_per_simd = statistics.subgroups_per_simd;
  row.latency = statistics.latency;
  row.inverse_throughput = statistics.inverse_throughput;
  row.inverse_throughput_ratio = statistics.inverse_throughput / baseline.inverse_throughput;
  row.instructions_ratio = statistics.instructions / baseline.instructions;
  row.latency_ratio = statistics.latency / baseline.latency;
  row.lights = static_cast<int>(group.lights);
  return row;
}

// The rows of one group on one family: its baseline, then every shader.
void measure_group(const hx::IsaCompiler& compiler, const IsaGroup& group, IsaTable& table) {
  const bool forward = group.shader == std::string_view(isa_forward_shader);
  const auto statistics = [&](const IsaShader& shader) {
    return forward ? compiler.fragment(shader.spirv, shader.layout) : compiler.compute(shader.spirv, shader.layout);
  };
  const hx::IsaStatistics baseline = statistics(group.baseline);
  table.devices[compiler.family()] = baseline.device_name;
  table.rows.push_back(isa_row(compiler.family(), group, isa_baseline, baseline, baseline));
  for (const IsaShader& shader : group.shaders)
    table.rows.push_back(isa_row(compiler.family(), group, shader.variant, statistics(shader), baseline));
}

// Paper, Table 2: the Sponza ratio of a variant, when the paper measured it.
std::string paper_ratio(const std::string& variant) {
  for (const VariantCase& known : variant_cases()) {
    if (known.id == variant && known.paper_ms) {
      std::array<double, 3> ratios{};
      for (std::size_t scene = 0; scene < 3; ++scene) ratios[scene] = (*known.paper_ms)[scene] / paper_no_saa_ms[scene];
      return fmt::format("x{:.2f}-{:.2f}", *std::min_element(ratios.begin(), ratios.end()),
                         *std::max_element(ratios.begin(), ratios.end()));
    }
  }
  return "-";
}

}  // namespace

std::vector<std::string> parse_isa_families(const std::string& list) {
  std::vector<std::string> families;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, comma - start);
    const auto& known = hx::isa_families();
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      throw Error(fmt::format("--isa: unknown GPU family '{}'; allowed: {} (comma-separated)", name, fmt::join(known, ", ")));
    }
    if (std::find(families.begin(), families.end(), name) != families.end()) {
      throw Error(fmt::format("--isa {}: GPU family '{}' is named twice; name each once", list, name));
    }
    families.push_back(name);
    start = comma + 1;
  }
  return families;
}

IsaTable measure_isa_costs(const std::vector<std::string>& families, const IsaProgressFn& progress) {
  IsaTable table;
  table.source_name = "the measured ISA statistics";
  table.families = families;
  // The SPIR-V (glslang, then spirv-opt: most of the time) does not depend on the family: it is
  // compiled once, on the first family's turn, and only the ISA compilation runs per family.
  std::vector<IsaGroup> groups;
  for (const std::string& family : families) {
    if (progress) progress(fmt::format("ISA statistics on {}", family));
    const hx::IsaCompiler compiler(family);
    table.driver = compiler.driver_info();
    if (groups.empty()) groups = isa_groups();
    for (const IsaGroup& group : groups) measure_group(compiler, group, table);
  }
  return table;
}

std::string format_light_count_table(const IsaTable& table) {
  std::vector<std::string> variants;
  for (const IsaRow& row : table.rows) {
    if (row.shader == isa_forward_shader && row.variant != isa_baseline &&
        std::find(variants.begin(), variants.end(), row.variant) == variants.end())
      variants.push_back(row.variant);
  }
  std::string text =
      "\nCost as work grows: the forward-shading shader's inverse-throughput ratio to no SAA with the same lights (mean of GLSL\n"
      "and HLSL). A forward form filters each light's half vector and shades it (N x (filter + BRDF)); a deferred form\n"
      "computes its roughness (deferred-aniso: its tensor) once per pixel, as its G-buffer side does, then its lobe per light.\n";
  text += fmt::format("{:<30}", "configuration");
  for (const std::string& family : table.families) text += fmt::format(" | {:<8} {:>5} {:>5} {:>5}", family, "1", "4", "16");
  text += "  paper Table 2\n";
  for (const std::string& variant : variants) {
    text += fmt::format("{:<30}", variant);
    for (const std::string& family : table.families) {
      text += fmt::format(" | {:<8}", "");
      for (const std::uint32_t lights : kMeasuredLightCounts) {
        const auto ratio = table.forward_ratio(family, variant, {}, static_cast<int>(lights));
        text += ratio ? fmt::format(" {:>5.3f}", *ratio) : fmt::format(" {:>5}", "-");
      }
    }
    text += fmt::format("  {}\n", paper_ratio(variant));
  }
  return text +
         "columns: lights per pixel; a configuration's feed (:geometric) and prefilter (+toksvig, +lean) change its inputs, not\n"
         "its code: deferred-sum:geometric/tail costs what deferred-sum/tail does. The planner reads these ratios at a manifest's\n"
         "`lights` (the nearest measured count not above it). paper: Table 2's measured time ratio, forward shading at 8K\n";
}

std::string format_isa_table(const IsaTable& table) {
  std::string text = fmt::format("GPU cost model: {}; {}\n", cost_model_name, table.driver);
  std::string family, shader;
  for (const IsaRow& row : table.rows) {
    if (row.lights != 1) continue;  // the light-count table below has the other counts
    if (row.family != family || row.shader != shader) {
      family = row.family;
      shader = row.shader;
      const auto device = table.devices.find(family);
      text += fmt::format(
          "\n{} ({}), {} shader{}\n", family, device == table.devices.end() ? std::string("RADV") : device->second,
          shader == isa_forward_shader ? "forward-shading fragment" : "deferred-pass compute",
          shader == isa_forward_shader ? " (bench_shading's scene, one light; no SAA = unfiltered GGX)" : " (no SAA = the copy pass)");
      text += fmt::format("{:<26} {:<5} {:>6} {:>5} {:>5} {:>6} {:>8} {:>8} {:>9} {:>9} {:>9}  {}\n", "variant", "tgt", "instr", "VGPR",
                          "SGPR", "waves", "latency", "inv.thr", "x instr", "x inv.thr", "x latency",
                          shader == isa_forward_shader ? "paper Table 2" : "");
    }
    text += fmt::format("{:<26} {:<5} {:>6} {:>5} {:>5} {:>6} {:>8} {:>8} {:>9.3f} {:>9.3f} {:>9.3f}  {}\n", row.variant, row.target.name(),
                        row.instructions, row.vgprs, row.sgprs, row.subgroups_per_simd, row.latency, row.inverse_throughput,
                        row.instructions_ratio, row.inverse_throughput_ratio, row.latency_ratio,
                        shader == isa_forward_shader ? paper_ratio(row.variant) : "");
  }
  text +=
      "\ninstr: ISA instructions; waves: subgroups per SIMD (occupancy); latency, inv.thr: ACO's estimates in cycles per wave\n"
      "(inverse throughput: the cost at full occupancy); x ...: ratio to no SAA; paper: Tokuyoshi & Kaplanyan 2019 Table 2,\n"
      "measured time ratio on an RX Vega 56 (vega10) over Sponza, Bistro and San Miguel\n";
  return text + format_light_count_table(table);
}

nlohmann::json isa_json(const IsaTable& table) {
  nlohmann::json rows = nlohmann::json::array();
  for (const IsaRow& row : table.rows) {
    nlohmann::json entry = {{"device", row.family},
                            {"shader", row.shader},
                            {"target", row.target.name()},
                            {"variant", row.variant},
                            {"cost_ratio", row.inverse_throughput_ratio},
                            {"instructions", row.instructions},
                            {"vgprs", row.vgprs},
                            {"sgprs", row.sgprs},
                            {"subgroups_per_simd", row.subgroups_per_simd},
                            {"latency", row.latency},
                            {"inverse_throughput", row.inverse_throughput},
                            {"instructions_ratio", row.instructions_ratio},
                            {"latency_ratio", row.latency_ratio}};
    // The deferred pass runs once per pixel whatever the light count: its rows carry none.
    if (row.shader == isa_forward_shader) entry["lights"] = row.lights;
    rows.push_back(std::move(entry));
  }
  // "generator": the ownership tag, so that `--isa-table F` may rewrite its own file without --force.
  return {{"cost_model", fmt::format("{}; cost_ratio: the inverse throughput over no SAA's with as many lights", cost_model_name)},
          {"driver", table.driver},
          {"devices", table.devices},
          {"families", table.families},
          {"generator", std::string(output_tag) + " saagen bench --isa"},
          {"rows", rows}};
}

}  // namespace saagen::report

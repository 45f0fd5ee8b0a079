#include "saagen/products/deferred_pass.hpp"

#include "saagen/emit/emitter.hpp"
#include "saagen/emit/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/print/glue.hpp"
#include "saagen/products/spirv_library.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/compiler.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <sstream>

namespace saagen {

namespace {

std::string intrinsic_name(const TargetSyntax& target, const std::string& dialect_name) {
  const auto found = target.intrinsics.find(dialect_name);
  if (found == target.intrinsics.end()) return dialect_name;
  return found->second.substr(0, found->second.find('('));
}

std::string underscored(std::string text) {
  std::replace(text.begin(), text.end(), '-', '_');
  return text;
}

std::string upper_identifier(std::string_view text) {
  std::string result;
  for (const char c : text)
    result += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : '_';
  return result;
}

// The pass body in the template dialect: decode the G-buffer texels, build the frame, call the
// wrapper with every argument chosen by parameter name, encode and store.
// One statement per roughness domain other than alpha^2: `to = CONVERSION(from)` when the pass's
// domain flag is the domain's index (roughness_domains(): 0 alpha^2, 1 alpha, 2 perceptual,
// 3 smoothness; deferred_pass_abi), calling the conversions of templates/05-domains.saa.
std::string domain_conversions(std::string_view to, std::string_view from, std::string RoughnessDomain::*conversion) {
  std::string statements = "    ";
  const auto& domains = roughness_domains();
  for (std::size_t index = 0; index < domains.size(); ++index) {
    const std::string& function = domains[index].*conversion;
    if (!function.empty()) statements += fmt::format("if (saagen_domain == {}) {} = {}({});\n    else ", index, to, function, from);
  }
  return statements.substr(0, statements.size() - std::string_view("    else ").size());
}

// The template functions the pass calls besides its wrapper: every domain conversion.
std::vector<std::string> domain_conversion_functions() {
  std::vector<std::string> names;
  for (const RoughnessDomain& domain : roughness_domains()) {
    for (const std::string& name : {domain.to_alpha2, domain.from_alpha2}) {
      if (!name.empty()) names.push_back(name);
    }
  }
  return names;
}

std::string pass_body(const Function& wrapper, bool tangents) {
  std::string body =
      "    // The normal: signed, or unorm-encoded (n * 0.5 + 0.5); renormalised, since G-buffer\n"
      "    // encodings are not exactly unit. A zero normal (no surface) stays zero.\n"
      "    real4 saagen_normal_texel = SAAGEN_NORMAL_TEXEL;\n"
      "    real3 saagen_n = saagen_normal_texel.xyz;\n"
      "    if (SAAGEN_NORMAL_UNORM) saagen_n = saagen_n * 2.0 - 1.0;\n"
      "    saagen_n = saagen_n * rsqrt(max(dot(saagen_n, saagen_n), 1e-30));\n";
  if (tangents) {
    body +=
        "    // The frame: the tangent made orthogonal to the normal (Gram-Schmidt) and unit, the\n"
        "    // bitangent cross(n, t) times the sign in the tangent's w.\n"
        "    real4 saagen_tangent_texel = SAAGEN_TANGENT_TEXEL;\n"
        "    real3 saagen_t = saagen_tangent_texel.xyz;\n"
        "    if (SAAGEN_TANGENT_UNORM) saagen_t = saagen_t * 2.0 - 1.0;\n"
        "    saagen_t = saagen_t - saagen_n * dot(saagen_n, saagen_t);\n"
        "    saagen_t = saagen_t * rsqrt(max(dot(saagen_t, saagen_t), 1e-30));\n"
        "    real3 saagen_b = cross(saagen_n, saagen_t) * (saagen_tangent_texel.w < 0.0 ? -1.0 : 1.0);\n";
  }
  body +=
      "    // Roughness in, in its domain: alpha^2, alpha, perceptual r (alpha = r^2) or smoothness 1 - r.\n"
      "    real saagen_r = SAAGEN_ROUGHNESS;\n"
      "    int saagen_domain = SAAGEN_DOMAIN;\n"
      "    real saagen_alpha2 = saagen_r;\n";
  body += domain_conversions("saagen_alpha2", "saagen_r", &RoughnessDomain::to_alpha2);
  std::vector<std::string> arguments;
  for (const Parameter& parameter : wrapper.parameters) {
    if (parameter.name == "alpha2" && parameter.type == "real")
      arguments.push_back("saagen_alpha2");
    else if (parameter.name == "normal_ws")
      arguments.push_back("saagen_n");
    else if (parameter.name == "tangent_ws" && tangents)
      arguments.push_back("saagen_t");
    else if (parameter.name == "bitangent_ws" && tangents)
      arguments.push_back("saagen_b");
    else if (parameter.name == "frag_coord")
      arguments.push_back("saagen_frag_coord");
    else
      throw Error(fmt::format("{}: the deferred pass has no input for parameter {} {}", wrapper.name, parameter.type, parameter.name));
  }
  if (wrapper.return_type != "real") throw Error(fmt::format("{}: a deferred pass writes one real", wrapper.name));
  body += fmt::format(
      "    // Every lane calls the wrapper (its derivatives need the whole quad).\n"
      "    real saagen_filtered = {}({});\n"
      "    // Filtered roughness out, in the domain it came in.\n",
      wrapper.name, fmt::join(arguments, ", "));
  body += domain_conversions("saagen_filtered", "saagen_filtered", &RoughnessDomain::from_alpha2);
  body += "    SAAGEN_STORE(saagen_filtered);\n";
  return body;
}

// The names the pass skeletons (targets/*/deferred_pass.*) give the body: the G-buffer texels,
// flags and roughness as macros, the pixel centre, and the store.
const GlueSymbols& pass_glue_symbols() {
  static const GlueSymbols symbols{{{"SAAGEN_NORMAL_TEXEL", "real4"},
                                    {"SAAGEN_TANGENT_TEXEL", "real4"},
                                    {"SAAGEN_NORMAL_UNORM", "bool"},
                                    {"SAAGEN_TANGENT_UNORM", "bool"},
                                    {"SAAGEN_ROUGHNESS", "real"},
                                    {"SAAGEN_DOMAIN", "int"},
                                    {"saagen_frag_coord", "real2"}},
                                   {{"SAAGEN_STORE", "", {"real"}}}};
  return symbols;
}

// The pass in `table`'s language: its deferred pass skeleton (TargetSyntax::deferred_pass) around
// the emitted file and the body.
std::string pass_source(const Catalogue& catalogue, const TargetSyntax& table, const EmittedFile& file, const DeferredPassKind& kind,
                        const DeferredPassOptions& options, const std::string& header_comment) {
  const TargetSyntax target = table.with_prefix(options.prefix, macro_prefix(options.prefix));
  const auto& skeleton = target.deferred_pass;
  const bool fine = options.derivatives == PlainDerivative::fine;
  NameMap names;
  for (const Function& function : catalogue.functions()) names[function.name] = prefixed_name(options.prefix, function.name);
  const std::string body =
      print_glue(target, catalogue, pass_body(*catalogue.find_function(kind.wrapper), kind.tangents), names, pass_glue_symbols());
  const auto fill = [&](std::string text) {
    text = substitute(std::move(text), "{plain_ddx}", intrinsic_name(target, fine ? "ddx_fine" : "ddx_coarse"));
    text = substitute(std::move(text), "{plain_ddy}", intrinsic_name(target, fine ? "ddy_fine" : "ddy_coarse"));
    text = substitute(std::move(text), "{output_format}", options.output_format);
    text = substitute(std::move(text), "{prefix}", options.prefix);
    return text;
  };
  std::string source = header_comment;
  source += fill(skeleton.at("prologue"));
  source += "\n// ---- " + file.file_name + " (saagen emit) ----\n";
  source += file.content;
  source += "// ---- end of " + file.file_name + " ----\n\n";
  source += fill(skeleton.at("resources"));
  if (kind.tangents) source += fill(skeleton.at("tangent_resources"));
  source += substitute(fill(skeleton.at("main")), "{body}", body);
  return source;
}

EmissionMarker pass_marker(OutputTarget file, const DeferredPassKind& kind, const DeferredPassOptions& options,
                           const std::map<std::string, double>& option_values) {
  return EmissionMarker{std::move(file), {kind.variant}, options.prefix, option_values, Precision::fp32, options.guards, {kind.wrapper}};
}

// The description shared by every file of a pass (comment lines without the comment leader).
std::vector<std::string> pass_description(const Catalogue& catalogue, const DeferredPassKind& kind, const DeferredPassOptions& options,
                                          const std::string& stem) {
  namespace abi = deferred_pass_abi;
  const Variant& variant = *catalogue.find_variant(kind.variant);
  const Function& wrapper = *catalogue.find_function(kind.wrapper);
  std::vector<std::string> lines = {
      fmt::format("Deferred roughness limiter, pass {}: {} per pixel.", kind.id, prefixed_name(options.prefix, kind.wrapper)),
      fmt::format("  {}", variant.summary),
      fmt::format("  {} -- {}", variant.paper, variant.equation),
      fmt::format("  {}", wrapper.cite),
      fmt::format("Files: {0}.comp (GLSL 4.50), {0}.hlsl (HLSL, SM 6.0 wave ops), {0}.spv (SPIR-V 1.3 from the GLSL), {0}.h.", stem),
      fmt::format("Dispatch: ({} + {}) / {} x ({} + {}) / {} x 1 workgroups of {} invocations; one invocation per pixel,", "width",
                  abi::tile_size - 1, abi::tile_size, "height", abi::tile_size - 1, abi::tile_size, abi::local_size),
      fmt::format("  a workgroup covers an {0} x {0} tile as {1} x {1} quads of 2 x 2 pixels.", abi::tile_size, abi::tile_size / 2),
      "Requires Vulkan 1.1 subgroup basic + quad operations in compute, subgroup size 4..64, and full",
      "  subgroups (consecutive lanes in fours are quads; VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT",
      "  guarantees them where the driver does not already).",
      "Bindings, descriptor set 0:",
      fmt::format("  {}  normal     sampled image (any float/unorm/snorm format), .xyz the shading normal, signed or", abi::binding_normal),
      "               unorm-encoded (flag 4); renormalised; a zero normal marks no surface",
      fmt::format("  {}  roughness  sampled image; channel roughness_channel; domain in flags bits 0-1", abi::binding_roughness),
      fmt::format("  {}  output     storage image, format {}: the filtered roughness, in the input's domain", abi::binding_output,
                  options.output_format),
  };
  if (kind.tangents) {
    lines.push_back(
        fmt::format("  {}  tangent    sampled image, .xyz tangent (signed, or unorm with flag 8), .w < 0 flips", abi::binding_tangent));
    lines.push_back("               the bitangent b = sign cross(n, t); t is made orthogonal to n and unit");
  }
  lines.insert(lines.end(),
               {
                   "Push constants (16 bytes, compute stage): uint32 width, height, roughness_channel (0..3), flags:",
                   "  bits 0-1 the roughness domain: 0 alpha^2, 1 alpha, 2 perceptual r (alpha = r^2), 3 smoothness 1 - r;",
                   "  4 normal unorm-encoded; 8 tangent unorm-encoded.",
                   fmt::format("Derivatives: quads of 2 x 2 pixels from (x & ~1, y & ~1); plain ddx/ddy are {} (ddx_fine/ddy_fine are",
                               options.derivatives == PlainDerivative::fine ? "fine, per row / column"
                                                                            : "coarse, one per quad from the top-left pixel"),
                   "  always fine). Past the right/bottom edge lanes read the edge texel (clamped) and write nothing:",
                   "  with an odd width the last column's derivative across x is 0 (likewise y for an odd height).",
               });
  std::string constants;
  for (const auto& [option, value] : resolve_options(catalogue, options.option_values)) constants += fmt::format(" {}={}", option, value);
  lines.push_back(fmt::format("Constants:{}; {}.", constants, options.guards ? "guarded" : "UNGUARDED paper form"));
  return lines;
}

std::string comment_block(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& line : lines) out += "// " + line + "\n";
  return out;
}

std::string pass_header(const DeferredPass& pass, const DeferredPassOptions& options, const std::vector<std::string>& description,
                        const EmissionMarker& marker) {
  namespace abi = deferred_pass_abi;
  const std::string macro = macro_prefix(options.prefix);
  const std::string pass_macro = upper_identifier(pass.stem);
  const std::string qualifier = macro + "SPV_CONST";
  const std::string common_guard = macro + "PASS_COMMON_DEFINITIONS";
  std::ostringstream out;
  out << fmt::format("// Generated by saagen {} -- do not edit; regenerate with `saagen pass`.\n", version());
  out << marker_line(marker) << "\n//\n" << comment_block(description);
  out << fmt::format("\n#ifndef {0}_H\n#define {0}_H\n\n#include <stddef.h>\n#include <stdint.h>\n\n", pass_macro);
  out << fmt::format("#ifndef {0}\n#ifdef __cplusplus\n#define {0} inline constexpr\n#else\n#define {0} static const\n#endif\n#endif\n\n",
                     qualifier);
  out << fmt::format("#ifndef {0}\n#define {0}\n", common_guard);
  out << "// The interface every pass shares (descriptor set 0).\n";
  out << fmt::format("#define {}PASS_BINDING_NORMAL {}u     /* VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE */\n", macro, abi::binding_normal);
  out << fmt::format("#define {}PASS_BINDING_ROUGHNESS {}u  /* VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE */\n", macro, abi::binding_roughness);
  out << fmt::format("#define {}PASS_BINDING_OUTPUT {}u     /* VK_DESCRIPTOR_TYPE_STORAGE_IMAGE */\n", macro, abi::binding_output);
  out << fmt::format("#define {}PASS_BINDING_TANGENT {}u    /* VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, tangent passes only */\n", macro,
                     abi::binding_tangent);
  out << fmt::format("#define {}PASS_TILE_SIZE {}u          /* pixels per workgroup along x and y */\n", macro, abi::tile_size);
  out << fmt::format("#define {}PASS_LOCAL_SIZE_X {}u       /* local size (x, 1, 1) */\n", macro, abi::local_size);
  out << fmt::format("#define {}PASS_DOMAIN_ALPHA2 {}u\n#define {}PASS_DOMAIN_ALPHA {}u\n#define {}PASS_DOMAIN_PERCEPTUAL {}u\n", macro,
                     abi::domain_alpha2, macro, abi::domain_alpha, macro, abi::domain_perceptual);
  out << fmt::format("#define {}PASS_FLAG_NORMAL_UNORM {}u\n#define {}PASS_FLAG_TANGENT_UNORM {}u\n", macro, abi::flag_normal_unorm, macro,
                     abi::flag_tangent_unorm);
  out << fmt::format(
      "/* Push constants (VK_SHADER_STAGE_COMPUTE_BIT, offset 0, 16 bytes). */\n"
      "typedef struct {0}pass_constants {{\n"
      "  uint32_t width;              /* image size in pixels */\n"
      "  uint32_t height;\n"
      "  uint32_t roughness_channel;  /* 0..3: r, g, b, a of the roughness G-buffer */\n"
      "  uint32_t flags;              /* {1}PASS_DOMAIN_* | {1}PASS_FLAG_* */\n"
      "}} {0}pass_constants;\n",
      options.prefix, macro);
  out << fmt::format(
      "#define {0}PASS_GROUPS(size) (((size) + {0}PASS_TILE_SIZE - 1u) / {0}PASS_TILE_SIZE)  /* workgroups along x or y */\n", macro);
  out << fmt::format("#endif  // {}\n\n", common_guard);
  out << fmt::format("#define {}_USES_TANGENT {}\n", pass_macro, pass.kind.tangents ? 1 : 0);
  out << fmt::format("#define {}_OUTPUT_FORMAT {}  /* VK_FORMAT_{} */\n", pass_macro, options.output_format == "r16f" ? 76 : 100,
                     options.output_format == "r16f" ? "R16_SFLOAT" : "R32_SFLOAT");
  out << fmt::format("#define {}_ENTRY_POINT \"main\"\n\n", pass_macro);
  out << fmt::format("// {}.spv: {} words, {} instructions.\n", pass.stem, pass.spirv.size(), count_spirv_instructions(pass.spirv));
  out << fmt::format("{} uint32_t {}_spv[{}] = {{\n{}}};\n", qualifier, pass.stem, pass.spirv.size(), spirv_c_initializer(pass.spirv));
  out << fmt::format("{} size_t {}_spv_word_count = {};\n", qualifier, pass.stem, pass.spirv.size());
  out << fmt::format("{} size_t {}_spv_size_bytes = {};\n", qualifier, pass.stem, pass.spirv.size() * 4);
  out << fmt::format("\n#endif  // {}_H\n", pass_macro);
  return out.str();
}

CompileResult compile_pass(SourceLanguage language, const std::string& name, const std::string& source) {
  CompileRequest request;
  request.language = language;
  request.stage = ShaderStage::compute;
  request.client = ClientApi::vulkan;
  request.sources = {{name, source}};
  return compile_to_spirv(request);
}

}  // namespace

std::vector<DeferredPassKind> deferred_pass_kinds(const Catalogue& catalogue) {
  std::vector<DeferredPassKind> kinds;
  for (const Variant& variant : catalogue.variants()) {
    if (variant.path != RenderPath::deferred) continue;
    for (const std::string& name : variant.functions) {
      const Function& function = *catalogue.find_function(name);
      // A pass writes one roughness: a wrapper returning a tensor (deferred-aniso) is not one.
      if (function.role != FunctionRole::fragment || function.return_type != "real") continue;
      std::string id = name.substr(0, name.rfind("_fragment"));
      std::replace(id.begin(), id.end(), '_', '-');
      const bool tangents = std::any_of(function.parameters.begin(), function.parameters.end(),
                                        [](const Parameter& parameter) { return parameter.name == "tangent_ws"; });
      kinds.push_back({id, variant.id, name, tangents});
    }
  }
  return kinds;
}

const std::string& DeferredPass::source(std::string_view target) const {
  for (const DeferredPassSource& pass_source : sources) {
    if (pass_source.target == target) return pass_source.text;
  }
  throw Error(fmt::format("{}: no deferred pass written in target '{}'", stem, target));
}

std::vector<std::pair<std::string, std::string>> DeferredPass::files() const {
  std::vector<std::pair<std::string, std::string>> files;
  for (const DeferredPassSource& pass_source : sources) files.emplace_back(pass_source.file_name, pass_source.text);
  files.emplace_back(stem + ".spv", spirv_file_bytes(spirv));
  files.emplace_back(stem + ".h", header);
  return files;
}

std::vector<DeferredPass> emit_deferred_passes(const Catalogue& catalogue, const DeferredPassOptions& options) {
  validate_prefix(options.prefix);
  if (options.output_format != "r32f" && options.output_format != "r16f") {
    throw Error(fmt::format("unknown output format '{}'; choose r32f or r16f", options.output_format));
  }
  const auto option_values = resolve_options(catalogue, options.option_values);
  const auto all = deferred_pass_kinds(catalogue);
  std::vector<DeferredPassKind> kinds;
  if (options.passes.empty()) kinds = all;
  for (const std::string& id : options.passes) {
    const auto found = std::find_if(all.begin(), all.end(), [&](const DeferredPassKind& kind) { return kind.id == id; });
    if (found == all.end()) {
      std::vector<std::string> ids;
      for (const DeferredPassKind& kind : all) ids.push_back(kind.id);
      throw Error(fmt::format("unknown pass '{}'; choose one of: {}", id, fmt::join(ids, ", ")));
    }
    kinds.push_back(*found);
  }

  std::vector<DeferredPass> passes;
  for (const DeferredPassKind& kind : kinds) {
    DeferredPass pass;
    pass.kind = kind;
    pass.stem = prefixed_name(options.prefix, "pass_" + underscored(kind.id));
    const auto description = pass_description(catalogue, kind, options, pass.stem);
    const auto generated = fmt::format("// Generated by saagen {} -- do not edit; regenerate with `saagen pass`.\n", version());
    const auto header_for = [&](const OutputTarget& target) {
      return generated + marker_line(pass_marker(target, kind, options, option_values)) + "\n//\n" + comment_block(description) + "\n";
    };
    for (const TargetSyntax* target : deferred_pass_targets()) {
      EmitOptions emit;
      emit.target = target->name;
      emit.prefix = options.prefix;
      emit.option_values = options.option_values;
      emit.guards = options.guards;
      // The wrapper's closure and the domain conversions the pass body calls, in one file.
      std::vector<std::string> functions = {kind.wrapper};
      for (const std::string& name : domain_conversion_functions()) functions.push_back(name);
      const EmittedFile file = emit_bundle(catalogue, emit, {"pass_" + underscored(kind.id), functions, {kind.variant}, {}});
      std::string source = pass_source(catalogue, *target, file, kind, options, header_for(OutputTarget::pass_source(target->name)));
      const std::string name = pass.stem + target->deferred_pass_extension;
      const CompileResult compiled = compile_pass(target->language, name, source);
      if (!compiled.ok) throw Error(fmt::format("{}: the pass does not compile: {}", name, compiled.log));
      if (target->spirv_library_source) {
        pass.spirv = add_module_processed(
            compiled.spirv, marker_line(pass_marker(OutputTarget::product(OutputKind::pass_spirv), kind, options, option_values)) + "\n");
        if (const std::string log = validate_spirv(pass.spirv, ClientApi::vulkan); !log.empty()) {
          throw Error(fmt::format("{}.spv: invalid after adding the marker: {}", pass.stem, log));
        }
      }
      pass.sources.push_back({target->name, name, std::move(source)});
    }
    pass.header =
        pass_header(pass, options, description, pass_marker(OutputTarget::product(OutputKind::pass_spirv), kind, options, option_values));
    passes.push_back(std::move(pass));
  }
  return passes;
}

}  // namespace saagen

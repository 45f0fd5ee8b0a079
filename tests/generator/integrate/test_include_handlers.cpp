// The include handlers (saagen/integrate/glslang_includer.hpp, saagen/integrate/shaderc_includer.hpp): user shaders
// that #include saagen snippets by name compile through glslang and shaderc, GLSL and HLSL, with
// options from the handler and from the name; a bad name or option fails the compile with the
// CLI's one-line message.
#include "support/include_shaders.hpp"

#include "saagen/error.hpp"

#include <gtest/gtest.h>

namespace {

using saagen::IncludeOptions;
using saagen::test::compile_with_glslang;
using saagen::test::compile_with_shaderc;
using saagen::test::glsl_user_shader;
using saagen::test::hlsl_user_shader;

bool is_spirv(const std::vector<std::uint32_t>& words) { return !words.empty() && words.front() == 0x07230203u; }

TEST(IncludeNames, ResolveVariantsPresetsAndOptions) {
  const saagen::EmitOptions preset = saagen::include_emit_options("saagen/hdrp.hlsl", {});
  EXPECT_EQ(preset.target, "hlsl");
  EXPECT_EQ(preset.variants, std::vector<std::string>{"deferred-sum"});
  EXPECT_EQ(preset.option_values.at("sigma2"), 0.1);
  EXPECT_EQ(preset.option_values.at("kappa"), 0.04);
  EXPECT_EQ(preset.domain, saagen::Domain::smoothness);
  // The name's options win over the preset's and the handler's.
  const saagen::EmitOptions mixed =
      saagen::include_emit_options("saagen/deferred-avg.glsl?domain=perceptual&kappa=0.1&prefix=eng_",
                                   IncludeOptions{.prefix = "saa_", .sigma2 = 0.2, .kappa = {}, .preset = {}, .domain = "alpha"});
  EXPECT_EQ(mixed.variants, std::vector<std::string>{"deferred-avg"});
  EXPECT_EQ(mixed.domain, saagen::Domain::perceptual);
  EXPECT_EQ(mixed.option_values.at("kappa"), 0.1);
  EXPECT_EQ(mixed.option_values.at("sigma2"), 0.2);
  EXPECT_EQ(mixed.prefix, "eng_");
}

TEST(IncludeNames, BadNamesAreOneLineCliMessages) {
  const auto message = [](const std::string& name) {
    try {
      saagen::resolve_include(name, {});
    } catch (const saagen::Error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(
      message("saagen/deferred-avg.glsl?domain=linear"),
      "saagen/deferred-avg.glsl?domain=linear: --domain 'linear' is not a roughness domain; use one of alpha2, alpha, perceptual, smoothness");
  EXPECT_EQ(
      message("saagen/deferred-avg.glsl?kappa=2"),
      "saagen/deferred-avg.glsl?kappa=2: --kappa 2 is out of range: allowed [0, 1] (clamp kappa of the kernel roughness, in the alpha^2 domain)");
  EXPECT_EQ(message("saagen/deferred-avg.glsl?sigma2=big"),
            "saagen/deferred-avg.glsl?sigma2=big: --sigma2 'big': not a number; pass a decimal number");
  EXPECT_EQ(message("saagen/deferred-avg.glsl?colour=red"),
            "saagen/deferred-avg.glsl?colour=red: unknown option 'colour'; use prefix, sigma2, kappa, preset, domain, precision, guards");
  EXPECT_EQ(message("saagen/deferred-avg.wgsl"), "saagen/deferred-avg.wgsl: unknown extension '.wgsl'; use .essl, .glsl, .hlsl");
  EXPECT_EQ(
      message("saagen/brdf-beckmann.glsl?domain=perceptual"),
      "saagen/brdf-beckmann.glsl?domain=perceptual: --domain perceptual: variant 'brdf-beckmann' takes or returns no scalar or per-axis "
      "roughness; emit it with --domain alpha2");
  for (const std::string name :
       {"saagen/unreal.glsl", "saagen/hdrp.glsl?preset=bevy", "saagen/x", "saagen/deferred-avg.glsl?precision=fp64"}) {
    const std::string text = message(name);
    EXPECT_EQ(text.rfind(name + ": ", 0), 0u) << text;
    EXPECT_EQ(text.find('\n'), std::string::npos) << text;
  }
}

struct CompileCase {
  const char* compiler;
  bool hlsl;
};

// The parameter as ctest lists it (without a printer gtest prints the object's bytes, pointers
// included, so the test's name would change from run to run).
void PrintTo(const CompileCase& c, std::ostream* os) { *os << c.compiler << (c.hlsl ? " hlsl" : " glsl"); }

class IncludeHandlerCompile : public ::testing::TestWithParam<CompileCase> {};

saagen::test::Compiled compile(const CompileCase& c, const std::string& source, const IncludeOptions& defaults) {
  if (std::string(c.compiler) == "glslang") {
    saagen::GlslangIncluder includer(defaults);
    return compile_with_glslang(source, c.hlsl, includer);
  }
  return compile_with_shaderc(source, c.hlsl, std::make_unique<saagen::ShadercIncluder>(defaults));
}

// The name's prefix sets the CORE_ONLY macro's (the shader is a compute shader: no derivatives).
std::string user_shader(const CompileCase& c, const std::string& name, const std::string& call) {
  const std::string include = "#include <saagen/" + name + ">";
  const std::string core_only = name.find("prefix=eng_") != std::string::npos ? "ENG_CORE_ONLY" : "SAA_CORE_ONLY";
  return c.hlsl ? hlsl_user_shader(include, call, core_only)
                : glsl_user_shader(include, call, std::string(c.compiler) == "glslang", core_only);
}

TEST_P(IncludeHandlerCompile, PresetsVariantsAndDomainsCompile) {
  const CompileCase& c = GetParam();
  const std::string ext = c.hlsl ? "hlsl" : "glsl";
  for (const auto& [name, call] :
       std::vector<std::pair<std::string, std::string>>{{"hdrp." + ext, "saa_deferred_sum_smoothness"},
                                                        {"filament." + ext, "saa_deferred_sum_perceptual"},
                                                        {"deferred-avg." + ext + "?domain=alpha&sigma2=0.2", "saa_deferred_avg_alpha"},
                                                        {"deferred-projected-space." + ext, "saa_deferred_projected_space"},
                                                        {"deferred-sum." + ext + "?prefix=eng_", "eng_deferred_sum"}}) {
    const auto compiled = compile(c, user_shader(c, name, call), {});
    EXPECT_TRUE(compiled.ok) << name << ":\n" << compiled.log;
    EXPECT_TRUE(is_spirv(compiled.spirv)) << name;
  }
  // Options given to the handler apply to names that carry none.
  const auto from_handler = compile(c, user_shader(c, "deferred-avg." + ext, "saa_deferred_avg_perceptual"),
                                    IncludeOptions{.prefix = "saa_", .sigma2 = {}, .kappa = {}, .preset = {}, .domain = "perceptual"});
  EXPECT_TRUE(from_handler.ok) << from_handler.log;
}

TEST_P(IncludeHandlerCompile, BadNamesFailWithTheOneLineMessage) {
  const CompileCase& c = GetParam();
  const std::string ext = c.hlsl ? "hlsl" : "glsl";
  const auto compiled = compile(c, user_shader(c, "deferred-avg." + ext + "?domain=linear", "saa_deferred_avg"), {});
  EXPECT_FALSE(compiled.ok);
  EXPECT_NE(compiled.log.find("--domain 'linear' is not a roughness domain; use one of alpha2, alpha, perceptual, smoothness"),
            std::string::npos)
      << compiled.log;
}

INSTANTIATE_TEST_SUITE_P(Compilers, IncludeHandlerCompile,
                         ::testing::Values(CompileCase{"glslang", false}, CompileCase{"glslang", true}, CompileCase{"shaderc", false},
                                           CompileCase{"shaderc", true}),
                         [](const auto& info) { return std::string(info.param.compiler) + (info.param.hlsl ? "_hlsl" : "_glsl"); });

}  // namespace

// Emission: every variant x target compiles and validates in-process; output is deterministic,
// prefixed, documented, and free of target matrix conventions.
#include "saagen/emit/emitter.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/validate/validation.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <sstream>

namespace {

using saagen::Catalogue;

std::vector<std::string> variant_ids() {
  std::vector<std::string> ids;
  for (const saagen::Variant& variant : Catalogue::builtin().variants()) ids.push_back(variant.id);
  return ids;
}

saagen::EmittedFile emit_one(const std::string& target, const std::string& variant, const std::string& prefix = "saa_") {
  saagen::EmitOptions options;
  options.target = target;
  options.variants = {variant};
  options.prefix = prefix;
  auto files = saagen::emit_variants(Catalogue::builtin(), options);
  EXPECT_EQ(files.size(), 1u);
  return files.front();
}

struct VariantTarget {
  std::string variant;
  std::string target;
};

void PrintTo(const VariantTarget& c, std::ostream* os) { *os << c.target << " " << c.variant; }

class EveryVariantAndTarget : public ::testing::TestWithParam<VariantTarget> {};

TEST_P(EveryVariantAndTarget, CompilesAndValidatesForEveryClientAndStage) {
  const auto file = emit_one(GetParam().target, GetParam().variant);
  const saagen::FileValidation validation = saagen::validate_file(Catalogue::builtin(), file.file_name, file.content);
  // GLSL is checked for Vulkan and OpenGL, HLSL for Vulkan; each in a fragment and a compute shader.
  const std::size_t expected_checks = GetParam().target == "glsl" ? 4 : 2;
  ASSERT_EQ(validation.checks.size(), expected_checks);
  for (const saagen::ValidationCheck& check : validation.checks) {
    EXPECT_TRUE(check.ok) << file.file_name << " " << check.name << ":\n" << check.log;
    EXPECT_GT(check.spirv_words, 100u) << check.name;
  }
}

std::vector<VariantTarget> all_pairs() {
  std::vector<VariantTarget> pairs;
  for (const std::string target : {"glsl", "hlsl"}) {
    for (const std::string& id : variant_ids()) pairs.push_back({id, target});
  }
  return pairs;
}

INSTANTIATE_TEST_SUITE_P(Catalogue, EveryVariantAndTarget, ::testing::ValuesIn(all_pairs()), [](const auto& info) {
  std::string name = info.param.target + "_" + info.param.variant;
  for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
});

TEST(Catalogue, HasEveryVariantOfTheMission) {
  const std::vector<std::string> expected = {"forward-aniso-slope",
                                             "forward-aniso-projected",
                                             "forward-axis-slope",
                                             "forward-axis-projected",
                                             "deferred-previous",
                                             "deferred-max",
                                             "deferred-sum",
                                             "deferred-avg",
                                             "deferred-projected-space",
                                             "deferred-aniso",
                                             "brdf-ggx",
                                             "brdf-beckmann",
                                             "prefilter-toksvig",
                                             "prefilter-lean"};
  EXPECT_EQ(variant_ids(), expected);
}

TEST(Catalogue, EveryDerivativeVariantHasACoreAndAFragmentWrapper) {
  for (const saagen::Variant& variant : Catalogue::builtin().variants()) {
    std::set<saagen::FunctionRole> roles;
    for (const std::string& name : variant.functions) roles.insert(Catalogue::builtin().find_function(name)->role);
    const bool is_brdf = variant.id.rfind("brdf-", 0) == 0;
    EXPECT_TRUE(roles.count(is_brdf ? saagen::FunctionRole::evaluate : saagen::FunctionRole::core)) << variant.id;
    // The texture-space prefilter-* variants take texture samples, not derivatives: core only.
    if (variant.id.rfind("prefilter-", 0) != 0) {
      EXPECT_TRUE(roles.count(saagen::FunctionRole::fragment)) << variant.id;
    }
  }
}

TEST(Catalogue, CoreFunctionsTakeNoDerivativesAndWrappersDo) {
  for (const saagen::Function& function : Catalogue::builtin().functions()) {
    if (function.role == saagen::FunctionRole::core || function.role == saagen::FunctionRole::evaluate) {
      EXPECT_FALSE(function.fragment_only) << function.name;
    }
    if (function.role == saagen::FunctionRole::fragment) {
      EXPECT_TRUE(function.fragment_only) << function.name;
    }
  }
}

TEST(Emission, IsByteIdenticalAcrossRuns) {
  for (const std::string target : {"glsl", "hlsl"}) {
    saagen::EmitOptions options;
    options.target = target;
    const auto first = saagen::emit_variants(Catalogue::builtin(), options);
    const auto second = saagen::emit_variants(Catalogue::builtin(), options);
    ASSERT_EQ(first.size(), second.size());
    for (std::size_t index = 0; index < first.size(); ++index) {
      EXPECT_EQ(first[index].file_name, second[index].file_name);
      EXPECT_EQ(first[index].content, second[index].content) << first[index].file_name;
    }
  }
}

// Every name the file declares at global scope (functions, constants, macros) carries the
// prefix, so two snippets or an engine's own code cannot collide with it.
TEST(Emission, PrefixesEveryGlobalName) {
  const std::regex function_definition(R"(^\w+ (\w+)\()");
  const std::regex constant_definition(R"(^(?:static )?const \w+ (\w+) =)");
  const std::regex macro_definition(R"(^#(?:define|ifndef) (\w+))");
  for (const std::string target : {"glsl", "hlsl"}) {
    for (const std::string& id : variant_ids()) {
      const auto file = emit_one(target, id, "eng7_");
      std::istringstream lines(file.content);
      int declarations = 0;
      for (std::string line; std::getline(lines, line);) {
        std::smatch match;
        if (std::regex_search(line, match, function_definition) || std::regex_search(line, match, constant_definition)) {
          EXPECT_EQ(match[1].str().rfind("eng7_", 0), 0u) << file.file_name << ": " << line;
          ++declarations;
        } else if (std::regex_search(line, match, macro_definition)) {
          EXPECT_EQ(match[1].str().rfind("ENG7_", 0), 0u) << file.file_name << ": " << line;
        }
      }
      EXPECT_GE(declarations, 2) << file.file_name;
      EXPECT_EQ(file.content.find("saa_"), std::string::npos) << file.file_name << " still uses the default prefix";
      EXPECT_TRUE(saagen::validate_file(Catalogue::builtin(), file.file_name, file.content).ok()) << file.file_name;
    }
  }
}

TEST(Emission, HeaderCarriesVersionConstantsCitationsAndGuard) {
  const auto file = emit_one("glsl", "deferred-sum");
  const std::string& text = file.content;
  EXPECT_NE(text.find(std::string("saagen ") + std::string(saagen::version())), std::string::npos);
  EXPECT_NE(text.find("// saagen-marker: target=glsl variants=deferred-sum prefix=saa_ kappa=0.18 sigma2=0.25"), std::string::npos);
  EXPECT_NE(text.find("#ifndef SAA_DEFERRED_SUM_GLSL"), std::string::npos);
  EXPECT_NE(text.find("const float saa_SIGMA2 = 0.25;"), std::string::npos);
  EXPECT_NE(text.find("const float saa_KAPPA = 0.18;"), std::string::npos);
  EXPECT_NE(text.find("Eq. 4"), std::string::npos);
  // Every function is preceded by a comment naming its role and citation.
  const std::regex cited_function(R"(// \[(core|fragment|helper|evaluate)\] [^\n]+\n(//[^\n]*\n)*\w+ saa_\w+\()");
  const std::regex any_function(R"(\n\w+ saa_\w+\()");
  const auto definitions = std::distance(std::sregex_iterator(text.begin(), text.end(), any_function), std::sregex_iterator());
  const auto cited = std::distance(std::sregex_iterator(text.begin(), text.end(), cited_function), std::sregex_iterator());
  EXPECT_EQ(definitions, cited);
  EXPECT_EQ(definitions, 3);  // deferred_sum, deferred_sum_fragment, isotropic_kernel_sum
}

TEST(Emission, OverriddenConstantsAreWrittenAndMarked) {
  saagen::EmitOptions options;
  options.target = "hlsl";
  options.variants = {"deferred-avg"};
  options.option_values = {{"sigma2", 0.15915494309189535}, {"kappa", 0.04}};
  const auto file = saagen::emit_variants(Catalogue::builtin(), options).front();
  EXPECT_NE(file.content.find("static const float saa_SIGMA2 = 0.15915494309189535;"), std::string::npos);
  EXPECT_NE(file.content.find("static const float saa_KAPPA = 0.04;"), std::string::npos);
  const auto marker = saagen::find_marker(file.content);
  ASSERT_TRUE(marker.has_value());
  EXPECT_DOUBLE_EQ(marker->option_values.at("sigma2"), 0.15915494309189535);
  EXPECT_DOUBLE_EQ(marker->option_values.at("kappa"), 0.04);
}

TEST(Emission, RejectsOutOfRangeOptionsNamingTheInterval) {
  saagen::EmitOptions options;
  options.option_values = {{"sigma2", 0.0}};
  try {
    saagen::emit_variants(Catalogue::builtin(), options);
    FAIL() << "sigma2 = 0 was accepted";
  } catch (const saagen::Error& error) {
    EXPECT_NE(std::string(error.what()).find("--sigma2 0 is out of range: allowed (0, 4]"), std::string::npos) << error.what();
  }
  options.option_values = {{"kappa", std::numeric_limits<double>::quiet_NaN()}};
  EXPECT_THROW(saagen::emit_variants(Catalogue::builtin(), options), saagen::Error);
}

TEST(Emission, EmitsOnlyTheClosureOfTheVariant) {
  const auto file = emit_one("glsl", "deferred-sum");
  EXPECT_EQ(file.content.find("saa_sym2_max_eigenvalue"), std::string::npos);
  EXPECT_EQ(file.content.find("saa_PI"), std::string::npos);  // unused constants are not emitted
  const auto brdf = emit_one("glsl", "brdf-ggx");
  // The filtered BRDF wrapper pulls the projected forward filter and its helpers.
  EXPECT_NE(brdf.content.find("vec3 saa_forward_aniso_projected_fragment("), std::string::npos);
  EXPECT_NE(brdf.content.find("vec3 saa_roughness_matrix_from_bounded_derivatives("), std::string::npos);
  // The tail-preserving filtered GGX evaluates its Beckmann lobes itself (with Beckmann's exp
  // guard) and pulls nothing else of the Beckmann variant.
  EXPECT_NE(brdf.content.find("float saa_filtered_ggx_mixture("), std::string::npos);
  EXPECT_NE(brdf.content.find("float saa_beckmann_falloff("), std::string::npos);
  EXPECT_EQ(brdf.content.find("saa_beckmann_ndf"), std::string::npos);
  EXPECT_EQ(brdf.content.find("saa_beckmann_brdf"), std::string::npos);
  EXPECT_EQ(brdf.content.find("saa_beckmann_lambda"), std::string::npos);
}

// The dialect has no matrices, so no file may depend on a target's row/column-major convention
// or on mul() argument order (the trap Listing 1's mul(tangentFrame, h) sets for a GLSL port).
TEST(Emission, UsesNoTargetMatrixTypesOrMul) {
  const std::regex matrix_token(R"(\b(mat[234](x[234])?|float[234]x[234]|half[234]x[234]|mul|transpose)\b)");
  for (const std::string target : {"glsl", "hlsl"}) {
    saagen::EmitOptions options;
    options.target = target;
    for (const auto& file : saagen::emit_variants(Catalogue::builtin(), options)) {
      std::smatch match;
      // Comments may mention "Delta^T Delta"; code lines must not use matrix tokens.
      std::istringstream lines(file.content);
      for (std::string line; std::getline(lines, line);) {
        if (line.rfind("//", 0) == 0) continue;
        EXPECT_FALSE(std::regex_search(line, match, matrix_token)) << file.file_name << ": " << line;
      }
    }
  }
}

TEST(Emission, CoreOnlyMacroRemovesEveryDerivative) {
  for (const std::string& id : variant_ids()) {
    const auto file = emit_one("glsl", id);
    // Strip the CORE_ONLY blocks the way the preprocessor would and look for derivative calls.
    std::string kept;
    int skipped_depth = 0;
    int depth = 0;
    std::istringstream lines(file.content);
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("#if", 0) == 0) {
        ++depth;
        if (line == "#ifndef SAA_CORE_ONLY" && skipped_depth == 0) skipped_depth = depth;
        continue;
      }
      if (line.rfind("#endif", 0) == 0) {
        if (skipped_depth == depth) skipped_depth = 0;
        --depth;
        continue;
      }
      if (skipped_depth == 0) kept += line + "\n";
    }
    EXPECT_EQ(kept.find("dFd"), std::string::npos) << id;
  }
}

TEST(Emission, UnknownVariantAndTargetAreRejected) {
  saagen::EmitOptions options;
  options.variants = {"deferred-median"};
  EXPECT_THROW(saagen::emit_variants(Catalogue::builtin(), options), saagen::Error);
  options.variants = {};
  options.target = "metal";
  try {
    saagen::emit_variants(Catalogue::builtin(), options);
    FAIL();
  } catch (const saagen::Error& error) {
    EXPECT_STREQ(error.what(), "unknown target 'metal'; choose one of: gles, glsl, hlsl, wgsl");
  }
}

TEST(Prefix, AcceptsSafeIdentifiers) {
  for (const std::string prefix : {"saa_", "a", "Engine_SAA_", "x9"}) EXPECT_NO_THROW(saagen::validate_prefix(prefix)) << prefix;
}

TEST(Prefix, RejectsAnythingThatCouldInjectCodeOrCollide) {
  for (const std::string& prefix : std::vector<std::string>{"", "9a", "_a", "a b", "a;b", "a(", "a\nb", "a//", "#define", "gl_x", "GL_x",
                                                            "a__b", "saa-", std::string(33, 'a')}) {
    EXPECT_THROW(saagen::validate_prefix(prefix), saagen::Error) << "accepted: " << prefix;
  }
}

TEST(Marker, RoundTripsAndIsAbsentFromForeignFiles) {
  saagen::EmissionMarker marker;
  marker.target = saagen::OutputTarget::snippet("hlsl");
  marker.variants = {"deferred-sum", "deferred-avg"};
  marker.prefix = "eng_";
  marker.option_values = {{"kappa", 0.1}, {"sigma2", 0.3}};
  const auto parsed = saagen::find_marker("// header\n" + saagen::marker_line(marker) + "\nfloat x;\n");
  ASSERT_TRUE(parsed.has_value());
  EXPECT_EQ(parsed->target, saagen::OutputTarget::snippet("hlsl"));
  EXPECT_EQ(parsed->variants, marker.variants);
  EXPECT_EQ(parsed->prefix, "eng_");
  EXPECT_EQ(parsed->option_values, marker.option_values);
  EXPECT_FALSE(saagen::find_marker("float4 main() : SV_Target { return 0; }").has_value());
}

// A marker's target is read once into a typed value: a table's snippet, or a product whose
// pseudo-target (spirv, pass-glsl, ...) is spelled in marker.hpp only.
TEST(Marker, TargetsAreTypedSnippetsOrProducts) {
  EXPECT_EQ(saagen::OutputTarget::named("wgsl"), saagen::OutputTarget::snippet("wgsl"));
  EXPECT_TRUE(saagen::OutputTarget::named("wgsl").is_snippet());
  for (const saagen::OutputKind kind : {saagen::OutputKind::spirv_library, saagen::OutputKind::pass_spirv}) {
    saagen::EmissionMarker marker;
    marker.target = saagen::OutputTarget::product(kind);
    marker.variants = {"deferred-sum"};
    marker.prefix = "saa_";
    const auto parsed = saagen::find_marker(saagen::marker_line(marker));
    ASSERT_TRUE(parsed.has_value());
    EXPECT_EQ(parsed->target.kind, kind);
    EXPECT_TRUE(parsed->target.table.empty());
    EXPECT_EQ(parsed->target.name(), saagen::marker_target(kind));
  }
  // A deferred pass's source names the table it is written in, whatever that table is: no
  // language is spelled here.
  for (const std::string table : {"glsl", "hlsl", "a-future-language"}) {
    const saagen::OutputTarget target = saagen::OutputTarget::named("pass-" + table);
    EXPECT_EQ(target, saagen::OutputTarget::pass_source(table));
    EXPECT_FALSE(target.is_snippet());
    EXPECT_EQ(target.name(), "pass-" + table);
  }
  EXPECT_EQ(saagen::OutputTarget::named("pass-spirv"), saagen::OutputTarget::product(saagen::OutputKind::pass_spirv));
  EXPECT_TRUE(saagen::OutputTarget::named("pass-").is_snippet());  // no table: an unknown target, said as one
  // EmitOptions::target is the same typed value, read from `--target`'s text where it is set.
  saagen::EmitOptions options;
  EXPECT_EQ(options.target, saagen::OutputTarget::snippet("glsl"));
  options.target = std::string("spirv");
  EXPECT_EQ(options.target, saagen::OutputTarget::product(saagen::OutputKind::spirv_library));
}

TEST(Validation, ReportsTheEmittedFileNameAndLineOfAnError) {
  auto file = emit_one("glsl", "deferred-avg");
  const std::string needle = "return saturate";
  auto position = file.content.find("return clamp");
  ASSERT_NE(position, std::string::npos) << needle;
  file.content.insert(position, "undeclared_identifier_x;\n");
  const auto validation = saagen::validate_file(Catalogue::builtin(), file.file_name, file.content);
  EXPECT_FALSE(validation.ok());
  EXPECT_NE(validation.summary().find("FAIL saa_deferred_avg.glsl"), std::string::npos) << validation.summary();
  EXPECT_NE(validation.checks.front().log.find("saa_deferred_avg.glsl:"), std::string::npos) << validation.checks.front().log;
  EXPECT_NE(validation.checks.front().log.find("undeclared_identifier_x"), std::string::npos);
}

TEST(Validation, RefusesFilesWithoutAMarker) {
  EXPECT_THROW(saagen::validate_file(Catalogue::builtin(), "foreign.glsl", "float f() { return 1.0; }\n"), saagen::Error);
}

struct Form {
  std::string target;
  std::string precision;
  bool guards;
};

void PrintTo(const Form& form, std::ostream* os) { *os << form.target << " " << form.precision << (form.guards ? "" : " unguarded"); }

class EveryForm : public ::testing::TestWithParam<Form> {};

// Every variant in every precision the target offers, guarded and unguarded, compiles and
// passes spirv-val; half-precision GLSL carries its extension and fp32 derivative helpers.
TEST_P(EveryForm, EveryVariantValidates) {
  const Form& form = GetParam();
  saagen::EmitOptions options;
  options.target = form.target;
  options.precision = saagen::parse_precision(form.precision);
  options.guards = form.guards;
  for (const auto& file : saagen::emit_variants(Catalogue::builtin(), options)) {
    const auto validation = saagen::validate_file(Catalogue::builtin(), file.file_name, file.content);
    EXPECT_TRUE(validation.ok()) << validation.summary() << "\n" << validation.checks.front().log;
    EXPECT_EQ(saagen::to_string(file.marker.precision), form.precision);
    EXPECT_EQ(file.marker.guards, form.guards);
    const auto parsed = saagen::find_marker(file.content);
    ASSERT_TRUE(parsed.has_value());
    EXPECT_EQ(saagen::to_string(parsed->precision), form.precision);
    EXPECT_EQ(parsed->guards, form.guards);
  }
}

INSTANTIATE_TEST_SUITE_P(Forms, EveryForm,
                         ::testing::Values(Form{"glsl", "fp16", true}, Form{"glsl", "fp16", false}, Form{"glsl", "fp32", false},
                                           Form{"hlsl", "min16", true}, Form{"hlsl", "min16", false}, Form{"hlsl", "fp32", false}),
                         [](const auto& info) {
                           return info.param.target + "_" + info.param.precision + (info.param.guards ? "" : "_unguarded");
                         });

TEST(Forms, HalfPrecisionGlslUsesFloat16TypesLiteralsAndFp32Derivatives) {
  saagen::EmitOptions options;
  options.precision = saagen::Precision::fp16;
  options.variants = {"deferred-sum"};
  const auto file = saagen::emit_variants(Catalogue::builtin(), options).front();
  EXPECT_EQ(file.file_name, "saa_deferred_sum_fp16.glsl");
  EXPECT_NE(file.content.find("#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require"), std::string::npos);
  EXPECT_NE(file.content.find("const float16_t saa_SIGMA2 = 0.25hf;"), std::string::npos);
  EXPECT_NE(file.content.find("float16_t saa_deferred_sum(float16_t alpha2, f16vec3 dn_dx, f16vec3 dn_dy)"), std::string::npos);
  // Vulkan SPIR-V takes derivatives of 32-bit values only.
  EXPECT_NE(file.content.find("f16vec3 saa_ddx_fp16(f16vec3 v) { return f16vec3(dFdx(vec3(v))); }"), std::string::npos);
  EXPECT_NE(file.content.find("saa_ddx_fp16(normal_ws)"), std::string::npos);
  EXPECT_EQ(file.content.find("dFdx(normal_ws)"), std::string::npos);
}

TEST(Forms, GuardsAppearOnlyWhereTemplatesPlaceThemAndUnguardedIsThePaperForm) {
  saagen::EmitOptions options;
  options.variants = {"forward-aniso-slope"};
  const auto guarded = saagen::emit_variants(Catalogue::builtin(), options).front();
  options.guards = false;
  const auto paper = saagen::emit_variants(Catalogue::builtin(), options).front();
  EXPECT_EQ(paper.file_name, "saa_forward_aniso_slope_unguarded.glsl");
  EXPECT_NE(guarded.content.find("return half_ts.xy / (max(abs(half_ts.z), saa_SLOPE_MIN_Z));"), std::string::npos);
  EXPECT_NE(paper.content.find("return half_ts.xy / (abs(half_ts.z));"), std::string::npos);
  // The guard helpers and constants follow the form that is emitted.
  EXPECT_NE(guarded.content.find("saa_clamp_derivative2("), std::string::npos);
  EXPECT_EQ(paper.content.find("saa_clamp_derivative2"), std::string::npos);
  EXPECT_EQ(paper.content.find("saa_SLOPE_MIN_Z"), std::string::npos);
  // A variant without guard sites is identical in both forms apart from its header.
  options.variants = {"deferred-sum"};
  const auto sum_paper = saagen::emit_variants(Catalogue::builtin(), options).front();
  options.guards = true;
  const auto sum_guarded = saagen::emit_variants(Catalogue::builtin(), options).front();
  // Compare from the first constant up to the header guard's closing line (whose name differs).
  const auto body = [](const std::string& text) {
    const auto begin = text.find("#ifndef SAA_CONST_SIGMA2");
    return text.substr(begin, text.rfind("#endif  // SAA_DEFERRED_SUM") - begin);
  };
  EXPECT_EQ(body(sum_paper.content), body(sum_guarded.content));
}

TEST(Forms, UnknownPrecisionNamesTheOnesTheTargetHas) {
  saagen::EmitOptions options;
  options.target = "hlsl";
  options.precision = saagen::Precision::fp16;
  try {
    saagen::emit_variants(Catalogue::builtin(), options);
    FAIL();
  } catch (const saagen::Error& error) {
    EXPECT_STREQ(error.what(), "target hlsl has no precision 'fp16'; choose one of: fp32, min16");
  }
}

// Precision is read once where it enters, as Domain is: every id names one value and back, and an
// unknown id is refused there in one line; a marker naming none is not saagen's.
TEST(Forms, PrecisionIdsRoundTripAndUnknownOnesAreRefusedWhereRead) {
  for (const saagen::Precision precision : saagen::every_precision_kind) {
    EXPECT_EQ(saagen::precision_named(saagen::to_string(precision)), precision);
  }
  EXPECT_FALSE(saagen::precision_named("fp64").has_value());
  try {
    saagen::parse_precision("fp64");
    FAIL();
  } catch (const saagen::Error& error) {
    EXPECT_STREQ(error.what(), "--precision fp64: unknown precision; use one of fp32, fp16, min16");
  }
  const std::string marker = "// saagen-marker: target=glsl variants=deferred-sum prefix=saa_";
  EXPECT_EQ(saagen::find_marker(marker + " precision=fp16")->precision, saagen::Precision::fp16);
  EXPECT_EQ(saagen::find_marker(marker)->precision, saagen::Precision::fp32);
  EXPECT_FALSE(saagen::find_marker(marker + " precision=fp64").has_value());
}

}  // namespace

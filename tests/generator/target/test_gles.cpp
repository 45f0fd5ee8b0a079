// The GLSL ES 3.00 target (targets/gles.json): every variant, in both precisions, guarded and
// unguarded, passes glslang's ES front end (profile es, version 300) in a fragment shader and,
// under <PREFIX>CORE_ONLY, in a vertex shader; the include states the precision of every
// declaration itself, maps fp16 to mediump, and says what replaces the fine derivatives.
#include "saagen/emit/emitter.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/scene/manifest.hpp"
#include "saagen/scene/planner.hpp"
#include "saagen/validate/validation.hpp"

#include <gtest/gtest.h>

#include <ostream>
#include <regex>

namespace {

using saagen::Catalogue;

saagen::EmitOptions gles_options(const std::string& precision = "fp32", bool guards = true) {
  saagen::EmitOptions options;
  options.target = "gles";
  options.precision = saagen::parse_precision(precision);
  options.guards = guards;
  return options;
}

saagen::EmittedFile emit_one(const std::string& variant, const std::string& precision = "fp32") {
  auto options = gles_options(precision);
  options.variants = {variant};
  return saagen::emit_variants(Catalogue::builtin(), options).front();
}

struct Form {
  std::string precision;
  bool guards;
};

// The parameter as ctest lists it (without a printer gtest prints the object's bytes, pointers
// included, so the test's name would change from run to run).
void PrintTo(const Form& form, std::ostream* os) { *os << form.precision << (form.guards ? "" : " unguarded"); }

class GlesForm : public ::testing::TestWithParam<Form> {};

TEST_P(GlesForm, EveryVariantPassesTheEsFrontEndInAFragmentAndAVertexShader) {
  const auto files = saagen::emit_variants(Catalogue::builtin(), gles_options(GetParam().precision, GetParam().guards));
  ASSERT_EQ(files.size(), Catalogue::builtin().variants().size());
  for (const auto& file : files) {
    const auto validation = saagen::validate_file(Catalogue::builtin(), file.file_name, file.content);
    ASSERT_EQ(validation.checks.size(), 2u);
    EXPECT_EQ(validation.checks[0].name, "opengl_es fragment");
    EXPECT_EQ(validation.checks[1].name, "opengl_es vertex");
    for (const auto& check : validation.checks) EXPECT_TRUE(check.ok) << file.file_name << " " << check.name << ":\n" << check.log;
  }
}

INSTANTIATE_TEST_SUITE_P(Forms, GlesForm,
                         ::testing::Values(Form{"fp32", true}, Form{"fp32", false}, Form{"fp16", true}, Form{"fp16", false}),
                         [](const auto& info) { return info.param.precision + (info.param.guards ? "" : "_unguarded"); });

TEST(Gles, IsAnIncludeWithoutVersionExtensionsOrDesktopOnlyIntrinsics) {
  for (const auto& file : saagen::emit_variants(Catalogue::builtin(), gles_options())) {
    EXPECT_EQ(file.file_name.substr(file.file_name.size() - 5), ".essl");
    EXPECT_EQ(file.content.find("\n#version"), std::string::npos) << file.file_name;
    EXPECT_EQ(file.content.find("\n#extension"), std::string::npos) << file.file_name;
    EXPECT_EQ(file.content.find("Fine("), std::string::npos) << file.file_name;
    EXPECT_EQ(file.content.find("Coarse("), std::string::npos) << file.file_name;
  }
}

// Every parameter, return type and constant carries highp; every body opens with scoped default
// precision statements (GLSL ES 3.00 section 4.5.4: a precision statement inside a compound
// statement ends with it), so the includer's defaults neither matter nor change.
TEST(Gles, EveryDeclarationStatesItsPrecision) {
  const auto file = emit_one("deferred-sum");
  EXPECT_NE(file.content.find("highp float saa_deferred_sum(highp float alpha2, highp vec3 dn_dx, highp vec3 dn_dy)\n{\n"
                              "    precision highp float;\n    precision highp int;\n"),
            std::string::npos)
      << file.content;
  EXPECT_NE(file.content.find("const highp float saa_SIGMA2 = 0.25;"), std::string::npos);
  // No signature line declares a float type without a qualifier.
  const std::regex unqualified(R"((^|[(,]\s*)(float|vec[234]|int)\s+saa_?\w*)");
  std::istringstream lines(file.content);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("//", 0) == 0 || line.rfind("    ", 0) == 0) continue;  // comments and bodies
    EXPECT_FALSE(std::regex_search(line, unqualified)) << line;
  }
}

TEST(Gles, HalfPrecisionIsMediumpNotFloat16) {
  const auto file = emit_one("deferred-sum", "fp16");
  EXPECT_EQ(file.file_name, "saa_deferred_sum_fp16.essl");
  EXPECT_EQ(file.content.find("float16_t"), std::string::npos);
  EXPECT_EQ(file.content.find("hf"), std::string::npos);
  EXPECT_NE(file.content.find("mediump float saa_deferred_sum(mediump float alpha2, mediump vec3 dn_dx, mediump vec3 dn_dy)\n{\n"
                              "    precision mediump float;\n"),
            std::string::npos)
      << file.content;
}

TEST(Gles, TheQuadAverageSubstituteIsStatedExactlyWhereItIsUsed) {
  for (const auto& file : saagen::emit_variants(Catalogue::builtin(), gles_options())) {
    const bool uses_quad_average = file.content.find("saa_quad_average_normal(") != std::string::npos;
    const bool noted = file.content.find("// Note:\n//   GLSL ES 3.00 has no dFdxFine/dFdyFine") != std::string::npos;
    EXPECT_EQ(uses_quad_average, noted) << file.file_name;
  }
  EXPECT_NE(emit_one("deferred-max").content.find("saa_quad_average_normal("), std::string::npos);
  // In mediump the note adds the range of exact pixel coordinates.
  EXPECT_NE(emit_one("deferred-max", "fp16").content.find("keeps its .5 pixel centres only below 1024 pixels"), std::string::npos);
  EXPECT_EQ(emit_one("deferred-max").content.find("1024 pixels"), std::string::npos);
  EXPECT_NE(emit_one("deferred-previous").content.find("saa_quad_average_normal("), std::string::npos);
}

// The ES front end is strict where desktop GLSL is not: a fragment-shader declaration with no
// precision (no default for float in the fragment language, section 4.5.4) is an error. Without
// the bodies' precision statements, the functions' local floats have none.
TEST(Gles, ValidationRejectsADeclarationWithoutPrecision) {
  auto file = emit_one("deferred-max");
  const std::string statement = "    precision highp float;\n";
  ASSERT_NE(file.content.find(statement), std::string::npos);
  for (auto at = file.content.find(statement); at != std::string::npos; at = file.content.find(statement))
    file.content.erase(at, statement.size());
  const auto validation = saagen::validate_file(Catalogue::builtin(), file.file_name, file.content);
  ASSERT_FALSE(validation.checks.empty());
  EXPECT_FALSE(validation.checks[0].ok);
  EXPECT_NE(validation.checks[0].log.find(file.file_name + ":"), std::string::npos) << validation.checks[0].log;
  EXPECT_NE(validation.checks[0].log.find("precision"), std::string::npos) << validation.checks[0].log;
}

TEST(Gles, BundlesValidate) {
  saagen::BundleRequest request;
  request.name = "materials";
  request.variants = {"deferred-max", "brdf-ggx"};
  request.functions = {"deferred_max_fragment", "ggx_brdf_axis"};
  for (const std::string precision : {"fp32", "fp16"}) {
    const auto file = saagen::emit_bundle(Catalogue::builtin(), gles_options(precision), request);
    EXPECT_EQ(file.marker.target, saagen::OutputTarget::snippet("gles"));
    const auto validation = saagen::validate_file(Catalogue::builtin(), file.file_name, file.content);
    EXPECT_TRUE(validation.ok()) << validation.summary() << "\n" << validation.checks.front().log;
  }
}

// A manifest naming gles gets a plan with a cost (the cost kernel compiles the same file as ES
// 3.10 for Vulkan, the first ES version with a SPIR-V form) and bundles that validate.
TEST(Gles, ManifestsPlanAndEmitGles) {
  const std::string text =
      "name = \"web\"\ntargets = [\"gles\"]\n"
      "[[material]]\nname = \"metal\"\npath = \"deferred\"\n"
      "[[material]]\nname = \"coat\"\npath = \"forward\"\nprecision = \"fp16\"\n";
  const saagen::Manifest manifest = saagen::parse_manifest(text, "web.saagen.toml", Catalogue::builtin());
  saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), manifest);
  saagen::measure_costs(Catalogue::builtin(), manifest, plan);
  for (const auto& material : plan.materials) {
    ASSERT_TRUE(material.cost.count("gles"));
    EXPECT_GT(material.cost.at("gles"), 0);
  }
  const auto files = saagen::emit_scene(Catalogue::builtin(), manifest, plan);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].file_name, "saa_web.essl");
  EXPECT_EQ(files[1].file_name, "saa_web_fp16.essl");
  for (const auto& file : files) {
    const auto validation = saagen::validate_file(Catalogue::builtin(), file.file_name, file.content);
    EXPECT_TRUE(validation.ok()) << validation.summary() << "\n" << validation.checks.front().log;
  }
}

// fp32 only: the glint variants refuse half precision (GlintEmission.HalfPrecisionIsRefusedAndListedAsUnsupported).
TEST(Gles, GlintSnippetsPassTheEsFrontEnd) {
  for (const std::string precision : {"fp32"}) {
    for (const auto& file : saagen::glints::emit(gles_options(precision))) {
      const auto validation = saagen::validate_file(saagen::glints::catalogue(), file.file_name, file.content);
      EXPECT_TRUE(validation.ok()) << validation.summary() << "\n" << validation.checks.front().log;
    }
  }
}

}  // namespace

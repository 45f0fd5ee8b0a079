// The template dialect: parsing rules, the error each mistake produces (file:line: what to do),
// and the translation of types, intrinsics and names into each target.
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/print/glue.hpp"
#include "saagen/target/target.hpp"
#include "saagen/validate/kernels.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

namespace {

using saagen::Catalogue;

const char* const valid_function = R"(@function twice
role: core
cite: test
returns: real | two times x
param: real x | input
{
    return 2.0 * x;
}
)";

std::string parse_error(const std::string& text) {
  try {
    Catalogue::parse({{"templates/test.saa", text}});
  } catch (const saagen::Error& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(TemplateParser, ReadsAFunctionWithItsParametersAndBody) {
  const Catalogue catalogue = Catalogue::parse({{"templates/test.saa", valid_function}});
  const saagen::Function* function = catalogue.find_function("twice");
  ASSERT_NE(function, nullptr);
  EXPECT_EQ(function->role, saagen::FunctionRole::core);
  EXPECT_EQ(function->return_type, "real");
  ASSERT_EQ(function->parameters.size(), 1u);
  EXPECT_EQ(function->parameters[0].name, "x");
  EXPECT_EQ(function->parameters[0].meaning, "input");
  EXPECT_EQ(function->body, "    return 2.0 * x;\n");
  EXPECT_EQ(function->line, 1);
}

TEST(TemplateParser, RejectsMatrixProductsWithALineAndAFix) {
  const std::string text = "\n\n@function bad\nrole: core\ncite: c\nreturns: real3 | r\nparam: real3 v | v\n{\n    return mul(v, v);\n}\n";
  EXPECT_EQ(parse_error(text), "templates/test.saa:3: bad uses 'mul': the dialect has no matrices; write the product with dot products");
}

TEST(TemplateParser, RejectsMatrixTypes) {
  EXPECT_EQ(parse_error("@function f\nrole: core\ncite: c\nreturns: real | r\nparam: float2x2 m | m\n{\n}\n"),
            "templates/test.saa:5: unknown type 'float2x2'; the dialect has real, real2, real3, real4, bool, int (no matrices)");
}

TEST(TemplateParser, ReportsEachKindOfMistakeAtItsLine) {
  EXPECT_EQ(parse_error("@function f\nrole: core\n"), "templates/test.saa:1: @function f is missing the 'cite:' line");
  EXPECT_EQ(parse_error("@function f\nrole: sometimes\n"),
            "templates/test.saa:2: role 'sometimes' is not one of core, fragment, evaluate, helper");
  EXPECT_EQ(parse_error("@function f\nrole: core\ncite: c\nreturns: real | r\n"),
            "templates/test.saa:1: @function f needs a body: a line '{', the code, and a line '}'");
  EXPECT_EQ(parse_error("@function f\nrole: core\ncite: c\nreturns: real | r\n{\n  return 1.0;\n"),
            "templates/test.saa:5: body of f has no closing '}' line at column 1");
  EXPECT_EQ(parse_error("@shader f\n"), "templates/test.saa:1: unknown block '@shader'; use @variant, @function or @constant");
  EXPECT_EQ(parse_error("@function f\nrole: core\ncolour: red\n"),
            "templates/test.saa:3: unknown function key 'colour'; allowed: role, cite, returns, param");
  EXPECT_EQ(parse_error("# alpha \xce\xb1\n"),
            "templates/test.saa:1: non-ASCII character; templates (and the code they emit) must be ASCII");
  // Found by the template fuzzer: control bytes (NUL here) used to pass into the emitted code.
  EXPECT_EQ(parse_error(std::string("# a\n# b\0c\n", 9)),
            "templates/test.saa:2: control character 0x00; templates (and the code they emit) are printable ASCII, indented with spaces");
  EXPECT_EQ(parse_error("#\ta\n"),
            "templates/test.saa:1: control character 0x09; templates (and the code they emit) are printable ASCII, indented with spaces");
  EXPECT_EQ(parse_error(std::string(valid_function) + valid_function), "templates/test.saa:9: function name 'twice' is already used");
}

TEST(TemplateParser, ChecksRolesAgainstDerivativeUse) {
  EXPECT_EQ(parse_error("@function f\nrole: core\ncite: c\nreturns: real | r\nparam: real x | x\n{\n    return ddx(x);\n}\n"),
            "templates/test.saa:1: f takes screen-space derivatives; its role must be fragment");
  // Derivative use propagates through helpers to their callers.
  const std::string chain =
      "@function h\nrole: helper\ncite: c\nreturns: real | r\nparam: real x | x\n{\n    return ddy_fine(x);\n}\n"
      "@function g\nrole: evaluate\ncite: c\nreturns: real | r\nparam: real x | x\n{\n    return h(x);\n}\n";
  EXPECT_EQ(parse_error(chain), "templates/test.saa:9: g takes screen-space derivatives; its role must be fragment");
}

TEST(TemplateParser, ChecksVariantsAndOptions) {
  EXPECT_EQ(parse_error("@variant v\nsummary: s\npaper: p\nequation: e\npath: sideways\n"),
            "templates/test.saa:5: path 'sideways' is not one of forward, deferred, any");
  EXPECT_EQ(parse_error("@variant v\nsummary: s\npaper: p\nequation: e\npath: any\ntangents: no\ndomain: d\nfunctions: nothing\n"),
            "templates/test.saa:1: variant v lists unknown function 'nothing'");
  EXPECT_EQ(parse_error("@constant K\ntype: real\nmeaning: m\noption: k\ndefault: 2\nrange: [0, 1]\n"),
            "templates/test.saa:1: default 2 of K is outside its range [0, 1]");
  // Found by the template fuzzer: an option name with a space broke the emitted marker line.
  EXPECT_EQ(parse_error("@constant K\ntype: real\nmeaning: m\noption: k ppa\ndefault: 0.1\nrange: [0, 1]\n"),
            "templates/test.saa:4: option 'k ppa' is not an identifier");
  // And a comma in a variant id broke the marker's comma-separated variant list.
  EXPECT_EQ(parse_error("@variant v,w\nsummary: s\n"),
            "templates/test.saa:1: variant id 'v,w' must be letters, digits and '-', starting with a letter");
  // A `precisions:` list is read into typed precisions where it is parsed.
  EXPECT_EQ(parse_error("@variant v\nsummary: s\nprecisions: fp32 fp64\n"),
            "templates/test.saa:3: precision 'fp64' is not one of fp32, fp16, min16");
}

TEST(TemplateParser, RecordsCallsConstantsAndClosureOrder) {
  const Catalogue& catalogue = Catalogue::builtin();
  const saagen::Function* sum = catalogue.find_function("deferred_sum");
  ASSERT_NE(sum, nullptr);
  EXPECT_EQ(sum->calls, std::vector<std::string>{"isotropic_kernel_sum"});
  EXPECT_EQ(sum->constants, std::vector<std::string>{"KAPPA"});
  std::vector<std::string> order;
  for (const saagen::Function* function : catalogue.closure({"deferred_sum_fragment"})) order.push_back(function->name);
  EXPECT_EQ(order, (std::vector<std::string>{"isotropic_kernel_sum", "deferred_sum", "deferred_sum_fragment"}));
}

// Glue (kernel bodies, validation calls, the deferred pass's body) goes through the typed tree like
// a template body: types, intrinsics and template names spelt per target, the skeleton's names as
// the table spells them, member accesses and comments kept.
std::string glue_for(const std::string& target, const std::string& code) {
  const saagen::NameMap names = {{"KAPPA", "eng_KAPPA"}};
  return saagen::print_glue(saagen::builtin_target(target), Catalogue::builtin(), code, names, saagen::kernel_glue_symbols());
}

const char* const kGlue =
    "    real x = SAAGEN_LOAD(0);  // the input\n"
    "    real3 v = saturate(lerp(real3(x, x, x), frac(real3(x, 0.5, 1.0)), rsqrt(real3(x, x, x)))) * KAPPA;\n"
    "    SAAGEN_STORE(saagen_index, v.x);\n";

TEST(GluePrinter, SpellsTypesIntrinsicsAndNamesPerTarget) {
  EXPECT_EQ(glue_for("glsl", kGlue),
            "    float x = SAAGEN_LOAD(0);  // the input\n"
            "    vec3 v = clamp(mix(vec3(x, x, x), fract(vec3(x, 0.5, 1.0)), inversesqrt(vec3(x, x, x))), 0.0, 1.0) * eng_KAPPA;\n"
            "    SAAGEN_STORE(saagen_index, v.x);\n");
  EXPECT_EQ(glue_for("hlsl", kGlue),
            "    float x = SAAGEN_LOAD(0);  // the input\n"
            "    float3 v = saturate(lerp(float3(x, x, x), frac(float3(x, 0.5, 1.0)), rsqrt(float3(x, x, x)))) * eng_KAPPA;\n"
            "    SAAGEN_STORE(saagen_index, v.x);\n");
}

TEST(GluePrinter, SpellsTheSkeletonsNamesAsAModuleTableDoes) {
  // WGSL has no macros: its skeletons define saagen_load and saagen_store (targets/wgsl.json "glue_names").
  EXPECT_EQ(glue_for("wgsl", kGlue),
            "    let x: f32 = saagen_load(0);  // the input\n"
            "    let v: vec3<f32> = saturate(mix(vec3<f32>(x, x, x), fract(vec3<f32>(x, 0.5, 1.0)), inverseSqrt(vec3<f32>(x, x, x)))) * "
            "eng_KAPPA;\n"
            "    saagen_store(saagen_index, v.x);\n");
}

TEST(GluePrinter, RefusesGlueThatDoesNotCheck) { EXPECT_THROW(glue_for("glsl", "    real2 v = real2(SAAGEN_LOAD(0));\n"), saagen::Error); }

TEST(TargetTable, ReportsMissingKeysAndTypes) {
  try {
    saagen::TargetSyntax::parse(R"({"name": "x"})", "targets/x.json");
    FAIL();
  } catch (const saagen::Error& error) {
    EXPECT_STREQ(error.what(), "targets/x.json: missing key 'description' in the target table");
  }
  try {
    saagen::TargetSyntax::parse(R"({"name": "x", "description": "d", "file_extension": "x", "language": "glsl",
                                    "types": {"real": "float"}})",
                                "targets/x.json");
    FAIL();
  } catch (const saagen::Error& error) {
    EXPECT_STREQ(error.what(), "targets/x.json: 'types' has no spelling for dialect type 'real2'");
  }
}

// The layout of an emitted file is the table's: the C preprocessor languages share an include
// guard form (targets/preprocessor/include_file.txt); WGSL's modules have none and take an import path.
TEST(TargetTable, ReadsTheFileFormAndTheProductsTargets) {
  const saagen::FileForm& include = saagen::builtin_target("hlsl").file_form;
  EXPECT_EQ(include.definitions_open, "\n#ifndef {guard}\n#define {guard}\n");
  EXPECT_EQ(include.fragment_only_close, "#endif  // {core_only}\n");
  EXPECT_EQ(include.body_open, "\n{\n");
  EXPECT_TRUE(saagen::builtin_target("gles").has_includes());
  EXPECT_FALSE(saagen::builtin_target("glsl").takes_import_path());
  const saagen::TargetSyntax& wgsl = saagen::builtin_target("wgsl");
  EXPECT_EQ(wgsl.file_form.definitions_open, "");
  EXPECT_EQ(wgsl.file_form.import_path, "\n#define_import_path {path}\n");
  EXPECT_TRUE(wgsl.takes_import_path() && wgsl.passes_resources() && !wgsl.has_includes() && !wgsl.compiled_in_process());
  EXPECT_EQ(saagen::spirv_library_target().name, "glsl");
  std::vector<std::string> passes, vulkan;
  for (const saagen::TargetSyntax* target : saagen::deferred_pass_targets()) passes.push_back(target->name);
  for (const saagen::TargetSyntax* target : saagen::vulkan_targets()) vulkan.push_back(target->name);
  EXPECT_EQ(passes, (std::vector<std::string>{"glsl", "hlsl"}));
  EXPECT_EQ(vulkan, (std::vector<std::string>{"glsl", "hlsl"}));
}

TEST(TargetTable, RefusesAFileFormWithoutASection) {
  std::ifstream file(SAAGEN_SOURCE_DIR "/targets/wgsl.json");
  std::stringstream text;
  text << file.rdbuf();
  std::string table = text.str();
  const std::string key = "\"body_open\": \" {\\n\",";
  ASSERT_NE(table.find(key), std::string::npos);
  table.erase(table.find(key), key.size());
  try {
    saagen::TargetSyntax::parse(table, "targets/wgsl.json");
    FAIL();
  } catch (const saagen::Error& error) {
    EXPECT_STREQ(error.what(), "targets/wgsl.json: 'file_form' needs a section 'body_open'");
  }
}

// Skeletons live as source files under targets/<language>/, split by "// saagen-section: NAME"
// lines; the tables name them, and a table naming a file this build lacks is refused.
TEST(TargetTable, LoadsSkeletonsFromSourceFiles) {
  const saagen::TargetSyntax& glsl = saagen::builtin_target("glsl");
  EXPECT_EQ(glsl.fragment_skeleton.prologue, "#version 450\n");
  EXPECT_EQ(glsl.compute_skeleton.prologue, "#version 450\n#define {core_only_macro}\n");
  EXPECT_EQ(saagen::builtin_target("hlsl").fragment_skeleton.prologue, "");
  EXPECT_NE(glsl.kernel_skeletons.at("quad_compute").prologue.find("#extension GL_KHR_shader_subgroup_quad : require\n"),
            std::string::npos);
  EXPECT_EQ(glsl.with_precision(saagen::Precision::fp16)
                .preamble.rfind("#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require\n", 0),
            0u);
  const auto pass = saagen::skeleton_sections("hlsl/deferred_pass.hlsl", "test");
  std::vector<std::string> names;
  for (const auto& [name, text] : pass) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"baseline", "main", "prologue", "resources", "tangent_resources"}));
  EXPECT_EQ(pass.at("main").substr(pass.at("main").size() - 8), "{body}}\n");

  std::ifstream file(SAAGEN_SOURCE_DIR "/targets/glsl.json");
  std::stringstream text;
  text << file.rdbuf();
  std::string table = text.str();
  const std::string named = "\"glsl/validate_fragment.glsl\"";
  ASSERT_NE(table.find(named), std::string::npos);
  table.replace(table.find(named), named.size(), "\"glsl/missing.glsl\"");
  try {
    saagen::TargetSyntax::parse(table, "targets/x.json");
    FAIL();
  } catch (const saagen::Error& error) {
    EXPECT_STREQ(error.what(),
                 "targets/x.json: skeleton file targets/glsl/missing.glsl is not in this build; add it under targets/ and rebuild");
  }
}

}  // namespace

// The WGSL target's emission, without a device: WGSL's rules hold by construction in every emitted
// module -- no preprocessor, every function and constant defined once, no ?: (select instead), no
// increment or assignment used as a value, every declaration typed, braces around every branch --
// and several variants make one module. Tint's verdict and the runs are in test_wgsl.
#include "support/web_support.hpp"

#include "saagen/emit/emitter.hpp"
#include "saagen/error.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/front/syntax_tree.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/target/target.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <sstream>

namespace {

using saagen::Catalogue;
using saagen::test::wgsl_options;

std::vector<saagen::EmittedFile> emit_all(saagen::EmitOptions options) {
  options.target = "wgsl";
  return saagen::emit_variants(saagen::glints::catalogue(), options);
}

// The code of a module: its lines with comments removed.
std::string code_of(const std::string& content) {
  std::istringstream lines(content);
  std::string code;
  for (std::string line; std::getline(lines, line);) code += line.substr(0, line.find("//")) + "\n";
  return code;
}

std::vector<std::string> all_matches(const std::string& text, const std::regex& pattern) {
  std::vector<std::string> found;
  for (auto match = std::sregex_iterator(text.begin(), text.end(), pattern); match != std::sregex_iterator(); ++match)
    found.push_back((*match)[1]);
  return found;
}

TEST(WgslEmission, EveryVariantInEveryFormIsAModuleWithoutPreprocessorOrCLikeSyntax) {
  std::size_t modules = 0;
  for (const saagen::EmitOptions& options :
       {wgsl_options(), wgsl_options("fp16"), wgsl_options("fp32", false), wgsl_options("fp32", true, "perceptual")}) {
    for (const saagen::EmittedFile& file : emit_all(options)) {
      ++modules;
      const std::string code = code_of(file.content);
      SCOPED_TRACE(file.file_name);
      EXPECT_EQ(code.find('#'), std::string::npos);
      EXPECT_EQ(code.find('?'), std::string::npos) << "?: must print as select()";
      EXPECT_FALSE(std::regex_search(code, std::regex(R"(\+\+[A-Za-z_]|--[A-Za-z_])"))) << "prefix increments are not WGSL";
      EXPECT_FALSE(std::regex_search(code, std::regex(R"(\b(float|vec[234]|int|half|float16_t|real[234]?)\s+[a-z_]+\s*[=;(])")))
          << "C-style declarations are not WGSL";
      EXPECT_FALSE(std::regex_search(code, std::regex(R"(\)\s*\n\s*(return|[a-z_]+ =))"))) << "every branch body is in braces";
      // Each function and constant is defined once, under the prefix.
      std::set<std::string> seen;
      for (const std::string& name : all_matches(code, std::regex(R"((?:^|\n)(?:fn|const) ([A-Za-z0-9_]+))"))) {
        EXPECT_TRUE(seen.insert(name).second) << name << " is defined twice";
        EXPECT_EQ(name.rfind("saa_", 0), 0u) << name;
      }
      EXPECT_FALSE(seen.empty());
      // f16 only behind `enable f16;`, which precedes every declaration.
      const bool half = code.find("f16") != std::string::npos;
      EXPECT_EQ(half, options.precision == saagen::Precision::fp16);
      if (half) {
        EXPECT_LT(code.find("enable f16;"),
                  code.find("const ") == std::string::npos ? code.find("fn ") : std::min(code.find("const "), code.find("fn ")));
        EXPECT_NE(file.content.find("shader-f16"), std::string::npos) << "the header names the device feature";
      }
    }
  }
  EXPECT_GE(modules, 4u * 9u);
}

TEST(WgslEmission, LocalsAreLetUnlessReassignedAndAssignedParametersAreCopied) {
  const saagen::EmitOptions options = wgsl_options("fp32", true, "alpha2", {"glints-ggaa"});
  const std::string code = code_of(emit_all(options).front().content);
  // glint_mix reassigns its parameter v: the signature takes v_in, the body copies it into a var.
  EXPECT_NE(code.find("fn saa_glint_mix(v_in: i32) -> i32 {\n    var v: i32 = v_in;"), std::string::npos);
  // A shift by a variable amount converts it to u32; a literal amount stays abstract.
  EXPECT_NE(code.find("<< u32(level)"), std::string::npos);
  EXPECT_NE(code.find("(v >> 16)"), std::string::npos);
  // The loop counters are vars, incremented by statements.
  EXPECT_TRUE(std::regex_search(code, std::regex(R"(for \(var j: i32 = first_row; j <= last_row; j\+\+\) \{)")));
  // Functions reading the dictionary take it, and pass it on.
  EXPECT_NE(code.find("glint_dictionary: texture_2d_array<f32>, glint_sampler: sampler) -> f32 {"), std::string::npos);
}

TEST(WgslEmission, SeveralVariantsMakeOneModuleWithTheirClosureOnce) {
  const std::vector<std::string> variants = {"deferred-sum", "deferred-avg", "forward-aniso-projected", "brdf-ggx"};
  const saagen::BundleRequest request{"module", saagen::public_functions(Catalogue::builtin(), variants), variants, {}};
  const saagen::EmittedFile file = saagen::emit_bundle(Catalogue::builtin(), wgsl_options(), request);
  EXPECT_EQ(file.file_name, "saa_module.wgsl");
  const std::string code = code_of(file.content);
  std::set<std::string> seen;
  for (const std::string& name : all_matches(code, std::regex(R"((?:^|\n)fn ([A-Za-z0-9_]+))")))
    EXPECT_TRUE(seen.insert(name).second) << name;
  for (const std::string& name : request.functions) EXPECT_TRUE(seen.count("saa_" + name)) << name;
}

TEST(WgslEmission, TheImportPathHeaderIsOptionalAndChecked) {
  saagen::EmitOptions options = wgsl_options("fp32", true, "alpha2", {"deferred-sum"}, "saagen::deferred_sum");
  const saagen::EmittedFile file = emit_all(options).front();
  EXPECT_NE(file.content.find("\n#define_import_path saagen::deferred_sum\n"), std::string::npos);
  EXPECT_EQ(saagen::find_marker(file.content)->import_path, "saagen::deferred_sum");
  EXPECT_EQ(emit_all(wgsl_options("fp32", true, "alpha2", {"deferred-sum"})).front().content.find("#define_import_path"),
            std::string::npos);
  for (const char* bad : {"saagen:deferred", "saagen::", "9lives", "a b", "saagen::x\n@compute fn f() {}"}) {
    options.import_path = bad;
    EXPECT_THROW(emit_all(options), saagen::Error) << bad;
  }
  options.import_path = "saagen::deferred_sum";
  options.target = "glsl";
  EXPECT_THROW(saagen::emit_variants(Catalogue::builtin(), options), saagen::Error);
}

TEST(WgslEmission, ReservedWordsAreRenamedAndIncrementsAreNeverValues) {
  const saagen::TargetSyntax& wgsl = saagen::builtin_target("wgsl");
  const std::vector<saagen::TemplateSource> sources = {{"templates/test.saa", R"(
@function f
role: helper
cite: test
param: real target | a parameter named like a WGSL reserved word
returns: real | its double
{
    real select = target * 2.0;
    return select;
}
@function g
role: helper
cite: test
param: int n | a count
returns: int | n + 2
{
    int k = n;
    k++;
    ++k;
    return k;
}
@function h
role: helper
cite: test
param: int n | a count
returns: int | never printed
{
    int k = n;
    return k++;
}
)"}};
  const Catalogue catalogue = Catalogue::parse(sources);
  const saagen::NameMap names;
  const saagen::dialect::PrintOptions print{&names};
  EXPECT_EQ(saagen::dialect::print_wgsl(*catalogue.find_function("f")->tree, wgsl, print),
            "    let select_: f32 = target_ * 2.0;\n    return select_;\n");
  EXPECT_EQ(saagen::dialect::parameter_name(wgsl, catalogue.find_function("f")->tree.get(), "target"), "target_");
  EXPECT_EQ(saagen::dialect::print_wgsl(*catalogue.find_function("g")->tree, wgsl, print),
            "    var k: i32 = n;\n    k++;\n    k++;\n    return k;\n");
  EXPECT_THROW(saagen::dialect::print_wgsl(*catalogue.find_function("h")->tree, wgsl, print), saagen::Error);
}

}  // namespace

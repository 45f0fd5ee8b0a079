// The language tables (targets/<language>/language.json): every target table's language has
// one, each names a printer that exists and a validator that decides how its files are checked,
// and a malformed table or an unknown language is one line naming the table.
#include "saagen/error.hpp"
#include "saagen/print/backend.hpp"
#include "saagen/target/language.hpp"
#include "saagen/target/target.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace {

using saagen::Language;
using saagen::SourceLanguage;

std::string error_of(auto&& call) {
  try {
    call();
  } catch (const saagen::Error& error) {
    return error.what();
  }
  return {};
}

TEST(Languages, EveryTargetTableNamesALanguageWithATableAndAPrinter) {
  const auto names = saagen::language_names();
  for (const std::string language : {"glsl", "hlsl", "wgsl"})
    EXPECT_NE(std::find(names.begin(), names.end(), language), names.end()) << language;
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  for (const std::string& target_name : saagen::builtin_target_names()) {
    const saagen::TargetSyntax& target = saagen::builtin_target(target_name);
    EXPECT_NE(std::find(names.begin(), names.end(), target.language.name()), names.end()) << target_name;
    EXPECT_NO_THROW(saagen::body_printer(*target.language)) << target_name;
  }
  // GLSL ES is GLSL's table on another client, not a language of its own.
  EXPECT_EQ(saagen::builtin_target("gles").language, SourceLanguage::named("glsl"));
}

TEST(Languages, TheTablesSayHowEachLanguageIsValidated) {
  const Language& glsl = *SourceLanguage::named("glsl");
  const Language& hlsl = *SourceLanguage::named("hlsl");
  const Language& wgsl = *SourceLanguage::named("wgsl");
  ASSERT_TRUE(glsl.compiled_in_process() && hlsl.compiled_in_process());
  EXPECT_FALSE(glsl.front_end().hlsl);
  EXPECT_EQ(glsl.front_end().default_version, 450);
  EXPECT_FALSE(glsl.front_end().named_entry_points);
  EXPECT_TRUE(hlsl.front_end().hlsl);
  EXPECT_EQ(hlsl.front_end().default_version, 100);
  EXPECT_TRUE(hlsl.front_end().named_entry_points);
  EXPECT_FALSE(wgsl.compiled_in_process());  // Tint, through the WebGPU runner
  EXPECT_NE(error_of([&] { wgsl.front_end(); }).find("Tint"), std::string::npos);
  EXPECT_EQ(glsl.printer, "c_like");
  EXPECT_EQ(hlsl.printer, "c_like");
  EXPECT_EQ(wgsl.printer, "wgsl");
}

TEST(Languages, AnUnknownLanguageOrAMalformedTableIsOneLineNamingIt) {
  EXPECT_FALSE(saagen::source_language("msl").has_value());
  const std::string unknown = error_of([] { SourceLanguage::named("msl"); });
  EXPECT_NE(unknown.find("targets/msl/language.json"), std::string::npos) << unknown;
  for (const std::string& language : saagen::language_names()) EXPECT_NE(unknown.find(language), std::string::npos) << unknown;
  EXPECT_EQ(unknown.find('\n'), std::string::npos);

  const std::string source = "targets/x/language.json";
  EXPECT_NE(
      error_of([&] { Language::parse(R"({"name": "x"})", source); }).find(source + ": missing key 'description' in the language table"),
      std::string::npos);
  EXPECT_NE(error_of([&] {
              Language::parse(R"({"name": "x", "description": "d", "printer": "c_like", "validator": "fxc"})", source);
            }).find("'validator' is 'glslang' or 'tint', not 'fxc'"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              Language::parse(R"({"name": "x", "description": "d", "printer": "c_like", "validator": "glslang"})", source);
            }).find("needs the object 'glslang'"),
            std::string::npos);
  EXPECT_NE(error_of([&] { Language::parse("[", source); }).find("not a JSON object"), std::string::npos);

  // A table whose printer this build has not: said when a body is printed, naming the table.
  const Language unprintable = Language::parse(R"({"name": "x", "description": "d", "printer": "msl", "validator": "tint"})", source);
  const std::string printer = error_of([&] { saagen::body_printer(unprintable); });
  EXPECT_NE(printer.find(source + ": printer 'msl' is not one of c_like, wgsl"), std::string::npos) << printer;
}

}  // namespace

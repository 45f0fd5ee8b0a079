// The glint snippets (templates/glints/) are emitted for GLSL and HLSL and pass the
// in-process validation (glslang + spirv-val, fragment and compute, every client API of the
// target), with the dictionary declared by the validation skeleton (targets/*.json "resources").
#include "saagen/emit/listing.hpp"
#include "saagen/error.hpp"
#include "saagen/products/glints.hpp"
#include "saagen/validate/kernels.hpp"
#include "saagen/validate/validation.hpp"

#include <gtest/gtest.h>

#include <iostream>
#include <ostream>

namespace {

namespace glints = saagen::glints;

saagen::EmitOptions options_for(const std::string& target, const std::string& precision = "fp32", bool guards = true) {
  saagen::EmitOptions options;
  options.target = target;
  options.precision = saagen::parse_precision(precision);
  options.guards = guards;
  return options;
}

struct Form {
  std::string target;
  std::string precision;
  bool guards;
};

// The parameter as ctest lists it (without a printer gtest prints the object's bytes).
void PrintTo(const Form& form, std::ostream* os) { *os << form.target << " " << form.precision << (form.guards ? "" : " unguarded"); }

class GlintEmission : public ::testing::TestWithParam<Form> {};

TEST_P(GlintEmission, BothVariantsCompileAndValidate) {
  const Form& form = GetParam();
  const auto files = glints::emit(options_for(form.target, form.precision, form.guards));
  ASSERT_EQ(files.size(), 2u);
  for (const auto& file : files) {
    const auto validation = saagen::validate_file(glints::catalogue(), file.file_name, file.content);
    std::cout << "[ validate ] " << validation.summary() << "\n";
    EXPECT_TRUE(validation.ok()) << validation.summary();
    for (const auto& check : validation.checks) EXPECT_TRUE(check.ok) << check.name << ":\n" << check.log;
  }
}

INSTANTIATE_TEST_SUITE_P(Forms, GlintEmission,
                         ::testing::Values(Form{"glsl", "fp32", true}, Form{"hlsl", "fp32", true}, Form{"glsl", "fp32", false},
                                           Form{"hlsl", "fp32", false}),
                         [](const auto& info) {
                           return info.param.target + "_" + info.param.precision + (info.param.guards ? "" : "_unguarded");
                         });

// Half precision is refused in one line (the SDF reaches ~1e6 at alpha ~ 0.01, beyond half range,
// and no half-precision bound is derived), and the catalogue and the file header say fp32 only.
TEST(GlintEmission, HalfPrecisionIsRefusedAndListedAsUnsupported) {
  for (const auto& [target, precision] : {std::pair{"glsl", "fp16"}, std::pair{"hlsl", "min16"}}) {
    try {
      glints::emit(options_for(target, precision));
      ADD_FAILURE() << target << " " << precision << " was emitted";
    } catch (const saagen::Error& error) {
      const std::string message = error.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      EXPECT_NE(message.find("fp32 only"), std::string::npos) << message;
      EXPECT_NE(message.find("--precision fp32"), std::string::npos) << message;
    }
  }
  const auto listing = saagen::catalogue_json(glints::catalogue(), "saa_");
  for (const auto& variant : listing.at("variants")) {
    const bool glint = variant.at("id").get<std::string>().rfind("glints", 0) == 0;
    if (glint) {
      EXPECT_EQ(variant.at("precisions"), nlohmann::json::array({"fp32"})) << variant.at("id");
    } else {
      EXPECT_EQ(variant.at("precisions").at(0), "fp32") << variant.at("id");
      EXPECT_GT(variant.at("precisions").size(), 1u) << variant.at("id");
    }
  }
  for (const auto& file : glints::emit(options_for("glsl"))) {
    EXPECT_NE(file.content.find("//   Precisions:  fp32 only"), std::string::npos) << file.file_name;
  }
}

TEST(GlintEmission, FilesNameTheDictionaryByMacroAndDeclareNothing) {
  for (const std::string target : {"glsl", "hlsl"}) {
    const auto files = glints::emit(options_for(target));
    ASSERT_EQ(files.size(), 2u);
    EXPECT_EQ(files[0].file_name, "saa_glints." + target);
    EXPECT_EQ(files[1].file_name, "saa_glints_ggaa." + target);
    for (const auto& file : files) {
      EXPECT_NE(file.content.find("SAA_GLINT_DICTIONARY"), std::string::npos);
      EXPECT_EQ(file.content.find("sampler1DArray"), std::string::npos);
      EXPECT_EQ(file.content.find("Texture1DArray"), std::string::npos);
      EXPECT_EQ(file.content.find("saagen_glint"), std::string::npos);  // the skeleton's names stay out
    }
    const std::string lookup = target == "glsl" ? "textureLod(SAA_GLINT_DICTIONARY" : "SAA_GLINT_DICTIONARY.SampleLevel(SAA_GLINT_SAMPLER";
    // Both variants read explicit levels only: the GGAA lookup computes its LOD and blends two
    // levels itself, so no gradient lookup leaves the LOD or the mip blend to the driver.
    const std::string gradient = target == "glsl" ? "textureGrad(" : ".SampleGrad(";
    for (const auto& file : files) {
      EXPECT_NE(file.content.find(lookup), std::string::npos);
      EXPECT_EQ(file.content.find(gradient), std::string::npos);
    }
    EXPECT_NE(files[1].content.find("GLINT_RESOLUTION"), std::string::npos);
  }
}

TEST(GlintEmission, OptionsReachTheConstantsAndTheMarker) {
  auto options = options_for("glsl");
  options.variants = {"glints-ggaa"};
  options.option_values = {{"glint_count", 96}, {"glint_lods", 12}, {"glint_alpha", 0.4}, {"glint_kernel_scale", 1.0}};
  const auto file = glints::emit(options).front();
  EXPECT_NE(file.content.find("glint_alpha=0.4 glint_count=96.0 glint_kernel_scale=1.0 glint_lods=12.0"), std::string::npos)
      << file.content.substr(0, 400);
  EXPECT_NE(file.content.find("const float saa_GLINT_COUNT = 96.0;"), std::string::npos);
  EXPECT_NE(file.content.find("const float saa_GLINT_KERNEL_SCALE = 1.0;"), std::string::npos);
  EXPECT_TRUE(saagen::validate_file(glints::catalogue(), file.file_name, file.content).ok());

  options.option_values = {{"glint_count", 98}};
  EXPECT_THROW(glints::emit(options), saagen::Error);  // not a multiple of 4
  options.option_values = {{"glint_kernel_scale", 0.0}};
  EXPECT_THROW(glints::emit(options), saagen::Error);  // out of (0, 8]
  options.option_values = {{"glint_resolution", 128}};
  EXPECT_NE(glints::emit(options).front().content.find("const float saa_GLINT_RESOLUTION = 128.0;"), std::string::npos);
  options.option_values = {{"glint_resolution", 48}};
  EXPECT_THROW(glints::emit(options), saagen::Error);  // not a power of two
}

TEST(GlintEmission, IsDeterministicAndPrefixed) {
  auto options = options_for("hlsl");
  options.prefix = "eng_";
  const auto first = glints::emit(options);
  const auto second = glints::emit(options);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t k = 0; k < first.size(); ++k) EXPECT_EQ(first[k].content, second[k].content);
  EXPECT_NE(first[1].content.find("float eng_glint_brdf_filtered("), std::string::npos);
  EXPECT_NE(first[1].content.find("ENG_GLINT_DICTIONARY.SampleLevel(ENG_GLINT_SAMPLER"), std::string::npos);
  EXPECT_NE(first[1].content.find("#ifndef ENG_CORE_ONLY"), std::string::npos);
  EXPECT_TRUE(saagen::validate_file(glints::catalogue(), first[1].file_name, first[1].content).ok());
}

// The SAA catalogue and its validation are untouched: no glint variant, no resource declaration.
TEST(GlintEmission, SaaCatalogueIsUnchanged) {
  EXPECT_EQ(saagen::Catalogue::builtin().find_variant("glints"), nullptr);
  EXPECT_EQ(saagen::Catalogue::builtin().variants().size(), 14u);
  EXPECT_EQ(glints::catalogue().variants().size(), 16u);
  saagen::EmitOptions options;
  options.variants = {"deferred-sum"};
  const auto file = saagen::emit_variants(saagen::Catalogue::builtin(), options).front();
  const auto pieces = saagen::validation_sources(saagen::Catalogue::builtin(), *saagen::find_marker(file.content), file.file_name,
                                                 file.content, saagen::ShaderStage::compute);
  for (const auto& piece : pieces) EXPECT_NE(piece.name, "saagen-validation-resources");
  // Kernels of the SAA variants get no resource piece either: their sources are as before.
  for (const saagen::Variant& variant : saagen::Catalogue::builtin().variants()) {
    saagen::EmitOptions variant_options;
    variant_options.variants = {variant.id};
    const auto variant_file = saagen::emit_variants(saagen::Catalogue::builtin(), variant_options).front();
    saagen::KernelRequest request;
    request.body = "    SAAGEN_STORE(0, 1.0);\n";
    request.output_stride = 1;
    const auto kernel = saagen::kernel_sources(saagen::Catalogue::builtin(), variant_file.file_name, variant_file.content, request);
    ASSERT_EQ(kernel.size(), 3u) << variant.id;
    for (const auto& piece : kernel) EXPECT_NE(piece.name, "saagen-kernel-resources") << variant.id;
  }
  const auto glint = glints::emit(options_for("glsl")).front();
  const auto glint_pieces = saagen::validation_sources(glints::catalogue(), *saagen::find_marker(glint.content), glint.file_name,
                                                       glint.content, saagen::ShaderStage::compute);
  ASSERT_EQ(glint_pieces.size(), 4u);
  EXPECT_EQ(glint_pieces[1].name, "saagen-validation-resources");
  EXPECT_NE(glint_pieces[1].text.find("uniform sampler1DArray saagen_glint_dictionary;"), std::string::npos);
}

}  // namespace

// Scene manifests (test_manifest): minimal emission (exactly the dependency closure; removing a
// material removes its code), one advice (the planner, emit's defaults, the emitted headers, the
// examples and examples/INTEGRATION.md say the same thing), and the scene commands of the CLI.
#include "manifest_support.hpp"

#include "saagen/validate/validation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using saagen::Catalogue;
using namespace saagen::test::manifest;

// ---------------------------------------------------------------------------------------------
// Minimal emission

TEST(Bundle, HoldsExactlyTheClosureOfTheMaterialsFunctions) {
  const saagen::Manifest manifest = saagen::load_manifest(example_manifest, Catalogue::builtin());
  const saagen::ScenePlan plan = saagen::plan_scene(Catalogue::builtin(), manifest);
  const auto files = saagen::emit_scene(Catalogue::builtin(), manifest, plan);
  // glsl + hlsl, fp32 only: the fp16 material, foliage, prefers speed and is planned no filter (on
  // curved content only deferred-aniso beats no SAA in the deferred path, its most expensive form).
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].file_name, "saa_scene.glsl");
  EXPECT_EQ(files[1].file_name, "saa_scene.hlsl");

  for (const saagen::EmittedFile& file : files) {
    const bool half = saagen::is_half(file.marker.precision);
    std::vector<std::string> roots;
    for (const saagen::MaterialPlan& material : plan.materials) {
      if (saagen::is_half(material.precision) != half) continue;
      for (const std::string& name : material.functions) {
        if (std::find(roots.begin(), roots.end(), name) == roots.end()) roots.push_back(name);
      }
    }
    EXPECT_EQ(file.marker.functions, roots) << file.file_name;
    // Catalogue functions only: a precision's target support (e.g. fp16 derivative helpers in
    // the target table's preamble) is not part of the catalogue's closure.
    std::set<std::string> defined;
    for (const std::string& name : defined_functions(file.content, "saa_")) {
      if (Catalogue::builtin().find_function(name)) defined.insert(name);
    }
    EXPECT_EQ(defined, closure_names(roots)) << file.file_name;
    // Nothing else of the catalogue appears, not even in a comment.
    for (const saagen::Function& function : Catalogue::builtin().functions()) {
      if (defined.count(function.name)) continue;
      EXPECT_FALSE(std::regex_search(file.content, std::regex("\\bsaa_" + function.name + "\\b")))
          << file.file_name << ": " << function.name;
    }
  }
  // The fp32 GLSL bundle: brushed_metal, terrain and car_paint (forward-aniso-projected/tail, saagen's
  // normal-mapped decision); not foliage's filter (advised no filter: nothing in the bundle).
  const std::set<std::string> defined = defined_functions(files[0].content, "saa_");
  // car_paint: the projected form's transported wrapper, as the advice was measured, not the papers'.
  EXPECT_TRUE(defined.count("forward_aniso_projected_transported_fragment"));
  EXPECT_TRUE(defined.count("forward_aniso_projected"));  // the wrapper pulls its core
  EXPECT_FALSE(defined.count("forward_aniso_projected_fragment"));
  EXPECT_TRUE(defined.count("forward_axis_slope_fragment"));  // brushed_metal: the cheapest form for speed
  EXPECT_FALSE(defined.count("deferred_aniso_fragment"));
  EXPECT_TRUE(defined.count("deferred_sum_fragment"));
  // GGX pulls the tail-preserving filtered GGX: terrain's deferred-sum at one light its one-pass
  // form (the split per pixel and per light is planned from 4 lights on, where it is costed).
  EXPECT_FALSE(defined.count("ggx_filtered_lobe_isotropic"));
  EXPECT_FALSE(defined.count("ggx_brdf_filtered_lobe"));
  EXPECT_TRUE(defined.count("ggx_brdf_filtered_axis"));
  EXPECT_FALSE(defined.count("beckmann_brdf_matrix"));  // brushed_metal (Beckmann) prefers speed: axis filter, own BRDF
  EXPECT_FALSE(defined.count("deferred_aniso"));
  EXPECT_FALSE(defined.count("ggx_brdf_axis"));
}

TEST(Bundle, RemovingAMaterialRemovesItsCode) {
  const std::string full = read_text(example_manifest);
  // Without terrain (the only deferred-sum material).
  const auto start = full.find("[[material]]\nname = \"terrain\"");
  ASSERT_NE(start, std::string::npos);
  const auto end = full.find("[[material]]", start + 1);
  const std::string reduced = full.substr(0, start) + full.substr(end);

  const auto before = emit_text(full);
  const auto after = emit_text(reduced);
  ASSERT_EQ(before.size(), after.size());
  const std::set<std::string> had = defined_functions(before[0].content, "saa_");
  const std::set<std::string> has = defined_functions(after[0].content, "saa_");
  std::set<std::string> removed;
  for (const std::string& name : had) {
    if (!has.count(name)) removed.insert(name);
  }
  EXPECT_TRUE(removed.count("deferred_sum_fragment"));
  EXPECT_TRUE(removed.count("deferred_sum"));
  for (const std::string& name : has) EXPECT_TRUE(had.count(name)) << name;
  EXPECT_EQ(has, closure_names(after[0].marker.functions));
  EXPECT_EQ(after[0].content.find("saa_deferred_sum"), std::string::npos);
  EXPECT_EQ(after[0].content.find("terrain"), std::string::npos);
  // The other target's bundle loses it too.
  EXPECT_EQ(after[1].content.find("terrain"), std::string::npos);
  EXPECT_NE(before[1].content.find("terrain"), std::string::npos);
}

TEST(Bundle, IsDeterministicAndValidatesInProcess) {
  const std::string text = read_text(example_manifest);
  const auto first = emit_text(text);
  const auto second = emit_text(text);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t index = 0; index < first.size(); ++index) {
    EXPECT_EQ(first[index].content, second[index].content);
    const saagen::FileValidation validation = saagen::validate_file(Catalogue::builtin(), first[index].file_name, first[index].content);
    EXPECT_TRUE(validation.ok()) << validation.summary();
  }
}

// An all-GGX scene that does not set sigma2 gets the kernel measured best with the
// tail-preserving filtered GGX it is shaded with (the pixel filter's own 0.25, said with its
// reason); a scene with a Beckmann material, or one that sets sigma2, keeps what it says.
TEST(Planner, AllGgxScenesGetTheGgxFittedKernel) {
  const auto ggx = emit_text(header + forward_material);
  EXPECT_EQ(saagen::find_marker(ggx.at(0).content)->option_values.at("sigma2"), saagen::kGgxSigma2);
  EXPECT_EQ(saagen::kGgxSigma2, 0.25);
  const saagen::Manifest manifest = parse(header + forward_material);
  EXPECT_NE(saagen::format_plan(Catalogue::builtin(), manifest, saagen::plan_scene(Catalogue::builtin(), manifest))
                .find("options: sigma2 = 0.25 (every material is GGX, shaded with the tail-preserving filtered GGX"),
            std::string::npos);
  const auto mixed = emit_text(header + forward_material + "[[material]]\nname = \"b\"\npath = \"deferred\"\nndf = \"beckmann\"\n");
  EXPECT_EQ(saagen::find_marker(mixed.at(0).content)->option_values.at("sigma2"), 0.25);
  const auto set = emit_text(header + "sigma2 = 0.2\n" + forward_material);
  EXPECT_EQ(saagen::find_marker(set.at(0).content)->option_values.at("sigma2"), 0.2);
}

TEST(Bundle, MarkerRecordsThePublicFunctions) {
  const auto files = emit_text(header + "prefix = \"eng_\"\nsigma2 = 0.5\n" + forward_material);
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].file_name, "eng_scene.glsl");
  const auto marker = saagen::find_marker(files[0].content);
  ASSERT_TRUE(marker);
  EXPECT_EQ(marker->target, saagen::OutputTarget::snippet("glsl"));
  EXPECT_EQ(marker->prefix, "eng_");
  // A forward GGX material without tangents on curved content: deferred-aniso (saagen/advice.hpp).
  EXPECT_EQ(marker->variants, (std::vector<std::string>{"deferred-aniso"}));
  EXPECT_EQ(marker->functions,
            (std::vector<std::string>{"deferred_aniso", "deferred_aniso_fragment", "deferred_aniso_roughness", "deferred_aniso_brdf"}));
  EXPECT_EQ(marker->option_values.at("sigma2"), 0.5);
  EXPECT_NE(files[0].content.find("#ifndef ENG_BUNDLE_SCENE_GLSL"), std::string::npos);
  EXPECT_NE(files[0].content.find("#ifndef ENG_CORE_ONLY"), std::string::npos);
  EXPECT_NE(files[0].content.find("const float eng_SIGMA2 = 0.5;"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// One advice (saagen/advice.hpp): the planner, emit's defaults, the emitted headers, the examples
// and examples/INTEGRATION.md say the same thing, so that they cannot drift apart again.

const saagen::MaterialPlan& planned(const saagen::ScenePlan& plan, const std::string& material) {
  for (const saagen::MaterialPlan& entry : plan.materials)
    if (entry.material == material) return entry;
  throw std::runtime_error("no material " + material);
}

TEST(Advice, EmitDefaultsAndHeadersAreTheAdvice) {
  const auto defaults = saagen::resolve_options(Catalogue::builtin(), {});
  EXPECT_EQ(defaults.at("sigma2"), saagen::advice::kSigma2);
  EXPECT_EQ(defaults.at("kappa"), saagen::advice::kKappa);
  EXPECT_EQ(saagen::kGgxSigma2, saagen::advice::kSigma2);
  EXPECT_EQ(saagen::kTaaSigma2, saagen::advice::kTaaSigma2);
  for (const std::string target : {"glsl", "gles", "hlsl", "wgsl"}) {
    saagen::EmitOptions options;
    options.target = target;
    options.variants = {"deferred-sum", "forward-axis-projected"};
    for (const saagen::EmittedFile& file : saagen::emit_variants(Catalogue::builtin(), options)) {
      EXPECT_NE(file.content.find(std::string(saagen::advice::kNormalText)), std::string::npos) << file.file_name;
      EXPECT_EQ(file.content.find("{advice:"), std::string::npos) << file.file_name;
    }
    // The prefilter snippets' headers say how to sample the map and its bake: the LOD bias.
    options.variants = {"prefilter-toksvig", "prefilter-lean"};
    const auto prefilter_files = saagen::emit_variants(Catalogue::builtin(), options);
    ASSERT_FALSE(prefilter_files.empty()) << target;
    for (const saagen::EmittedFile& file : prefilter_files) {
      EXPECT_NE(file.content.find(std::string(saagen::advice::kPrefilterSamplingText)), std::string::npos) << file.file_name;
      EXPECT_EQ(file.content.find("{advice:"), std::string::npos) << file.file_name;
    }
  }
  // The text quotes the constant: the bias argument of each language's sample.
  const std::string bias = std::to_string(saagen::advice::kPrefilterLodBias) + ".0";
  for (const std::string call : {"texture(map, uv, ", "SampleBias(s, uv, ", "textureSampleBias(map, s, uv, "}) {
    EXPECT_NE(std::string(saagen::advice::kPrefilterSamplingText).find(call + bias + ")"), std::string::npos) << call;
  }
}

TEST(Advice, ExamplesAndDocsAgreeWithThePlanner) {
  const fs::path root(SAAGEN_SOURCE_DIR);
  // The reference manifest's normal-mapped materials: car_paint follows the advice for
  // normal-mapped content; terrain names its filter and gets saagen's decision among its feeds and
  // bakes (the geometric normal, no bake), the three.js module's default.
  const saagen::Manifest example = saagen::load_manifest(example_manifest, Catalogue::builtin());
  const saagen::ScenePlan example_plan = saagen::plan_scene(Catalogue::builtin(), example);
  const bool normal_mapped_wins = planned(saagen::plan_scene(Catalogue::builtin(), parse(header + "[[material]]\nname = \"m\"\npath = "
                                                                                                  "\"deferred\"\nnormal_maps = true\n")),
                                          "m")
                                      .variant != "none";
  EXPECT_EQ(planned(example_plan, "car_paint").variant == "none", !normal_mapped_wins);
  const saagen::MaterialPlan& terrain = planned(example_plan, "terrain");
  EXPECT_EQ(terrain.rule, "manifest");
  EXPECT_EQ(terrain.variant, "deferred-sum");
  EXPECT_EQ(terrain.feed, "geometric");
  EXPECT_EQ(terrain.prefilter, "none");
  // A planned bake comes with the LOD bias its trade rows were measured with; no bake, no bias.
  EXPECT_EQ(terrain.normal_advice.find(std::string(saagen::advice::kPrefilterSamplingText)) != std::string::npos,
            terrain.prefilter != "none")
      << terrain.normal_advice;
  const std::string module = read_text(root / "examples" / "threejs" / "saagen-three.js");
  std::smatch defaults;
  ASSERT_TRUE(std::regex_search(module, defaults, std::regex("wrapper = '(\\w+)', normal = '(\\w+)'"))) << "installSaagen's defaults";
  EXPECT_EQ(defaults[1].str(), terrain.wrapper);
  EXPECT_EQ(defaults[2].str(), terrain.feed);
  std::smatch bias;
  ASSERT_TRUE(std::regex_search(module, bias, std::regex("PREFILTER_LOD_BIAS = (\\d+);"))) << "the module's LOD bias";
  EXPECT_EQ(std::stoi(bias[1].str()), saagen::advice::kPrefilterLodBias);
  const std::string page = read_text(root / "examples" / "threejs" / "index.html");
  // The page installs what its manifest's plan says per material (installPlan); what it claims
  // of the normal-mapped material is that plan.
  const saagen::Manifest three = saagen::load_manifest(root / "examples" / "threejs" / "scene.saagen.toml", Catalogue::builtin());
  const saagen::ScenePlan three_plan = saagen::plan_scene(Catalogue::builtin(), three);
  EXPECT_EQ(planned(three_plan, "bumpy").variant == "none", !normal_mapped_wins);
  // The page and the module claim no plan of their own: they point at `saagen plan --advice`.
  for (const std::string* text : {&page, &module}) {
    EXPECT_EQ(text->find("advice for normal-mapped content is no"), std::string::npos);
    EXPECT_NE(text->find("saagen plan --advice"), std::string::npos);
  }
  EXPECT_NE(page.find("saagen plan examples/threejs/scene.saagen.toml --json > examples/threejs/generated/plan.json"), std::string::npos);
  EXPECT_NE(page.find("saagen emit --manifest examples/threejs/scene.saagen.toml -o examples/threejs/generated"), std::string::npos);
  EXPECT_NE(page.find("planEntry("), std::string::npos);
  EXPECT_EQ(page.find("--sigma2"), std::string::npos);  // emit's default: the advice's sigma^2
  EXPECT_EQ(page.find("--kappa"), std::string::npos);

  // The WebGPU example calls what its manifest plans.
  const fs::path webgpu = root / "examples" / "webgpu";
  const saagen::Manifest beads = saagen::load_manifest(webgpu / "scene.saagen.toml", Catalogue::builtin());
  const saagen::ScenePlan beads_plan = saagen::plan_scene(Catalogue::builtin(), beads);
  const saagen::MaterialPlan& glossy = planned(beads_plan, "glossy_beads");
  EXPECT_EQ(glossy.rule, "manifest");  // named: the example shows the call whatever the advice
  EXPECT_EQ(glossy.variant, "forward-aniso-projected");
  const std::string render = read_text(webgpu / "render.mjs");
  EXPECT_NE(render.find("saa_" + glossy.wrapper + "("), std::string::npos) << glossy.wrapper;
  ASSERT_TRUE(glossy.brdf);
  EXPECT_NE(render.find("saa_" + *glossy.brdf + "("), std::string::npos) << *glossy.brdf;

  // The CMake consumer's shaders call what its manifest plans.
  const fs::path consumer = root / "examples" / "cmake-consumer";
  const saagen::Manifest consumer_manifest = saagen::load_manifest(consumer / "scene.saagen.toml", Catalogue::builtin());
  std::string shaders;
  for (const char* name : {"forward_lit.frag", "gbuffer.frag", "deferred_light.frag"}) shaders += read_text(consumer / "shaders" / name);
  // Its normal-mapped materials' shaders sample the map with the advised LOD bias.
  const std::string biased_read = "texture(normal_map, in_uv, " + std::to_string(saagen::advice::kPrefilterLodBias) + ".0)";
  EXPECT_EQ(std::regex_search(shaders, std::regex("texture\\(normal_map, in_uv\\)")), false) << "a normal map read without the bias";
  EXPECT_NE(shaders.find(biased_read), std::string::npos) << biased_read;
  for (const saagen::MaterialPlan& material : saagen::plan_scene(Catalogue::builtin(), consumer_manifest).materials) {
    EXPECT_NE(shaders.find("saa_" + material.wrapper + "("), std::string::npos) << material.material;
    if (material.brdf) {
      EXPECT_NE(shaders.find("saa_" + *material.brdf + "("), std::string::npos) << material.material;
    }
  }

  // INTEGRATION.md lists every target (its advice table: IntegrationGuideHoldsTheAdviceTable).
  const std::string integration = read_text(root / "examples" / "INTEGRATION.md");
  // INTEGRATION.md, the user guide and docs/PREFILTER.md give the same bias argument.
  const std::string bias_argument = "texture(map, uv, " + std::to_string(saagen::advice::kPrefilterLodBias) + ".0)";
  for (const char* doc : {"examples/INTEGRATION.md", "docs/GUIDE.md", "docs/PREFILTER.md"}) {
    EXPECT_NE(read_text(root / doc).find(bias_argument), std::string::npos) << doc << ": " << bias_argument;
  }
  const auto targets_row = integration.find("| `targets` |");
  ASSERT_NE(targets_row, std::string::npos);
  const std::string row = integration.substr(targets_row, integration.find('\n', targets_row) - targets_row);
  for (const char* target : {"glsl", "gles", "hlsl", "wgsl", "spirv"}) EXPECT_NE(row.find(target), std::string::npos) << target;
}

// ---------------------------------------------------------------------------------------------
// CLI

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

class SceneCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    scratch_ = fs::temp_directory_path() / (std::string("saagen-manifest-") + info->name() + "-" + std::to_string(::getpid()));
    fs::remove_all(scratch_);
    fs::create_directories(scratch_);
  }
  void TearDown() override { fs::remove_all(scratch_); }

  CliRun saagen(const std::string& arguments) const {
    const fs::path out = scratch_ / "stdout.txt";
    const fs::path err = scratch_ / "stderr.txt";
    const std::string command = std::string("'") + SAAGEN_CLI_PATH + "' " + arguments + " >'" + out.string() + "' 2>'" + err.string() + "'";
    const int status = std::system(command.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(out), read_text(err)};
  }

  void write(const fs::path& path, const std::string& text) const {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
  }

  fs::path scratch_;
};

TEST_F(SceneCli, PlanPrintsVariantWhyCallAndCost) {
  const CliRun run = saagen("plan '" + example_manifest.string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("material terrain"), std::string::npos);
  EXPECT_NE(run.out.find("variant   deferred-sum  [manifest]"), std::string::npos) << run.out;  // terrain names it
  EXPECT_NE(run.out.find("variant   none  [advice]"), std::string::npos) << run.out;            // foliage
  EXPECT_NE(run.out.find("[saagen's decision on normal-mapped content in saagen's trade"), std::string::npos) << run.out;  // car_paint
  EXPECT_NE(run.out.find("  measure   this advice"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("why       "), std::string::npos);
  EXPECT_NE(run.out.find("cost      glsl +"), std::string::npos) << run.out;
}

TEST_F(SceneCli, BadManifestIsOneLineWithPosition) {
  write(scratch_ / "bad.toml", header + forward_material + "ndf = \"phong\"\n");
  const CliRun run = saagen("plan '" + (scratch_ / "bad.toml").string() + "' --no-cost");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("bad.toml:5:7: key 'ndf' of material 'm': unknown value \"phong\"; allowed: \"ggx\", \"beckmann\""),
            std::string::npos)
      << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
}

TEST_F(SceneCli, EmitWritesOnlyWhenBytesChangeAndRefusesForeignFiles) {
  const fs::path out = scratch_ / "out";
  const std::string manifest = "--manifest '" + example_manifest.string() + "' -o '" + out.string() + "'";
  CliRun run = saagen("emit " + manifest);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("wrote     " + (out / "saa_scene.glsl").string()), std::string::npos) << run.out;
  run = saagen("emit " + manifest);
  EXPECT_NE(run.out.find("unchanged " + (out / "saa_scene.glsl").string()), std::string::npos) << run.out;
  run = saagen("validate '" + out.string() + "'");
  EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("2 file(s) validated, 0 failed"), std::string::npos) << run.out;

  run = saagen("emit " + manifest + " --list-outputs");
  EXPECT_EQ(run.out, (out / "saa_scene.glsl").string() + "\n" + (out / "saa_scene.hlsl").string() + "\n");

  write(out / "saa_scene.hlsl", "// my own file\n");
  run = saagen("emit " + manifest);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("exists and was not written by saagen; refusing to overwrite it (use --force)"), std::string::npos) << run.err;
  EXPECT_EQ(read_text(out / "saa_scene.hlsl"), "// my own file\n");
  run = saagen("emit " + manifest + " --force");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(saagen::find_marker(read_text(out / "saa_scene.hlsl")));
}

// A manifest whose every material is advised no filter writes nothing and says so.
TEST_F(SceneCli, EmitOfOnlyNoFilterMaterialsWritesNothing) {
  // Curved content, deferred, prefer speed: only the most expensive form beats no SAA, so no filter.
  const fs::path manifest = scratch_ / "speed.toml";
  write(manifest, header + "[[material]]\nname = \"m\"\npath = \"deferred\"\nprefer = \"speed\"\n");
  const CliRun run = saagen("emit --manifest '" + manifest.string() + "' -o '" + (scratch_ / "out").string() + "'");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("nothing to write: every material of"), std::string::npos) << run.out;
  EXPECT_FALSE(fs::exists(scratch_ / "out"));
}

TEST_F(SceneCli, ManifestExcludesPerVariantOptions) {
  const CliRun run = saagen("emit --manifest '" + example_manifest.string() + "' --target hlsl -o '" + (scratch_ / "out").string() + "'");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--target excludes --manifest"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(scratch_ / "out"));
}

TEST_F(SceneCli, CompileResolvesIncludesOfTheBundle) {
  const fs::path out = scratch_ / "gen";
  ASSERT_EQ(saagen("emit --manifest '" + example_manifest.string() + "' -o '" + out.string() + "'").exit_code, 0);
  write(scratch_ / "shaders" / "lit.frag",
        "#version 450\n"
        "#include \"saa_scene.glsl\"\n"
        "layout(location = 0) in vec3 normal_ws;\n"
        "layout(location = 0) out vec4 color;\n"
        "void main() { color = vec4(saa_deferred_sum_fragment(0.04, normalize(normal_ws))); }\n");
  CliRun run = saagen("compile '" + (scratch_ / "shaders" / "lit.frag").string() + "' -I '" + out.string() + "' -o '" +
                      (scratch_ / "lit.spv").string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  EXPECT_GT(fs::file_size(scratch_ / "lit.spv"), 100u);
  EXPECT_EQ(read_text(scratch_ / "lit.spv").substr(0, 4), std::string("\x03\x02\x23\x07", 4));  // SPIR-V magic

  // An error names the file and the line after the include.
  write(scratch_ / "shaders" / "bad.frag", "#version 450\n#include \"saa_scene.glsl\"\nvoid main() { undefined_call(); }\n");
  run = saagen("compile '" + (scratch_ / "shaders" / "bad.frag").string() + "' -I '" + out.string() + "' -o '" +
               (scratch_ / "bad.spv").string() + "'");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.err.find("bad.frag:3"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(scratch_ / "bad.spv"));
}

}  // namespace

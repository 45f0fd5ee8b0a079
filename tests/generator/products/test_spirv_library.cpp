// Linkable SPIR-V library modules and the C/C++ headers that embed them.
//
// - Every variant's library is a valid SPIR-V 1.3 module (universal rules; Vulkan's reject the
//   Linkage capability itself) with Linkage, no entry point, and an Export decoration named by
//   the emitted function name on each core / evaluate function; bytes are deterministic.
// - The header holds the same words (parsed back and also compiled and run as C++, and compiled
//   as C), the marker line, and the reflection JSON of `saagen list --json`.
// - The link test: for every exported function, a consumer compute shader is compiled with a
//   stub of the function, the stub becomes an Import declaration (saagen::import_stub_functions),
//   the library and the consumer are linked with the SPIRV-Tools linker API, the result passes
//   spirv-val with Vulkan 1.1 rules and runs on the Vulkan device (lavapipe) over 10 240 inputs,
//   compared with the double-precision reference (bound below) and with the same function
//   compiled from source (the emitted GLSL included in the kernel).
//
// Inputs (a local generator, not test_gpu_core's grid): unit directions with z in [0.2, 1],
// alpha^2 in [1e-4, 1], roughness matrices with eigenvalues in [0.01, 0.5] and ratio <= 10,
// derivative magnitudes 1e-4 .. 1. Bound per output: 4e-5 * S + 1e-30 with S the magnitude scale
// of test_gpu_core (filters: the function on the absolute values of the derivative inputs; BRDF
// terms: |f| (1 + conditioning + Beckmann exponent), Lambda terms: (1 + |f|)(1 + conditioning)),
// twice test_gpu_core's 2e-5.
#include "host_compiler.hpp"
#include "support/gpu_support.hpp"
#include "support/reference_dispatch.hpp"

#include "saagen/emit/engines.hpp"
#include "saagen/emit/listing.hpp"
#include "saagen/error.hpp"
#include "saagen/products/output_validation.hpp"
#include "saagen/products/spirv_library.hpp"
#include "saagen/reference/reference.hpp"

#include <spirv-tools/libspirv.hpp>
#include <spirv-tools/linker.hpp>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <regex>
#include <sstream>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
namespace ref = saagen::ref;
using ref::Sym2;
using ref::Vec2;
using ref::Vec3;
using saagen::Catalogue;

constexpr std::uint32_t element_count = 10240;
constexpr double rounding_bound = 4e-5;

const std::vector<saagen::SpirvLibrary>& libraries() {
  static const std::vector<saagen::SpirvLibrary> all = saagen::emit_spirv_libraries(Catalogue::builtin(), saagen::EmitOptions{});
  return all;
}

const saagen::SpirvLibrary& library_of(const std::string& variant) {
  for (const auto& library : libraries()) {
    if (library.marker.variants.front() == variant) return library;
  }
  throw std::runtime_error("no library for " + variant);
}

std::vector<std::string> exported_template_names(const saagen::Variant& variant) {
  std::vector<std::string> names;
  for (const std::string& name : variant.functions) {
    if (!Catalogue::builtin().find_function(name)->fragment_only) names.push_back(name);
  }
  return names;
}

std::string disassembly(const std::vector<std::uint32_t>& words) { return saagen::disassemble_spirv(words); }

std::string read_file(const fs::path& path) {
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream content;
  content << stream.rdbuf();
  return content.str();
}

int run_command(const std::string& command) { return std::system((command + " > /dev/null 2>&1").c_str()); }

fs::path fresh_directory(const std::string& name) {
  const fs::path directory = fs::temp_directory_path() / fmt::format("saagen_{}_{}", name, ::getpid());
  fs::remove_all(directory);
  fs::create_directories(directory);
  return directory;
}

// ---------------------------------------------------------------------------------------------
// Module structure

TEST(SpirvLibrary, EveryVariantIsAValidLinkableModuleExportingItsCoreFunctions) {
  ASSERT_EQ(libraries().size(), Catalogue::builtin().variants().size());
  std::size_t exported = 0;
  for (const saagen::Variant& variant : Catalogue::builtin().variants()) {
    const auto& library = library_of(variant.id);
    std::vector<std::string> names;
    for (const std::string& name : exported_template_names(variant)) names.push_back("saa_" + name);
    EXPECT_EQ(saagen::validate_spirv_library(library.words, names), "") << library.file_name;
    const std::string text = disassembly(library.words);
    EXPECT_NE(text.find("OpCapability Linkage"), std::string::npos);
    EXPECT_EQ(text.find("OpEntryPoint"), std::string::npos);
    EXPECT_EQ(text.find("WorkgroupSize"), std::string::npos) << "the validation main's workgroup size must go with it";
    EXPECT_NE(text.find("saagen-marker: target=spirv variants=" + variant.id + " prefix=saa_"), std::string::npos);
    ASSERT_EQ(library.exports.size(), names.size());
    for (std::size_t index = 0; index < names.size(); ++index) {
      EXPECT_EQ(library.exports[index].name, names[index]);
      EXPECT_NE(text.find(fmt::format("OpDecorate %{} LinkageAttributes \"{}\" Export", library.exports[index].id, names[index])),
                std::string::npos);
      // glslang's calling convention: every parameter a Function pointer.
      const saagen::Function& function = *Catalogue::builtin().find_function(library.exports[index].template_name);
      std::size_t pointers = 0;
      for (std::size_t at = 0; (at = library.exports[index].spirv_type.find("ptr<Function,", at)) != std::string::npos; ++at) ++pointers;
      EXPECT_EQ(pointers, function.parameters.size()) << library.exports[index].spirv_type;
    }
    // Helpers are not exported: the Export decorations are exactly the public functions.
    std::size_t decorations = 0;
    for (std::size_t at = 0; (at = text.find("LinkageAttributes", at)) != std::string::npos; ++at) ++decorations;
    EXPECT_EQ(decorations, names.size()) << library.file_name;
    exported += names.size();
    std::cout << fmt::format("[ size     ] {:<34} {:>6} bytes {:>5} instructions, {} export(s)\n", library.file_name,
                             library.words.size() * 4, saagen::count_spirv_instructions(library.words), names.size());
  }
  // As test_kernels: 4 forward + 7 deferred cores, deferred-aniso's covariance and 6 lighting
  // functions, 14 GGX + 6 Beckmann evaluators, 9 prefilter cores.
  EXPECT_EQ(exported, 47u);
}

TEST(SpirvLibrary, BytesAreDeterministicAndFollowTheEmissionOptions) {
  saagen::EmitOptions options;
  options.variants = {"deferred-sum"};
  const auto first = saagen::emit_spirv_libraries(Catalogue::builtin(), options).front();
  const auto second = saagen::emit_spirv_libraries(Catalogue::builtin(), options).front();
  EXPECT_EQ(first.words, second.words);
  EXPECT_EQ(saagen::spirv_library_header(Catalogue::builtin(), first), saagen::spirv_library_header(Catalogue::builtin(), second));

  options.prefix = "eng_";
  options.option_values = {{"kappa", 0.5}};
  const auto prefixed = saagen::emit_spirv_libraries(Catalogue::builtin(), options).front();
  EXPECT_EQ(prefixed.file_name, "eng_deferred_sum.spv");
  EXPECT_EQ(prefixed.exports.front().name, "eng_deferred_sum");
  const std::string text = disassembly(prefixed.words);
  EXPECT_NE(text.find("LinkageAttributes \"eng_deferred_sum\" Export"), std::string::npos);
  EXPECT_NE(text.find("kappa=0.5"), std::string::npos);
  EXPECT_NE(prefixed.words, first.words);

  options.precision = saagen::Precision::fp16;
  options.prefix = "saa_";
  const auto half = saagen::emit_spirv_libraries(Catalogue::builtin(), options).front();
  EXPECT_EQ(half.file_name, "saa_deferred_sum_fp16.spv");
  EXPECT_EQ(saagen::validate_spirv_library(half.words, {"saa_deferred_sum"}), "");
  EXPECT_NE(half.exports.front().spirv_type.find("f16"), std::string::npos) << half.exports.front().spirv_type;

  saagen::EmitOptions unknown;
  unknown.variants = {"no-such-variant"};
  EXPECT_THROW(saagen::emit_spirv_libraries(Catalogue::builtin(), unknown), saagen::Error);
}

TEST(SpirvLibrary, ReflectionIsTheListJsonOfTheExportedFunctions) {
  const nlohmann::json catalogue = saagen::catalogue_json(Catalogue::builtin(), "saa_");
  for (const auto& library : libraries()) {
    const auto& reflection = library.reflection;
    EXPECT_EQ(reflection.at("module"), library.file_name);
    EXPECT_EQ(reflection.at("prefix"), "saa_");
    const auto& exports = reflection.at("exports");
    ASSERT_EQ(exports.size(), library.exports.size());
    for (std::size_t index = 0; index < exports.size(); ++index) {
      nlohmann::json entry = exports[index];
      EXPECT_EQ(entry.at("linkage_name"), library.exports[index].name);
      EXPECT_EQ(entry.at("spirv_type"), library.exports[index].spirv_type);
      entry.erase("linkage_name");
      entry.erase("spirv_type");
      bool found = false;
      for (const auto& variant : catalogue.at("variants")) {
        for (const auto& function : variant.at("functions")) found = found || function == entry;
      }
      EXPECT_TRUE(found) << library.file_name << ": " << entry.dump();
    }
  }
}

TEST(SpirvLibrary, HeaderEmbedsTheWordsAndCompilesAsCppAndC) {
  SAAGEN_SKIP_WITHOUT_HOST_COMPILER(SAAGEN_TEST_CXX_COMPILER);
  const auto& library = library_of("deferred-sum");
  const std::string header = saagen::spirv_library_header(Catalogue::builtin(), library);
  EXPECT_EQ(header.find("// saagen-marker: target=spirv variants=deferred-sum prefix=saa_"), header.find("// saagen-marker:"));
  EXPECT_TRUE(saagen::find_marker(header).has_value());
  EXPECT_NE(header.find("#ifndef SAA_DEFERRED_SUM_SPV_H"), std::string::npos);
  EXPECT_NE(header.find("inline constexpr"), std::string::npos);
  EXPECT_NE(header.find(fmt::format("saa_deferred_sum_spv_word_count = {};", library.words.size())), std::string::npos);
  // The array, parsed back.
  const auto begin = header.find("saa_deferred_sum_spv[");
  const auto end = header.find("};", begin);
  std::vector<std::uint32_t> words;
  const std::string array = header.substr(begin, end - begin);
  const std::regex hex("0x([0-9a-f]{8})u");
  for (auto it = std::sregex_iterator(array.begin(), array.end(), hex); it != std::sregex_iterator(); ++it) {
    words.push_back(static_cast<std::uint32_t>(std::stoul((*it)[1].str(), nullptr, 16)));
  }
  EXPECT_EQ(words, library.words);

  // Compiled and run as C++ (constexpr, the JSON parses), and compiled as C.
  const fs::path directory = fresh_directory("spv_header");
  std::ofstream(directory / library.header_name) << header;
  std::ofstream(directory / "main.cpp") << R"(#include "saa_deferred_sum.spv.h"
#include <cstdio>
#include <ostream>
static_assert(saa_deferred_sum_spv[0] == 0x07230203u, "magic");
static_assert(sizeof(saa_deferred_sum_spv) / 4 == saa_deferred_sum_spv_word_count, "count");
int main() {
  unsigned long sum = 0;
  for (size_t i = 0; i < saa_deferred_sum_spv_word_count; ++i) sum = sum * 31u + saa_deferred_sum_spv[i];
  std::printf("%lu %zu\n", sum, sizeof(saa_deferred_sum_spv_reflection_json));
  return 0;
}
)";
  std::ofstream(directory / "main.c")
      << "#include \"saa_deferred_sum.spv.h\"\nint main(void) { return (int)(saa_deferred_sum_spv[0] != 0x07230203u); }\n";
  const std::string compiler = SAAGEN_TEST_CXX_COMPILER;
  ASSERT_EQ(run_command(fmt::format("{} -std=c++17 -Wall -Wextra -Werror -o {} {}", compiler, (directory / "cpp").string(),
                                    (directory / "main.cpp").string())),
            0);
  const std::string output_path = (directory / "cpp.out").string();
  ASSERT_EQ(std::system(fmt::format("{} > {}", (directory / "cpp").string(), output_path).c_str()), 0);
  unsigned long expected_sum = 0;
  for (std::uint32_t word : library.words) expected_sum = expected_sum * 31u + word;
  std::istringstream output(read_file(output_path));
  unsigned long sum = 0;
  std::size_t json_size = 0;
  output >> sum >> json_size;
  EXPECT_EQ(sum, expected_sum);
  EXPECT_EQ(json_size, library.reflection.dump(2).size() + 2);  // + '\n' + NUL
  EXPECT_EQ(run_command(fmt::format("{} -x c -std=c99 -Wall -Werror -fsyntax-only {}", compiler, (directory / "main.c").string())), 0);
  fs::remove_all(directory);
}

TEST(SpirvLibrary, CliEmitWritesModulesAndHeadersThatValidate) {
  const fs::path directory = fresh_directory("spv_cli");
  const std::string cli = SAAGEN_CLI_PATH;
  ASSERT_EQ(run_command(fmt::format("{} emit --target spirv --variant deferred-sum --variant brdf-ggx -o {}", cli, directory.string())), 0);
  for (const std::string stem : {"saa_deferred_sum", "saa_brdf_ggx"}) {
    const std::string bytes = read_file(directory / (stem + ".spv"));
    const std::string variant = stem == "saa_deferred_sum" ? "deferred-sum" : "brdf-ggx";
    EXPECT_EQ(saagen::spirv_words_from_bytes(bytes), library_of(variant).words) << stem;
    EXPECT_EQ(read_file(directory / (stem + ".spv.h")), saagen::spirv_library_header(Catalogue::builtin(), library_of(variant)));
  }
  EXPECT_EQ(run_command(fmt::format("{} validate {}", cli, directory.string())), 0);
  // Re-running rewrites nothing (the marker in the module lets saagen recognise its own files).
  const auto before = fs::last_write_time(directory / "saa_deferred_sum.spv");
  ASSERT_EQ(run_command(fmt::format("{} emit --target spirv --variant deferred-sum -o {}", cli, directory.string())), 0);
  EXPECT_EQ(fs::last_write_time(directory / "saa_deferred_sum.spv"), before);
  // A corrupted module fails validation.
  std::string bytes = read_file(directory / "saa_brdf_ggx.spv");
  bytes[bytes.size() - 8] = '\x7f';
  std::ofstream(directory / "saa_brdf_ggx.spv", std::ios::binary) << bytes;
  EXPECT_NE(run_command(fmt::format("{} validate {}", cli, directory.string())), 0);
  fs::remove_all(directory);
}

// ---------------------------------------------------------------------------------------------
// The link test

Vec3 direction(double z, double azimuth) {
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(azimuth), r * std::sin(azimuth), z};
}

struct Draw {
  Vec3 h, w, i, o;
  Vec2 alpha2;
  Vec3 dh_x, dh_y;
  Sym2 a;
  double tau = 0.0;
  saagen::test::PrefilterInputs texel;  // normal-map prefiltering inputs
  saagen::test::TextureFrame frame;     // deferred_aniso_covariance's texture frame around h
};

Draw draw(std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto angle = [&] { return 6.283185307179586 * unit(random); };
  Draw d;
  d.h = direction(0.2 + 0.8 * unit(random), angle());
  d.w = direction(0.2 + 0.8 * unit(random), angle());
  d.i = direction(0.2 + 0.8 * unit(random), angle());
  d.o = direction(0.2 + 0.8 * unit(random), angle());
  d.alpha2 = {std::pow(10.0, -4.0 * unit(random)), std::pow(10.0, -4.0 * unit(random))};
  const ref::SphereBasis basis = ref::sphere_tangent_basis(d.h);
  const double m = std::pow(10.0, -4.0 + 4.0 * unit(random)), psi = angle(), ratio = unit(random);
  d.texel = saagen::test::prefilter_inputs(random());
  d.dh_x = m * (std::cos(psi) * basis.e_theta + std::sin(psi) * basis.e_phi);
  d.dh_y = (m * ratio) * (-std::sin(psi) * basis.e_theta + std::cos(psi) * basis.e_phi);
  const double l1 = 0.01 + 0.49 * unit(random), l2 = std::clamp(l1 * (1.0 + 9.0 * unit(random)), 0.01, 0.5);
  const double c = std::cos(psi), s = std::sin(psi);
  d.a = {l1 * c * c + l2 * s * s, (l1 - l2) * c * s, l1 * s * s + l2 * c * c};
  d.tau = ref::sym2_determinant(d.a) * (0.5 + unit(random));
  // From the draws above (no further draw, so the other functions' inputs stay as they were).
  d.frame = saagen::test::texture_frame(d.h, psi, ratio < 0.5 ? -1.0 : 1.0);
  return d;
}

void push(std::vector<float>& out, double v) { out.push_back(static_cast<float>(v)); }
void push(std::vector<float>& out, Vec2 v) { push(out, v.x), push(out, v.y); }
void push(std::vector<float>& out, Vec3 v) { push(out, v.x), push(out, v.y), push(out, v.z); }
void push(std::vector<float>& out, Sym2 m) { push(out, m.xx), push(out, m.xy), push(out, m.yy); }

// The inputs of a function, by parameter name (templates/*.saa).
void pack(const saagen::Function& function, const Draw& d, std::vector<float>& out) {
  const bool reads_alpha2 = saagen::test::takes_unfiltered_alpha2(function);
  const Sym2 tensor = ref::deferred_aniso(ref::Params{}, d.dh_x, d.dh_y, d.h);  // deferred-aniso's geometry pass
  for (const saagen::Parameter& parameter : function.parameters) {
    const std::string& name = parameter.name;
    if (name == "alpha2")
      parameter.type == "real" ? push(out, d.alpha2.x) : push(out, d.alpha2);
    else if (name == "dslope_dx")
      push(out, ref::slope_differential(d.h, d.dh_x));
    else if (name == "dslope_dy")
      push(out, ref::slope_differential(d.h, d.dh_y));
    else if (name == "dproj_dx")
      push(out, ref::projected_differential(d.h, d.dh_x));
    else if (name == "dproj_dy")
      push(out, ref::projected_differential(d.h, d.dh_y));
    else if (name == "dn_dx")
      push(out, d.dh_x);
    else if (name == "dn_dy")
      push(out, d.dh_y);
    else if (name == "h")
      push(out, function.name.find("g2") != std::string::npos ? ref::normalize(d.i + d.o) : d.h);
    else if (name == "w")
      push(out, d.w);
    else if (name == "i")
      push(out, d.i);
    else if (name == "o")
      push(out, d.o);
    else if (name == "a")
      push(out, reads_alpha2 ? Sym2{d.alpha2.x, 0.0, d.alpha2.y} + d.a : d.a);
    else if (name == "tau")
      push(out, d.tau);
    else if (name == "filtered")
      parameter.type == "real" ? push(out, d.a.xx) : push(out, Vec2{d.a.xx, d.a.yy});
    else if (name == "lobe")
      for (double v : ref::ggx_filtered_lobe_isotropic(d.a.xx, d.alpha2.x)) push(out, v);
    else if (name == "kernel")
      push(out, d.a.xx - d.alpha2.x);
    else if (name == "normal_ws")
      push(out, d.h);
    else if (name == "light_ws")
      push(out, d.i);
    else if (name == "view_ws")
      push(out, d.o);
    else if (name == "tensor")
      push(out, tensor);
    else if (name == "tensor_lobe")
      for (double v : ref::deferred_aniso_lobe(ref::Params{}, tensor, d.alpha2.x)) push(out, v);
    else if (name == "mean_length")
      push(out, d.texel.mean_length);
    else if (name == "slope_mean")
      push(out, d.texel.slope_mean);
    else if (name == "slope_second")
      push(out, d.texel.slope_second);
    else if (name == "tangent_ws")
      push(out, d.frame.tangent);
    else if (name == "bitangent_ws")
      push(out, d.frame.bitangent);
    else if (name == "covariance")
      push(out, ref::deferred_aniso_covariance(ref::Params{}, d.texel.slope_mean, d.texel.slope_second, d.frame.tangent, d.frame.bitangent,
                                               d.h));
    else
      throw std::runtime_error("no input for parameter " + name + " of " + function.name);
  }
}

using Reader = saagen::test::FloatReader;

struct Expected {
  std::vector<double> values;
  double scale = 0.0;  // magnitude scale of the bound (see the file comment)
};

double max_abs(const std::vector<double>& values) {
  double m = 0.0;
  for (double v : values) m = std::max(m, std::fabs(v));
  return m;
}

double conditioning(Sym2 a) {
  const double mean = 0.5 * (a.xx + a.yy), spread = std::sqrt(0.25 * (a.xx - a.yy) * (a.xx - a.yy) + a.xy * a.xy);
  return (mean + spread) / std::max(mean - spread, 1e-30);
}
double beckmann_exponent(Vec3 h, Sym2 a, double tau) {
  const double det = std::max(ref::sym2_determinant(a), tau);
  return ref::sym2_quadratic_form({a.yy, -a.xy, a.xx}, {h.x / h.z, h.y / h.z}) / det;
}

// The reference of every exported function on one element's fp32 inputs.
Expected reference(const std::string& name, Reader in) {
  const ref::Params p;
  Reader terms = in;
  if (auto prefiltered = saagen::test::prefilter_reference(name, p, in)) {
    const auto scale = *saagen::test::prefilter_reference(name, p, terms, true);
    return {*prefiltered, std::max(max_abs(*prefiltered), max_abs(scale))};
  }
  if (auto filtered = saagen::test::filtered_ggx_reference(name, p, in)) {
    const auto scale = *saagen::test::filtered_ggx_reference(name, p, terms, true);
    return {*filtered, std::max(max_abs(*filtered), max_abs(scale))};
  }
  if (auto tensor = saagen::test::deferred_aniso_reference(name, p, in)) {
    const auto scale = *saagen::test::deferred_aniso_reference(name, p, terms, true);
    return {*tensor, std::max(max_abs(*tensor), max_abs(scale))};
  }
  if (auto filter = saagen::test::filter_core_reference(name, p, in)) {
    const auto scale = *saagen::test::filter_core_reference(name, p, terms, true);
    return {*filter, std::max(max_abs(*filter), max_abs(scale))};
  }
  if (name == "ndf_clamp_tau") {
    const double v = ref::ndf_clamp_tau(in.vec2());
    return {{v}, std::fabs(v)};
  }
  const bool beckmann = name.rfind("beckmann", 0) == 0;
  if (name == "ggx_ndf_matrix" || name == "beckmann_ndf_matrix") {
    const Vec3 h = in.vec3();
    const Sym2 a = in.sym2();
    const double tau = in.real();
    const double v = beckmann ? ref::beckmann_ndf_matrix(h, a, tau) : ref::ggx_ndf_matrix(h, a, tau);
    return {{v}, std::fabs(v) * (1.0 + conditioning(a) + (beckmann ? beckmann_exponent(h, a, tau) : 0.0))};
  }
  if (name == "ggx_lambda_matrix" || name == "beckmann_lambda_matrix") {
    const Vec3 w = in.vec3();
    const Sym2 a = in.sym2();
    const double v = beckmann ? ref::beckmann_lambda_matrix(w, a) : ref::ggx_lambda_matrix(w, a);
    return {{v}, (1.0 + std::fabs(v)) * (1.0 + conditioning(a))};
  }
  if (name == "ggx_g2_matrix") {
    const Vec3 i = in.vec3(), o = in.vec3(), h = in.vec3();
    const Sym2 a = in.sym2();
    const double v = ref::ggx_g2_matrix(i, o, h, a);
    return {{v}, std::fabs(v) * (1.0 + conditioning(a))};
  }
  if (name == "ggx_brdf_matrix" || name == "beckmann_brdf_matrix") {
    const Vec3 i = in.vec3(), o = in.vec3();
    const Sym2 a = in.sym2();
    const double tau = in.real();
    const double v = beckmann ? ref::beckmann_brdf_matrix(i, o, a, tau) : ref::ggx_brdf_matrix(i, o, a, tau);
    const double exponent = beckmann ? beckmann_exponent(ref::normalize(i + o), a, tau) : 0.0;
    return {{v}, std::fabs(v) * (1.0 + conditioning(a) + exponent)};
  }
  if (name == "ggx_ndf_axis" || name == "beckmann_ndf_axis" || name == "ggx_lambda_axis") {
    const Vec3 h = in.vec3();
    const Vec2 a2 = in.vec2();
    const Sym2 a{a2.x, 0.0, a2.y};
    if (name == "ggx_lambda_axis") {
      const double v = ref::ggx_lambda_axis(h, a2);
      return {{v}, (1.0 + std::fabs(v)) * (1.0 + conditioning(a))};
    }
    const double v = beckmann ? ref::beckmann_ndf_axis(h, a2) : ref::ggx_ndf_axis(h, a2);
    return {{v}, std::fabs(v) * (1.0 + conditioning(a) + (beckmann ? beckmann_exponent(h, a, a2.x * a2.y) : 0.0))};
  }
  if (name == "ggx_brdf_axis" || name == "beckmann_brdf_axis") {
    const Vec3 i = in.vec3(), o = in.vec3();
    const Vec2 a2 = in.vec2();
    const Sym2 a{a2.x, 0.0, a2.y};
    const double v = beckmann ? ref::beckmann_brdf_axis(i, o, a2) : ref::ggx_brdf_axis(i, o, a2);
    const double exponent = beckmann ? beckmann_exponent(ref::normalize(i + o), a, a2.x * a2.y) : 0.0;
    return {{v}, std::fabs(v) * (1.0 + conditioning(a) + exponent)};
  }
  throw std::runtime_error("no reference for " + name);
}

// A consumer: the kernel that loads, calls and stores, compiled with a stub of `function` whose
// definition then becomes an Import declaration.
std::vector<std::uint32_t> consumer_module(const std::string& variant, const std::string& function, saagen::KernelRequest& request) {
  const saagen::EmissionMarker marker{
      saagen::OutputTarget::snippet("glsl"), {variant}, "saa_", {}, saagen::Precision::fp32, true, {function}};
  const std::string stubs = saagen::marker_line(marker) + "\n" + saagen::glsl_import_stubs(Catalogue::builtin(), {function}, "saa_");
  request.body = saagen::load_call_store_body(Catalogue::builtin(), function, request);
  const auto compiled =
      saagen::compile_to_spirv(saagen::kernel_compile_request(Catalogue::builtin(), "consumer-stubs.glsl", stubs, request));
  if (!compiled.ok) throw std::runtime_error("the consumer does not compile:\n" + compiled.log);
  return saagen::import_stub_functions(compiled.spirv, {"saa_" + function});
}

std::string link_messages;
spv_result_t link(const std::vector<std::vector<std::uint32_t>>& modules, std::vector<std::uint32_t>& linked) {
  spvtools::Context context(SPV_ENV_UNIVERSAL_1_3);
  link_messages.clear();
  context.SetMessageConsumer(
      [](spv_message_level_t, const char*, const spv_position_t&, const char* message) { link_messages += std::string(message) + "\n"; });
  return spvtools::Link(context, modules, &linked, spvtools::LinkerOptions{});
}

// `spirv`, a load-call-store kernel of `request`, over element_count elements of `inputs`.
std::vector<float> run_elements(const std::vector<std::uint32_t>& spirv, const std::vector<float>& inputs,
                                const saagen::KernelRequest& request) {
  saagen::harness::ComputeRun compute;
  compute.shader.spirv = spirv;
  compute.buffers = {saagen::harness::input_buffer(0, inputs),
                     saagen::harness::output_buffer<float>(1, std::size_t{element_count} * request.output_stride)};
  compute.groups = {element_count / request.workgroup_size, 1, 1};
  return saagen::harness::run_compute(saagen::test::gpu(), compute).buffer_as<float>(1);
}

struct LinkCase {
  std::string variant;
  std::string function;
};

// The parameter as ctest lists it (without a printer gtest prints the object's bytes, pointers
// included, so the test's name would change from run to run).
void PrintTo(const LinkCase& c, std::ostream* os) { *os << c.variant << " " << c.function; }

class LinkedLibraryOnGpu : public ::testing::TestWithParam<LinkCase> {};

TEST_P(LinkedLibraryOnGpu, ImportLinkValidateAndRunAgainstTheReference) {
  const LinkCase& c = GetParam();
  const saagen::Function& function = *Catalogue::builtin().find_function(c.function);
  const auto& library = library_of(c.variant);

  saagen::KernelRequest request;
  const auto consumer = consumer_module(c.variant, c.function, request);
  const std::string consumer_text = disassembly(consumer);
  EXPECT_NE(consumer_text.find(fmt::format("LinkageAttributes \"saa_{}\" Import", c.function)), std::string::npos);
  EXPECT_EQ(saagen::validate_spirv_library(consumer, {}).find("spirv-val"), std::string::npos)
      << saagen::validate_spirv_library(consumer, {});

  std::vector<std::uint32_t> linked;
  ASSERT_EQ(link({library.words, consumer}, linked), SPV_SUCCESS) << link_messages;
  ASSERT_EQ(saagen::validate_spirv(linked, saagen::ClientApi::vulkan), "");
  const std::string linked_text = disassembly(linked);
  EXPECT_EQ(linked_text.find("LinkageAttributes"), std::string::npos);
  EXPECT_EQ(linked_text.find("OpCapability Linkage"), std::string::npos);

  std::mt19937_64 random(0x5a1e8u + std::hash<std::string>{}(c.function) % 1000u);
  std::vector<float> inputs;
  for (std::uint32_t element = 0; element < element_count; ++element) pack(function, draw(random), inputs);
  ASSERT_EQ(inputs.size(), std::size_t{element_count} * request.input_stride);

  const auto run = [&](const std::vector<std::uint32_t>& spirv) { return run_elements(spirv, inputs, request); };
  const auto got = run(linked);

  std::vector<double> expected, bound;
  for (std::uint32_t element = 0; element < element_count; ++element) {
    const Expected e = reference(c.function, Reader(inputs.data() + std::size_t{element} * request.input_stride));
    ASSERT_EQ(e.values.size(), request.output_stride);
    for (double v : e.values) {
      expected.push_back(v);
      bound.push_back(rounding_bound * std::max(std::fabs(v), e.scale) + 1e-30);
    }
  }
  const auto report = saagen::harness::compare_with_bounds(got, expected, bound, fmt::format("linked saa_{} ({})", c.function, c.variant));
  std::cout << "[ worst    ] " << report.summary() << "\n";
  EXPECT_EQ(report.failing, 0u) << report.summary();

  // The same function compiled from the emitted GLSL: the link changes nothing.
  const auto direct = run(saagen::test::compile_kernel(saagen::test::emit_variant("glsl", c.variant), request));
  std::size_t differing = 0;
  for (std::size_t index = 0; index < got.size(); ++index) differing += std::memcmp(&got[index], &direct[index], sizeof(float)) != 0;
  std::cout << fmt::format("[ direct   ] saa_{}: {} of {} outputs differ bitwise from the source-compiled kernel\n", c.function, differing,
                           got.size());
  EXPECT_EQ(differing, 0u);
}

std::vector<LinkCase> link_cases() {
  std::vector<LinkCase> cases;
  for (const saagen::Variant& variant : Catalogue::builtin().variants()) {
    for (const std::string& name : exported_template_names(variant)) cases.push_back({variant.id, name});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(EveryExport, LinkedLibraryOnGpu, ::testing::ValuesIn(link_cases()), [](const auto& info) {
  std::string name = info.param.variant + "_" + info.param.function;
  for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name;
});

// A library emitted in another roughness domain exports the domain's wrapper (the GLSL emission in
// that domain, compiled): linked into a consumer that imports it, it returns bitwise what the
// emitted domain source compiled directly returns (that source is proven against the reference by
// the domain suites), and `saagen validate` accepts the module.
class DomainLibraryOnGpu : public ::testing::TestWithParam<std::string> {};

TEST_P(DomainLibraryOnGpu, LinkedDomainWrapperMatchesTheEmittedDomainSourceBitwise) {
  const std::string domain = GetParam(), variant = "deferred-avg";
  saagen::EmitOptions options;
  options.variants = {variant};
  const saagen::Domain kind = saagen::find_domain(domain).kind;
  options.domain = kind;
  const auto libraries = saagen::emit_spirv_libraries(Catalogue::builtin(), options);
  ASSERT_EQ(libraries.size(), 1u);
  const saagen::SpirvLibrary& library = libraries.front();
  EXPECT_EQ(library.marker.domain, kind);
  const Catalogue& catalogue = saagen::domain_catalogue(Catalogue::builtin(), kind);
  const std::string function = saagen::domain_function_name("deferred_avg", kind);
  ASSERT_NE(std::find_if(library.exports.begin(), library.exports.end(), [&](const auto& e) { return e.template_name == function; }),
            library.exports.end());
  const std::string bytes(reinterpret_cast<const char*>(library.words.data()), library.words.size() * 4);
  EXPECT_TRUE(saagen::validate_spirv_or_pass_file(Catalogue::builtin(), library.file_name, bytes).ok());

  saagen::KernelRequest request;
  const saagen::EmissionMarker marker{
      saagen::OutputTarget::snippet("glsl"), {variant}, "saa_", {}, saagen::Precision::fp32, true, {function}, kind};
  const std::string stubs = saagen::marker_line(marker) + "\n" + saagen::glsl_import_stubs(catalogue, {function}, "saa_");
  request.body = saagen::load_call_store_body(catalogue, function, request);
  const auto compiled = saagen::compile_to_spirv(saagen::kernel_compile_request(catalogue, "consumer-stubs.glsl", stubs, request));
  ASSERT_TRUE(compiled.ok) << compiled.log;
  const auto consumer = saagen::import_stub_functions(compiled.spirv, {"saa_" + function});
  std::vector<std::uint32_t> linked;
  ASSERT_EQ(link({library.words, consumer}, linked), SPV_SUCCESS) << link_messages;
  ASSERT_EQ(saagen::validate_spirv(linked, saagen::ClientApi::vulkan), "");

  // Roughness in (0, 1) in the domain, normal derivatives of a curved surface.
  std::mt19937_64 random(0xd0a1u);
  std::uniform_real_distribution<double> roughness(0.02, 0.98), derivative(-0.3, 0.3);
  std::vector<float> inputs;
  for (std::uint32_t element = 0; element < element_count; ++element) {
    inputs.push_back(static_cast<float>(roughness(random)));
    for (int k = 0; k < 6; ++k) inputs.push_back(static_cast<float>(derivative(random)));
  }
  ASSERT_EQ(inputs.size(), std::size_t{element_count} * request.input_stride);
  const auto run = [&](const std::vector<std::uint32_t>& spirv) { return run_elements(spirv, inputs, request); };
  const auto got = run(linked);
  options.target = "glsl";
  const saagen::EmittedFile source = saagen::emit_variants(Catalogue::builtin(), options).front();
  const auto direct_compiled =
      saagen::compile_to_spirv(saagen::kernel_compile_request(catalogue, source.file_name, source.content, request));
  ASSERT_TRUE(direct_compiled.ok) << direct_compiled.log;
  const auto direct = run(direct_compiled.spirv);
  ASSERT_EQ(got.size(), direct.size());
  std::size_t differing = 0, finite = 0;
  for (std::size_t index = 0; index < got.size(); ++index) {
    differing += std::memcmp(&got[index], &direct[index], sizeof(float)) != 0;
    finite += std::isfinite(got[index]) && got[index] >= 0.0f && got[index] <= 1.0f;
  }
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(finite, got.size());  // a roughness in [0, 1] in every domain
}

INSTANTIATE_TEST_SUITE_P(EveryOtherDomain, DomainLibraryOnGpu, ::testing::Values("alpha", "perceptual", "smoothness"));

TEST(SpirvLink, TwoLibrariesLinkIntoOneConsumerAndDuplicateExportsAreRejected) {
  // One consumer importing from deferred-sum and brdf-ggx.
  const saagen::EmissionMarker marker{
      saagen::OutputTarget::snippet("glsl"), {"deferred-sum", "brdf-ggx"}, "saa_", {}, saagen::Precision::fp32, true, {}};
  const std::string stubs =
      saagen::marker_line(marker) + "\n" + saagen::glsl_import_stubs(Catalogue::builtin(), {"deferred_sum", "ggx_brdf_axis"}, "saa_");
  saagen::KernelRequest request;
  request.body =
      "    real a2 = deferred_sum(SAAGEN_LOAD(0), real3(SAAGEN_LOAD(1), 0.0, 0.0), real3(0.0, SAAGEN_LOAD(2), 0.0));\n"
      "    SAAGEN_STORE(0, ggx_brdf_axis(real3(0.0, 0.6, 0.8), real3(0.0, -0.6, 0.8), real2(a2, a2)));\n";
  request.input_stride = 3;
  request.output_stride = 1;
  const auto compiled = saagen::compile_to_spirv(saagen::kernel_compile_request(Catalogue::builtin(), "two.glsl", stubs, request));
  ASSERT_TRUE(compiled.ok) << compiled.log;
  const auto consumer = saagen::import_stub_functions(compiled.spirv, {"saa_deferred_sum", "saa_ggx_brdf_axis"});
  std::vector<std::uint32_t> linked;
  ASSERT_EQ(link({library_of("deferred-sum").words, library_of("brdf-ggx").words, consumer}, linked), SPV_SUCCESS) << link_messages;
  EXPECT_EQ(saagen::validate_spirv(linked, saagen::ClientApi::vulkan), "");

  // One workgroup of 64 invocations, each given the same three inputs.
  std::vector<float> inputs;
  for (int k = 0; k < 64; ++k) inputs.insert(inputs.end(), {0.01f, 0.3f, 0.2f});
  saagen::harness::ComputeRun run;
  run.shader.spirv = linked;
  run.buffers = {saagen::harness::input_buffer(0, inputs), saagen::harness::output_buffer<float>(1, 64)};
  run.groups = {1, 1, 1};
  const auto got = saagen::harness::run_compute(saagen::test::gpu(), run).buffer_as<float>(1);
  const double a2 = ref::deferred_sum(ref::Params{}, 0.01, {0.3, 0.0, 0.0}, {0.0, 0.2, 0.0});
  const double expected = ref::ggx_brdf_axis({0.0, 0.6, 0.8}, {0.0, -0.6, 0.8}, {a2, a2});
  EXPECT_NEAR(got[0], expected, 1e-4 * expected);

  // brdf-ggx and brdf-beckmann both export saa_ndf_clamp_tau: they link together as long as
  // nothing imports that name; an import of it is ambiguous and the linker refuses it.
  std::vector<std::uint32_t> both;
  EXPECT_EQ(link({library_of("deferred-sum").words, library_of("brdf-ggx").words, library_of("brdf-beckmann").words, consumer}, both),
            SPV_SUCCESS)
      << link_messages;
  EXPECT_EQ(saagen::validate_spirv(both, saagen::ClientApi::vulkan), "");
  saagen::KernelRequest clamp_request;
  const auto clamp_consumer = consumer_module("brdf-ggx", "ndf_clamp_tau", clamp_request);
  std::vector<std::uint32_t> rejected;
  EXPECT_NE(link({library_of("brdf-ggx").words, library_of("brdf-beckmann").words, clamp_consumer}, rejected), SPV_SUCCESS);
  EXPECT_NE(link_messages.find("saa_ndf_clamp_tau"), std::string::npos) << link_messages;
  EXPECT_EQ(link({library_of("brdf-ggx").words, clamp_consumer}, rejected), SPV_SUCCESS) << link_messages;
}

TEST(SpirvLink, ImportStubsRejectsMissingFunctions) {
  const auto& library = library_of("deferred-sum");
  EXPECT_THROW(saagen::import_stub_functions(library.words, {"saa_not_there"}), saagen::Error);
}

}  // namespace

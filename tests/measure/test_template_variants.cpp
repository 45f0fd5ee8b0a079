// The templates are the one registry of variants: the list generated from templates/*.saa at
// build time (saagen/template_variants.hpp) is the catalogue's, every variant it lists has a CPU
// reference, every SAA filter among them is a row of the measurement renderer, and the renderer
// measures no filter that no template declares.
//
// Which template variants are measured as rows of the trade: the screen-space SAA filters
// (forward-*, deferred-*: core functions and a fragment wrapper, what the planner assigns per
// material). The others are measured inside those rows, not as rows of their own:
//  - brdf-* are the lobes a filter's roughness feeds: the renderer shades every row with GGX
//    (ref::ggx_brdf_axis / _matrix and the filtered GGX of its Lobe option); brdf-beckmann's
//    reference is compared with the emitted code by the GPU suites, and no row shades with it;
//  - prefilter-* are the texture-space half of SAA: the renderer's Prefilter option on a
//    filter's row (a configuration such as deferred-avg:geometric+toksvig), so each must name one.
#include "support/core_cases.hpp"
#include "support/reference_dispatch.hpp"

#include "saagen/front/catalogue.hpp"
#include "saagen/measure/renderer.hpp"
#include "saagen/template_variants.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <string_view>

namespace measure = saagen::measure;
namespace ref = saagen::ref;
namespace templates = saagen::templates;

namespace {

// Rows of the renderer that no template declares, each for a reason: the no-SAA baseline, and
// deferred-max's tangent-free form, a function of the deferred-max variant that the trade
// measures as a row of its own. The engine-* rows are the engines' shipped forms (all_engines()),
// reference rows that saagen never emits.
constexpr std::string_view kRendererOnlyRows[] = {"none", "deferred-max-tangent-free"};

const saagen::Variant& catalogue_variant(std::string_view id) { return saagen::Catalogue::builtin().variant(id); }

bool renderer_measures(std::string_view id) {
  const std::optional<measure::Variant> variant = measure::variant_from_id(id);
  if (!variant) return false;
  const auto rows = measure::all_variants();
  return std::find(rows.begin(), rows.end(), *variant) != rows.end();
}

bool is_template_variant(std::string_view id) {
  return std::any_of(templates::kTemplateVariants.begin(), templates::kTemplateVariants.end(),
                     [&](const templates::TemplateVariant& variant) { return variant.id == id; });
}

// A 2x2 quad of unit vectors that vary across it, so that every wrapper has derivatives to read.
ref::Quad<ref::Vec3> tilted_quad(ref::Vec3 centre) {
  return {ref::normalize(centre), ref::normalize(centre + ref::Vec3{0.05, 0.0, 0.0}), ref::normalize(centre + ref::Vec3{0.0, 0.04, 0.0}),
          ref::normalize(centre + ref::Vec3{0.05, 0.04, 0.0})};
}

// Whether the shared reference dispatch of the suites that compare emitted code with the CPU
// reference (reference_dispatch.hpp, core_cases.hpp) has `function`: a fragment wrapper is
// evaluated on a quad (it throws for a name it does not know); core and evaluate functions are
// looked up in the core table.
bool has_cpu_reference(const saagen::Function& function, const std::map<std::string, saagen::test::core::ReferenceFunction>& core) {
  if (function.role != saagen::FunctionRole::fragment) return core.count(function.name) == 1;
  std::map<std::string, ref::Quad<ref::Vec3>> vectors = {
      {"half_ts", tilted_quad({0.1, 0.2, 1.0})},
      {"half_ws", tilted_quad({0.2, 0.2, 1.0})},
      {"normal_ws", tilted_quad({0.2, 0.1, 1.0})},
      {"tangent_ws", tilted_quad({1.0, 0.0, -0.2})},
      {"bitangent_ws", tilted_quad({0.0, 1.0, -0.1})},
      {"i", tilted_quad({0.3, 0.1, 1.0})},
      {"o", tilted_quad({-0.2, 0.1, 1.0})},
  };
  try {
    saagen::test::wrapper_reference_on_quad(function.name, ref::Params{}, {0.04, 0.04}, vectors, 0);
    return true;
  } catch (const std::runtime_error&) {
    return false;
  }
}

}  // namespace

TEST(TemplateVariants, GeneratedListIsTheCatalogues) {
  const std::vector<saagen::Variant>& catalogue = saagen::Catalogue::builtin().variants();
  ASSERT_EQ(templates::kTemplateVariants.size(), catalogue.size());
  for (std::size_t i = 0; i < catalogue.size(); ++i) {
    SCOPED_TRACE(catalogue[i].id);
    EXPECT_EQ(templates::kTemplateVariants[i].id, catalogue[i].id);
    EXPECT_EQ(templates::kTemplateVariants[i].path, saagen::to_string(catalogue[i].path));
    EXPECT_TRUE(catalogue[i].source_file.ends_with(templates::kTemplateVariants[i].file)) << catalogue[i].source_file;
    // The registry's filters are the catalogue's screen-space filters, which the planner assigns.
    EXPECT_EQ(templates::is_saa_filter(templates::kTemplateVariants[i]),
              saagen::is_screen_space_filter(saagen::Catalogue::builtin(), catalogue[i]));
  }
}

TEST(TemplateVariants, EveryVariantHasACpuReference) {
  const auto core = saagen::test::core::reference_functions(ref::Params{});
  for (const templates::TemplateVariant& variant : templates::kTemplateVariants) {
    for (const std::string& name : catalogue_variant(variant.id).functions) {
      const saagen::Function* function = saagen::Catalogue::builtin().find_function(name);
      ASSERT_NE(function, nullptr) << name;
      EXPECT_TRUE(has_cpu_reference(*function, core)) << variant.id << ": " << name << " has no CPU reference in tests/support";
    }
  }
}

TEST(TemplateVariants, EveryFilterIsARendererRow) {
  for (std::string_view id : templates::kSaaFilterIds) {
    EXPECT_TRUE(renderer_measures(id)) << id << " is not in measure::all_variants()";
    if (const std::optional<measure::Variant> variant = measure::variant_from_id(id)) {
      EXPECT_EQ(measure::variant_id(*variant), id);
    }
  }
}

TEST(TemplateVariants, EveryRendererRowHasATemplate) {
  for (measure::Variant variant : measure::all_variants()) {
    const std::string_view id = measure::variant_id(variant);
    if (std::find(std::begin(kRendererOnlyRows), std::end(kRendererOnlyRows), id) != std::end(kRendererOnlyRows)) continue;
    EXPECT_TRUE(std::find(templates::kSaaFilterIds.begin(), templates::kSaaFilterIds.end(), id) != templates::kSaaFilterIds.end())
        << id << " is measured but no template declares it";
  }
  for (measure::Variant engine : measure::all_engines()) {
    EXPECT_FALSE(is_template_variant(measure::variant_id(engine))) << "the engines' forms are never emitted";
    EXPECT_FALSE(renderer_measures(measure::variant_id(engine))) << "an engine is not one of saagen's variants";
  }
}

TEST(TemplateVariants, EveryPrefilterIsARendererOption) {
  const measure::Prefilter options[] = {measure::Prefilter::toksvig, measure::Prefilter::lean, measure::Prefilter::unreal,
                                        measure::Prefilter::filament_vmf, measure::Prefilter::hdrp};
  for (const templates::TemplateVariant& variant : templates::kTemplateVariants) {
    if (!variant.id.starts_with("prefilter-")) continue;
    const std::string_view name = variant.id.substr(std::string_view("prefilter-").size());
    EXPECT_TRUE(
        std::any_of(std::begin(options), std::end(options), [&](measure::Prefilter p) { return measure::prefilter_name(p) == name; }))
        << variant.id << " is not a Prefilter of the renderer";
  }
}

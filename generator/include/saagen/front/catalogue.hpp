// The variant catalogue: every variant, function and constant read from templates/*.saa.
// Parsing checks the dialect's rules and reports problems as "file:line: what; what to do".
#pragma once

#include "saagen/front/syntax_tree.hpp"
#include "saagen/precision.hpp"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace saagen {
namespace dialect {
struct Body;
}

enum class FunctionRole { core, fragment, evaluate, helper };
std::string_view to_string(FunctionRole role);

struct Parameter {
  std::string type;
  std::string name;
  std::string meaning;
};

struct Function {
  std::string name;  // unprefixed
  FunctionRole role = FunctionRole::helper;
  std::string cite;
  std::string return_type;
  std::string return_meaning;
  std::vector<Parameter> parameters;
  std::string body;  // dialect code between the braces, without them
  std::string source_file;
  int line = 0;
  int body_line = 0;  // the line of the body's first statement line
  // The body's typed syntax tree (saagen/front/syntax_tree.hpp), checked when the catalogue loads.
  std::shared_ptr<const dialect::Body> tree;
  // Template functions and constants this body references directly, with guards (the default)
  // and in the unguarded paper form (guarded(safe, paper) resolved either way).
  std::vector<std::string> calls;
  std::vector<std::string> constants;
  std::vector<std::string> paper_calls;
  std::vector<std::string> paper_constants;
  bool has_guards = false;     // the body contains guarded(...)
  bool fragment_only = false;  // takes derivatives itself or through a callee
};

// An interval of allowed values for an emission option, e.g. (0, 4].
struct Interval {
  double low = 0.0;
  double high = 0.0;
  bool low_inclusive = true;
  bool high_inclusive = true;
  bool contains(double value) const;
  std::string describe() const;
};

struct Constant {
  std::string name;  // unprefixed
  std::string type;
  std::string meaning;
  std::string option;                // non-empty for emission-time options (sigma2, kappa)
  double value = 0.0;                // the fixed value, or the option's default
  std::optional<double> half_value;  // the value in half-precision emissions, when it differs
  std::optional<Interval> range;
  std::string source_file;
  int line = 0;
};

enum class RenderPath { forward, deferred, any };
std::string_view to_string(RenderPath path);

struct Variant {
  std::string id;
  std::string summary;
  std::string paper;
  std::string equation;
  RenderPath path = RenderPath::any;
  bool needs_tangents = false;
  std::string domain;
  std::vector<std::string> functions;  // public functions, in documentation order
  // `precisions:` the precisions the variant is numerically supported in (each with a derived
  // and proven error bound); empty: every precision of the target.
  std::vector<Precision> precisions;
  std::string source_file;
  int line = 0;
};

struct TemplateSource {
  std::string name;  // e.g. templates/deferred.saa, used in diagnostics
  std::string text;
};

class Catalogue {
 public:
  // Parses and links the given template files; throws saagen::Error on the first problem.
  static Catalogue parse(const std::vector<TemplateSource>& sources);
  // The catalogue compiled into this build from templates/.
  static const Catalogue& builtin();

  const std::vector<Variant>& variants() const { return variants_; }
  const std::vector<Function>& functions() const { return functions_; }
  const std::vector<Constant>& constants() const { return constants_; }

  const Variant* find_variant(std::string_view id) const;
  // The variant `id`; throws saagen::Error "unknown variant 'ID'; run `saagen list` to see the ids".
  const Variant& variant(std::string_view id) const;
  const Function* find_function(std::string_view name) const;
  const Constant* find_constant(std::string_view name) const;
  const Constant* find_option(std::string_view option) const;

  // The functions needed to define `roots`, callees before callers, otherwise in template
  // order. Deterministic. `guarded` selects the guarded form's references or the paper form's.
  std::vector<const Function*> closure(const std::vector<std::string>& roots, bool guarded = true) const;
  // The constants referenced by `functions`, in template order.
  std::vector<const Constant*> constants_used(const std::vector<const Function*>& functions, bool guarded = true) const;

  // The template sources this catalogue was parsed from (a derived catalogue re-parses them with
  // more functions: saagen/emit/engines.hpp).
  const std::vector<TemplateSource>& sources() const { return sources_; }
  // A copy whose variants are `variants` (same functions and constants); throws saagen::Error
  // when a variant names an unknown function.
  Catalogue with_variants(std::vector<Variant> variants) const;

 private:
  void link();
  std::vector<TemplateSource> sources_;
  std::vector<Variant> variants_;
  std::vector<Function> functions_;
  std::vector<Constant> constants_;
  std::map<std::string, std::size_t, std::less<>> function_index_;
};

// The resources that the dependency closure of `roots` reads (the dialect's intrinsics marked
// `resource NAME` in templates/intrinsics.sig, e.g. glint_dictionary), sorted: what an includer
// must declare, in every target (each target table spells the declaration).
// Whether `variant` may be emitted in `precision` (its `precisions:` list, or any when it has none).
bool supports_precision(const Variant& variant, Precision precision);

// The templates compiled into this build (templates/*.saa), in file-name order: the files carry
// a numeric prefix, so that order is catalogue order.
std::vector<TemplateSource> builtin_template_sources();

// A screen-space filter the planner can assign per material: core functions and a fragment
// wrapper. The prefilter-* variants (texture-space, core only) and the BRDFs are not.
bool is_screen_space_filter(const Catalogue& catalogue, const Variant& variant);

// The type checker's view of a template function: its result and parameter types.
dialect::FunctionSignature signature_of(const Function& function);

std::vector<std::string> resources_read(const Catalogue& catalogue, const std::vector<std::string>& roots);

}  // namespace saagen

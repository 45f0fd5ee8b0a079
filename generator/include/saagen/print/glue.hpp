// Glue: the dialect statements that harness skeletons wrap around emitted functions (kernel
// bodies, validation call lists, the deferred pass's body, test shaders). Glue is parsed,
// type-checked and printed from its typed tree like a template body, for every target; the
// skeleton's own names are declared by the caller (GlueSymbols) and spelt by the target table
// (TargetSyntax::glue_names).
#pragma once

#include "saagen/front/catalogue.hpp"
#include "saagen/target/target.hpp"

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace saagen {

// The names a glue body may use besides the catalogue's functions and constants: the skeleton's
// variables and functions, with their dialect types.
struct GlueSymbols {
  std::vector<std::pair<std::string, std::string>> variables;  // name, dialect type
  // name, dialect result type ("" for none), dialect parameter types
  struct Callable {
    std::string name;
    std::string result;
    std::vector<std::string> parameters;
  };
  std::vector<Callable> functions;
};

// A glue body in the target's language: parsed, type-checked against `catalogue` and `symbols`,
// and printed from the typed tree (layout and comments kept). `names`: the catalogue's names as
// emitted; the skeleton's names as the table spells them (TargetSyntax::glue_names). Calls of
// functions that read a resource pass the skeleton's resource declarations in a language that
// passes resources (TargetSyntax::Resource::caller_arguments). `target` has its precision and
// prefix applied. Throws saagen::Error ("glue:LINE: ...") for glue that does not check.
std::string print_glue(const TargetSyntax& target, const Catalogue& catalogue, std::string_view code, const NameMap& names,
                       const GlueSymbols& symbols);

}  // namespace saagen

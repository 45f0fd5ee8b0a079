// How a target declares and passes the resources that template functions read (the target
// tables' "resources"; which resources a function reads is the dialect's: resources_read in
// saagen/front/catalogue.hpp).
#pragma once

#include "saagen/front/catalogue.hpp"
#include "saagen/target/target.hpp"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace saagen {

// The names of the target's resources (TargetSyntax::resources) that the functions `roots` read
// through their dependency closure in `catalogue`, in the table's order; empty when none.
std::vector<std::string> resources_used(const TargetSyntax& target, const Catalogue& catalogue, const std::vector<std::string>& roots);

// In a module language (TargetSyntax::module), how each function of `catalogue` that reads a
// resource, directly or through its callees, passes it: the `what` text of each resource it reads
// (Resource::parameters, ::arguments or ::caller_arguments), joined by ", ". Functions that read
// none are absent; so is everything in an include language, which names resources by macro.
std::map<std::string, std::string, std::less<>> resource_lists(const TargetSyntax& target, const Catalogue& catalogue,
                                                               std::string TargetSyntax::Resource::*what);

// The target's resource declarations (TargetSyntax::resources) that the functions `roots`
// need, through their dependency closure in `catalogue`; empty when they sample nothing.
// `target` must have its prefix applied (with_prefix).
std::string resource_declarations(const TargetSyntax& target, const Catalogue& catalogue, const std::vector<std::string>& roots);

}  // namespace saagen

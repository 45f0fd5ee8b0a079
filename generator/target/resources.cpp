// What a target declares for the resources a function reads (the tables' "resources": the glint
// dictionary's texture binding, or its parameters and arguments in a module language).
#include "saagen/target/resources.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace saagen {

std::vector<std::string> resources_used(const TargetSyntax& target, const Catalogue& catalogue, const std::vector<std::string>& roots) {
  const std::vector<std::string> read = resources_read(catalogue, roots);
  std::vector<std::string> names;
  for (const auto& [name, resource] : target.resources) {
    if (std::find(read.begin(), read.end(), name) != read.end()) names.push_back(name);
  }
  return names;
}

std::map<std::string, std::string, std::less<>> resource_lists(const TargetSyntax& target, const Catalogue& catalogue,
                                                               std::string TargetSyntax::Resource::*what) {
  std::map<std::string, std::string, std::less<>> lists;
  if (!target.module || target.resources.empty()) return lists;
  for (const Function& function : catalogue.functions()) {
    std::vector<std::string> items;
    for (const std::string& name : resources_used(target, catalogue, {function.name})) items.push_back(target.resources.at(name).*what);
    if (!items.empty()) lists[function.name] = fmt::format("{}", fmt::join(items, ", "));
  }
  return lists;
}

std::string resource_declarations(const TargetSyntax& target, const Catalogue& catalogue, const std::vector<std::string>& roots) {
  std::string declarations;
  for (const std::string& name : resources_used(target, catalogue, roots)) declarations += target.resources.find(name)->second.declaration;
  return declarations;
}

}  // namespace saagen

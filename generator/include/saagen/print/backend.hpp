// What the generator does differently per source language in C++: the printer of its function
// bodies, chosen by name by the language's table (targets/<language>/language.json, "printer";
// saagen/target/language.hpp). Everything else that differs per language is the tables' data:
// glslang's front end and its settings, or validation by Tint. A new language whose bodies the
// C-like printer spells is its tables alone; one that needs a printer of its own adds it here.
#pragma once

#include "saagen/front/syntax_tree.hpp"
#include "saagen/target/language.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace saagen {

// Prints a function body or glue from the typed tree in the target's language.
using BodyPrinter = std::string (*)(const dialect::Body& body, const TargetSyntax& target, const dialect::PrintOptions& options);

// The printer a language's table names; throws saagen::Error naming the table when there is none of that name.
BodyPrinter body_printer(const Language& language);
// The printers' names, as the language tables name them.
std::vector<std::string_view> body_printer_names();

}  // namespace saagen

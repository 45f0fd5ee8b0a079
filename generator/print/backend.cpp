#include "saagen/print/backend.hpp"

#include "saagen/error.hpp"
#include "saagen/target/target.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace saagen {
namespace {

std::string print_c_like_body(const dialect::Body& body, const TargetSyntax& target, const dialect::PrintOptions& options) {
  return dialect::print_c_like(body, target, *options.names, options.guarded);
}

struct NamedPrinter {
  std::string_view name;
  BodyPrinter print;
};
// One entry per printer: the C-like one spells GLSL, GLSL ES and HLSL from their tables.
constexpr NamedPrinter kPrinters[] = {
    {"c_like", print_c_like_body},
    {"wgsl", dialect::print_wgsl},
};

}  // namespace

BodyPrinter body_printer(const Language& language) {
  for (const NamedPrinter& printer : kPrinters) {
    if (printer.name == language.printer) return printer.print;
  }
  throw Error(fmt::format("{}: printer '{}' is not one of {}", language.table, language.printer, fmt::join(body_printer_names(), ", ")));
}

std::vector<std::string_view> body_printer_names() {
  std::vector<std::string_view> names;
  for (const NamedPrinter& printer : kPrinters) names.push_back(printer.name);
  return names;
}

}  // namespace saagen

namespace saagen::dialect {

std::string print_body(const Body& body, const TargetSyntax& target, const PrintOptions& options) {
  return body_printer(*target.language)(body, target, options);
}

}  // namespace saagen::dialect

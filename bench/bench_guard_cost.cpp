// What the guards cost. For every variant and target, a fragment kernel calls each
// public function of the variant (arguments loaded from a buffer, results stored), compiled
// in-process, optimized with spirv-opt -O (saagen::optimize_spirv) and counted
// (saagen::count_spirv_instructions), once guarded (saagen's default) and once in the unguarded
// paper form (EmitOptions::guards = false). Prints the variant totals and the per-function
// differences as Markdown (docs/STABILITY.md).
//
//   bench_guard_cost [--check]
//
// --check fails (exit 1) unless the guards cost something exactly in the functions whose
// dependency closure holds a guarded(...) site, and nothing elsewhere.
#include "saagen/emit/emitter.hpp"
#include "saagen/front/catalogue.hpp"
#include "saagen/validate/compiler.hpp"
#include "saagen/validate/kernels.hpp"

#include <fmt/format.h>

#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using saagen::Catalogue;

// A body calling `functions` with arguments loaded from distinct input floats.
std::string calls_body(const std::vector<std::string>& functions, std::uint32_t& outputs) {
  std::string body;
  std::uint32_t input = 0;
  outputs = 0;
  int index = 0;
  for (const std::string& name : functions) {
    const saagen::Function& f = *Catalogue::builtin().find_function(name);
    std::string arguments;
    for (const saagen::Parameter& p : f.parameters) {
      if (!arguments.empty()) arguments += ", ";
      if (p.name == "frag_coord") {
        arguments += "saagen_frag_coord";
        continue;
      }
      std::string loads;
      for (std::uint32_t k = 0; k < saagen::component_count(p.type); ++k) loads += fmt::format("{}SAAGEN_LOAD({})", k ? ", " : "", input++);
      const std::string variable = fmt::format("saagen_a{}_{}", index, p.name);
      body += fmt::format("    {} {} = {}({});\n", p.type, variable, p.type, loads);
      arguments += variable;
    }
    body += fmt::format("    {} saagen_r{} = {}({});\n", f.return_type, index, name, arguments);
    const std::uint32_t count = saagen::component_count(f.return_type);
    for (std::uint32_t k = 0; k < count; ++k) {
      body +=
          fmt::format("    SAAGEN_STORE({}, saagen_r{}{});\n", outputs++, index, count == 1 ? std::string() : std::string(".") + "xyzw"[k]);
    }
    ++index;
  }
  return body;
}

std::size_t optimized_instructions(const std::string& target, const std::string& variant, bool guards,
                                   const std::vector<std::string>& functions) {
  saagen::EmitOptions options;
  options.target = target;
  options.variants = {variant};
  options.guards = guards;
  const saagen::EmittedFile file = saagen::emit_variants(Catalogue::builtin(), options).front();
  saagen::KernelRequest request;
  request.kind = saagen::KernelKind::fragment;
  request.width = 64;
  request.body = calls_body(functions, request.output_stride);
  const auto compiled =
      saagen::compile_to_spirv(saagen::kernel_compile_request(Catalogue::builtin(), file.file_name, file.content, request));
  if (!compiled.ok) throw std::runtime_error(fmt::format("{} {}: kernel does not compile: {}", target, variant, compiled.log));
  const auto optimized = saagen::optimize_spirv(compiled.spirv, saagen::ClientApi::vulkan);
  if (optimized.empty()) throw std::runtime_error(fmt::format("{} {}: spirv-opt failed", target, variant));
  return saagen::count_spirv_instructions(optimized);
}

// Whether the guarded closure of `function` holds a guarded(...) site.
bool has_guard_sites(const std::string& function) {
  for (const saagen::Function* f : Catalogue::builtin().closure({function}, true)) {
    if (f->has_guards) return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  const bool check = argc > 1 && std::string(argv[1]) == "--check";
  bool ok = true;
  try {
    std::cout << "| variant | target | guarded | paper | guard cost | per public function (guarded - paper) |\n";
    std::cout << "|---|---|---:|---:|---:|---|\n";
    for (const saagen::Variant& variant : Catalogue::builtin().variants()) {
      for (const std::string target : {"glsl", "hlsl"}) {
        const std::size_t guarded = optimized_instructions(target, variant.id, true, variant.functions);
        const std::size_t paper = optimized_instructions(target, variant.id, false, variant.functions);
        std::string per_function;
        for (const std::string& name : variant.functions) {
          const long delta = static_cast<long>(optimized_instructions(target, variant.id, true, {name})) -
                             static_cast<long>(optimized_instructions(target, variant.id, false, {name}));
          per_function += fmt::format("{}{} {:+d}", per_function.empty() ? "" : ", ", name, delta);
          if (check && (delta != 0) != has_guard_sites(name)) {
            std::cerr << fmt::format("{} {}: guard cost {:+d} but the closure {} guard sites\n", target, name, delta,
                                     has_guard_sites(name) ? "has" : "has no");
            ok = false;
          }
        }
        std::cout << fmt::format("| `{}` | {} | {} | {} | {:+d} | {} |\n", variant.id, target, guarded, paper,
                                 static_cast<long>(guarded) - static_cast<long>(paper), per_function);
      }
    }
  } catch (const std::exception& error) {
    std::cerr << "bench_guard_cost: " << error.what() << "\n";
    return 1;
  }
  return ok ? 0 : 1;
}

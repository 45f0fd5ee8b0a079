#include "pass_commands.hpp"

#include "arguments.hpp"

#include "saagen/emit/engines.hpp"
#include "saagen/error.hpp"
#include "saagen/io/output.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>

namespace saagen::cli {

PassCommand::PassCommand(CLI::App& app) {
  command_ = app.add_subcommand(
      "pass", "Write the deferred roughness-limiter compute pass per deferred variant: GLSL, HLSL, SPIR-V and a C/C++ header");
  command_->add_option("--variant,-v", options_.passes,
                       "Pass id (repeatable): deferred-previous, deferred-max, deferred-max-tangent-free, deferred-sum, "
                       "deferred-avg, deferred-projected-space; all when none is named");
  preset_option_ =
      command_->add_option("--preset", preset_,
                           "An engine's shipped form: hdrp, filament, filament-taa, o3de, bevy or vsgl (pass, sigma^2 and kappa; "
                           "the roughness domain is the pass's run-time flag; explicit options win)");
  command_->add_option("--prefix", options_.prefix, "Prefix of every global name in the output")->capture_default_str();
  sigma2_option_ = command_->add_option("--sigma2", sigma2_, "Variance of the pixel filter in pixels^2, in (0, 4] (default 0.25)");
  kappa_option_ = command_->add_option("--kappa", kappa_, "Clamp of the kernel roughness in the alpha^2 domain, in [0, 1] (default 0.18)");
  command_->add_option("--derivatives", derivatives_, "What plain ddx/ddy mean in the emulated 2x2 quads: fine or coarse")
      ->capture_default_str();
  command_->add_option("--output-format", options_.output_format, "Storage image format of the output: r32f or r16f")
      ->capture_default_str();
  command_->add_flag("--unguarded", unguarded_, "Emit the papers' unguarded formulas (for comparison)");
  command_->add_option("--output,-o", directory_, "Output directory")->required();
  command_->add_flag("--force", force_, "Overwrite files that saagen did not write");
}

int PassCommand::run(const Catalogue& catalogue) const {
  check_output_named("--output", directory_);
  check_named_once("--variant", options_.passes);
  DeferredPassOptions options = options_;
  if (derivatives_ != "fine" && derivatives_ != "coarse") {
    throw Error(fmt::format("unknown derivative mode '{}'; choose fine or coarse", derivatives_));
  }
  options.derivatives = derivatives_ == "fine" ? PlainDerivative::fine : PlainDerivative::coarse;
  options.guards = !unguarded_;
  if (*preset_option_) {
    const Preset& preset = find_preset(preset_);
    if (options.passes.empty()) options.passes = {preset.variant};
    options.option_values["sigma2"] = preset.sigma2;
    options.option_values["kappa"] = preset.kappa;
  }
  if (*sigma2_option_) options.option_values["sigma2"] = parse_number("--sigma2", sigma2_);
  if (*kappa_option_) options.option_values["kappa"] = parse_number("--kappa", kappa_);

  std::vector<OutputFile> outputs;
  for (const DeferredPass& pass : emit_deferred_passes(catalogue, options)) {
    for (auto& [name, content] : pass.files()) outputs.push_back({std::filesystem::path(directory_) / name, std::move(content)});
  }
  const WriteReport report = write_outputs(outputs, force_);
  for (const auto& path : report.written) std::cout << "wrote     " << path.string() << "\n";
  for (const auto& path : report.unchanged) std::cout << "unchanged " << path.string() << "\n";
  return 0;
}

}  // namespace saagen::cli

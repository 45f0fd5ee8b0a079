// The deferred roughness-limiter pass command of the CLI: `saagen pass -o DIR` writes,
// per deferred pass, the compute shader as GLSL (.comp), HLSL (.hlsl) and SPIR-V (.spv) and a
// C/C++ header (.h) describing bindings and push constants. Kept apart from main.cpp, which
// only registers and dispatches it.
#pragma once

#include "saagen/front/catalogue.hpp"
#include "saagen/products/deferred_pass.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace saagen::cli {

class PassCommand {
 public:
  explicit PassCommand(CLI::App& app);

  bool requested() const { return command_->parsed(); }
  int run(const Catalogue& catalogue) const;

 private:
  CLI::App* command_ = nullptr;
  DeferredPassOptions options_;
  std::string directory_;
  std::string derivatives_ = "fine";
  bool unguarded_ = false;
  bool force_ = false;
  std::string sigma2_;
  std::string kappa_;
  CLI::Option* sigma2_option_ = nullptr;
  CLI::Option* kappa_option_ = nullptr;
  std::string preset_;
  CLI::Option* preset_option_ = nullptr;
};

}  // namespace saagen::cli

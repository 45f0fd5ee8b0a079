// The scene-manifest commands of the CLI: `saagen plan`, `saagen emit --manifest`
// and `saagen compile`. Kept apart from main.cpp, which only registers and dispatches them.
#pragma once

#include "saagen/front/catalogue.hpp"
#include "saagen/validate/compiler.hpp"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace saagen::cli {

class SceneCommands {
 public:
  // Adds `plan` and `compile` to the app, and --manifest, --trade-table, --list-outputs to
  // `emit`. `emit_exclusive` are emit's per-variant options that --manifest replaces.
  SceneCommands(CLI::App& app, CLI::App* emit, const std::vector<CLI::Option*>& emit_exclusive);

  bool plan_requested() const { return plan_->parsed(); }
  bool compile_requested() const { return compile_->parsed(); }
  bool emit_from_manifest() const { return !emit_manifest_.empty(); }

  int run_plan(const Catalogue& catalogue) const;
  int run_emit(const Catalogue& catalogue, const std::string& output_directory, bool force) const;
  int run_compile() const;

 private:
  // plan --gltf: writes the asset's manifest to --output (checked by parsing it first) and
  // returns its path.
  std::string write_gltf_manifest(const Catalogue& catalogue) const;
  // Stage, language, client and entry point from the options and the input's extension.
  CompileRequest compile_settings(const std::filesystem::path& input) const;

  CLI::App* plan_ = nullptr;
  std::string plan_manifest_;
  std::string plan_trade_table_;
  bool plan_no_cost_ = false;
  bool plan_rules_ = false;
  bool plan_advice_ = false;  // print saagen's table-free advice (advice_markdown)
  bool plan_json_ = false;
  bool plan_taa_ = false;
  // plan --gltf ASSET -o MANIFEST: the manifest written from a glTF asset's materials.
  std::string plan_gltf_;
  std::string plan_output_;
  std::string plan_path_ = "forward";
  std::vector<std::string> plan_targets_{"glsl"};
  bool plan_force_ = false;
  // plan --gltf ASSET --measure: measure the asset first (`saagen bench --preset medium --scene
  // ASSET`, ground truths cached in plan_cache_) and plan with that table.
  bool plan_measure_ = false;
  std::string plan_cache_;

  std::string emit_manifest_;
  std::string emit_trade_table_;
  bool emit_list_outputs_ = false;

  CLI::App* compile_ = nullptr;
  std::string compile_input_;
  std::string compile_output_;
  std::string compile_stage_;
  std::string compile_language_;
  std::string compile_client_ = "vulkan";
  std::string compile_entry_ = "main";
  std::vector<std::string> compile_include_dirs_;
  bool compile_optimize_ = false;
  bool compile_force_ = false;
};

}  // namespace saagen::cli

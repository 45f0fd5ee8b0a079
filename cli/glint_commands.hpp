// The glint commands of the CLI: `saagen glints emit|validate|dictionary|lean`. Kept
// apart from main.cpp, which only registers and dispatches them. docs/GLINTS.md.
#pragma once

#include "glint_options.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace saagen::cli {

class GlintCommands {
 public:
  explicit GlintCommands(CLI::App& app);

  bool requested() const { return glints_->parsed(); }
  int run() const;

 private:
  int run_emit() const;
  int run_validate() const;
  int run_dictionary() const;
  int run_lean() const;

  CLI::App* glints_ = nullptr;
  CLI::App* emit_ = nullptr;
  CLI::App* validate_ = nullptr;
  CLI::App* dictionary_ = nullptr;
  CLI::App* lean_ = nullptr;

  // emit
  std::string target_ = "glsl";
  std::vector<std::string> variants_;
  std::string prefix_ = "saa_";
  std::string precision_ = "fp32";
  bool unguarded_ = false;
  std::string output_directory_;
  bool force_ = false;
  // shared by emit (shader constants) and dictionary (count, lods and alpha: generation)
  GlintOptions glint_options_;
  // dictionary
  int resolution_ = 64;
  double lobe_sigma_ = 0.02;
  std::string seed_ = "2021";  // parsed strictly (parse_unsigned): CLI11 wrapped -1 and saturated 2^64
  bool no_mips_ = false;
  std::string output_file_;
  std::string raw_file_;
  // validate
  std::string validate_directory_;
  // lean
  std::string normal_map_;
};

}  // namespace saagen::cli

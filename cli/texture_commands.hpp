// `saagen texture prefilter`: normal-map prefiltering to KTX2 (saagen/products/prefilter.hpp). Kept apart
// from main.cpp, which only registers and dispatches it.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace saagen::cli {

class TextureCommands {
 public:
  explicit TextureCommands(CLI::App& app);

  bool requested() const { return texture_->parsed(); }
  int run() const;

 private:
  CLI::App* texture_ = nullptr;
  CLI::App* prefilter_ = nullptr;
  std::string input_;
  std::string output_;
  std::string method_ = "toksvig";
  std::string domain_ = "perceptual";
  double roughness_ = 0.0;
  bool float32_ = false;
  bool gltf_ = false;
  double metallic_ = 0.0;
  double scale_ = 1.0;
  bool force_ = false;
};

}  // namespace saagen::cli

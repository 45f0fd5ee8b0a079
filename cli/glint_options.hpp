// The glint catalogue's emission options on the command line (templates/glints: glint_count,
// glint_lods, glint_resolution, glint_alpha, glint_kernel_scale, glint_max_anisotropy,
// glint_relative_area, the keys a manifest takes too). `saagen glints emit` spells them --count,
// --lods, --resolution, --alpha, --kernel-scale, --max-anisotropy and --relative-area; `saagen
// emit` --glint-count and so on.
#pragma once

#include "saagen/emit/emitter.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <optional>
#include <string>

namespace saagen::cli {

struct GlintOptions {
  std::optional<int> count;
  std::optional<int> lods;
  std::optional<int> resolution;
  std::optional<double> alpha;
  std::optional<double> kernel_scale;
  std::optional<double> max_anisotropy;
  std::optional<double> relative_area;

  // The options on `app`, each named `spelling` + its name (spelling "" or "glint-").
  void add_to(CLI::App* app, const std::string& spelling) {
    app->add_option("--" + spelling + "count", count, "Distributions N in the dictionary (multiple of 4; default 192)");
    app->add_option("--" + spelling + "lods", lods, "LODs L of the dictionary (default 16)");
    app->add_option("--" + spelling + "resolution", resolution,
                    "Texels per distribution R of the dictionary (its level-0 width; default 64)");
    app->add_option("--" + spelling + "alpha", alpha, "Beckmann roughness of the dictionary (default 0.5)");
    app->add_option("--" + spelling + "kernel-scale", kernel_scale, "s_K of GGAA (default 0.5)");
    app->add_option("--" + spelling + "max-anisotropy", max_anisotropy,
                    "Largest footprint anisotropy before the minor axis is widened, in [1, 8] (default 8)");
    app->add_option("--" + spelling + "relative-area", relative_area,
                    "Microfacet relative area: probability that a cell holds microfacets, in (0, 1] (default 1)");
  }

  bool any() const { return count || lods || resolution || alpha || kernel_scale || max_anisotropy || relative_area; }

  void apply(EmitOptions& options) const {
    if (count) options.option_values["glint_count"] = *count;
    if (lods) options.option_values["glint_lods"] = *lods;
    if (resolution) options.option_values["glint_resolution"] = *resolution;
    if (alpha) options.option_values["glint_alpha"] = *alpha;
    if (kernel_scale) options.option_values["glint_kernel_scale"] = *kernel_scale;
    if (max_anisotropy) options.option_values["glint_max_anisotropy"] = *max_anisotropy;
    if (relative_area) options.option_values["glint_relative_area"] = *relative_area;
  }

  // The library names an option by its constant ("--glint_count 3 is out of range"): the message
  // with the command line's spelling of each.
  static std::string spelled(std::string message, const std::string& spelling) {
    for (const char* name : {"count", "lods", "resolution", "alpha", "kernel_scale", "max_anisotropy", "relative_area"}) {
      const std::string internal = std::string("--glint_") + name;
      std::string option = "--" + spelling + name;
      std::replace(option.begin(), option.end(), '_', '-');
      for (auto at = message.find(internal); at != std::string::npos; at = message.find(internal, at + option.size())) {
        message.replace(at, internal.size(), option);
      }
    }
    return message;
  }
};

}  // namespace saagen::cli

// Every valid combination of a scene manifest's material keys (96: path, anisotropic with
// tangents, tangents, ndf, normal_maps, precision, prefer), each as its TOML lines with the
// defaults left out (so that 10,000 materials stay under the 1 MiB manifest limit), and a
// manifest of `count` materials cycling through them. Used by the plan-scale test and benchmark.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace saagen::test {

inline std::vector<std::string> material_key_combinations() {
  std::vector<std::string> combinations;
  for (const std::string path : {"forward", "deferred"})
    for (const bool anisotropic : {false, true})
      for (const bool tangents : {false, true}) {
        if (anisotropic && !tangents) continue;
        for (const std::string ndf : {"ggx", "beckmann"})
          for (const bool normal_maps : {false, true})
            for (const std::string precision : {"fp32", "fp16"})
              for (const std::string prefer : {"accuracy", "speed"}) {
                std::string keys = "path = \"";
                keys.append(path).append("\"\n");
                if (anisotropic) keys.append("anisotropic = true\n");
                if (tangents) keys.append("tangents = true\n");
                if (ndf != "ggx") keys.append("ndf = \"").append(ndf).append("\"\n");
                if (normal_maps) keys.append("normal_maps = true\n");
                if (precision != "fp32") keys.append("precision = \"").append(precision).append("\"\n");
                if (prefer != "accuracy") keys.append("prefer = \"").append(prefer).append("\"\n");
                combinations.push_back(keys);
              }
      }
  return combinations;
}

inline std::string manifest_of_materials(std::size_t count, const std::string& name) {
  const std::vector<std::string> combinations = material_key_combinations();
  std::string text = "name = \"";
  text.append(name).append("\"\ntargets = [\"glsl\", \"hlsl\"]\n");
  for (std::size_t index = 0; index < count; ++index) {
    text.append("[[material]]\nname = \"m").append(std::to_string(index)).append("\"\n").append(combinations[index % combinations.size()]);
  }
  return text;
}

}  // namespace saagen::test

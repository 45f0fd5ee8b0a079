// What the suites that run emitted functions outside the Vulkan harness share (test_webgl:
// WebGL2 in headless Chromium; test_wgsl: WebGPU on Dawn for Node): the worst error against a
// per-output bound, the raw float files the runners write, and WGSL emission options.
#pragma once

#include "saagen/emit/emitter.hpp"
#include "saagen/emit/engines.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace saagen::test {

// The worst |got - expected| / bound over a run, and how many outputs exceed their bound.
struct Worst {
  double ratio = 0.0;
  double error = 0.0, bound = 0.0, expected = 0.0;
  float got = 0.0f;
  std::size_t failing = 0, count = 0;
  void add(float value, double reference, double limit) {
    ++count;
    const double e = std::isnan(value) ? INFINITY : std::fabs(static_cast<double>(value) - reference);
    const double r = e / limit;
    if (!(r <= 1.0)) ++failing;
    if (!(r <= ratio)) ratio = r, error = e, bound = limit, expected = reference, got = value;
  }
  std::string summary(const std::string& what) const {
    return fmt::format("{}: worst error / bound {:.3g} (error {:.3g}, bound {:.3g}, got {:.9g}, reference {:.9g}); {} of {} outside", what,
                       ratio, error, bound, got, expected, failing, count);
  }
};

// A file of raw floats (a runner's <id>.out.f32); empty when it does not exist.
inline std::vector<float> read_floats(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return {};
  std::vector<float> values(static_cast<std::size_t>(in.tellg()) / sizeof(float));
  in.seekg(0);
  in.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(float)));
  return values;
}

// WGSL emission options set field by field (designated initializers would leave members unnamed).
inline saagen::EmitOptions wgsl_options(const std::string& precision = "fp32", bool guards = true, const std::string& domain = "alpha2",
                                        std::vector<std::string> variants = {}, const std::string& import_path = "") {
  saagen::EmitOptions options;
  options.target = "wgsl";
  options.precision = saagen::parse_precision(precision);
  options.guards = guards;
  options.domain = saagen::find_domain(domain).kind;
  options.variants = std::move(variants);
  options.import_path = import_path;
  return options;
}

}  // namespace saagen::test

// What test_webgl (WebGL2 in headless Chromium) and test_wgsl (WebGPU on Dawn for Node) share
// around their one runner process: the batch of cases' runner entries with their inputs, the core
// functions' inputs subsampled from test_gpu_core's, and the core functions' outputs measured
// against the double reference.
#pragma once

#include "core_cases.hpp"
#include "web_support.hpp"

#include "saagen/front/catalogue.hpp"
#include "saagen/validate/kernels.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace saagen::test {

// Appends to `entries` the runner entry of each case, entry_of(case, inputs), which writes the
// case's files and fills `inputs` with what the case reads; keeps those inputs by case id.
template <class Cases, class EntryOf>
void add_runner_entries(const Cases& cases, EntryOf entry_of, nlohmann::json& entries,
                        std::map<std::string, std::vector<float>>& inputs_by_id) {
  for (const auto& c : cases) {
    std::vector<float> inputs;
    entries.push_back(entry_of(c, inputs));
    if (!inputs.empty()) inputs_by_id[c.id] = std::move(inputs);
  }
}

// `function`'s packed inputs on `elements` of test_gpu_core's inputs (core_cases.hpp): one of each
// run of element_count / elements, at a rotating offset, so that every residue mod 8 appears (the
// texel statistics of core_cases.hpp depend on index % 8).
inline std::vector<float> subsampled_core_inputs(const saagen::Function& function, std::uint32_t elements) {
  static const std::vector<core::Scenario> scenarios = core::scenarios();
  const std::uint32_t subsample = core::element_count / elements;
  const ref::Params params;
  std::vector<float> inputs;
  for (std::uint32_t element = 0; element < elements; ++element) {
    const std::uint64_t index = std::uint64_t{element} * subsample + element % subsample;
    core::pack_inputs(function, scenarios[index], index, params, inputs);
  }
  return inputs;
}

// The worst error of core function `function` of the built-in catalogue on `elements` of its packed
// `inputs` against the double reference: element e's output k at out[e * output_stride + k], each
// within bound(the output's magnitude scale, core_cases.hpp).
template <class Bound>
Worst core_worst(const std::string& function, const ref::Params& params, std::uint32_t elements, const std::vector<float>& inputs,
                 const std::vector<float>& out, std::size_t output_stride, Bound bound) {
  saagen::KernelRequest request;
  (void)saagen::load_call_store_body(saagen::Catalogue::builtin(), function, request);
  const core::ReferenceFunction reference = core::reference_functions(params).at(function);
  Worst worst;
  for (std::uint32_t element = 0; element < elements; ++element) {
    core::Inputs value_inputs(inputs.data() + std::size_t{element} * request.input_stride);
    core::Inputs scale_inputs(inputs.data() + std::size_t{element} * request.input_stride);
    const auto values = reference.value(value_inputs);
    const auto scales = reference.scale(scale_inputs);
    for (std::size_t k = 0; k < values.size(); ++k) {
      const double scale = std::max(std::fabs(values[k]), scales[std::min(k, scales.size() - 1)]);
      worst.add(out[std::size_t{element} * output_stride + k], values[k], bound(scale));
    }
  }
  return worst;
}

}  // namespace saagen::test

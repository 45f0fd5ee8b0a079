// Executes the descriptions of description.hpp. A Program builds its resources and pipeline
// once and can then run many times (repetitions for timing, new buffer contents for sweeps);
// run_compute / run_fragment are the one-shot forms.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <saagen/harness/context.hpp>
#include <saagen/harness/description.hpp>
#include <saagen/harness/formats.hpp>  // format_info, for the callers of program.hpp
#include <span>
#include <vector>

namespace saagen::harness {

struct RunOptions {
  // The recorded work is submitted this many times; each submission is waited on and timed.
  // Outputs are read back after the last one.
  std::uint32_t repetitions = 1;
  // Record GPU timestamps around the dispatch/draw when the queue supports them.
  bool gpu_timestamps = true;
};

struct Timing {
  double pipeline_create_ms = 0.0;  // shader modules + pipeline creation (once per program)
  std::vector<double> host_ms;      // wall clock around vkQueueSubmit + fence wait, per repetition
  std::vector<double> gpu_ms;       // timestamp difference per repetition; empty when unavailable

  static double min(const std::vector<double>& samples);     // NaN when empty
  static double median(const std::vector<double>& samples);  // NaN when empty
};

// A color attachment read back as floats: `components` values per texel, rows top to bottom
// (row 0 is gl_FragCoord.y = 0.5).
struct Attachment {
  VkFormat format = VK_FORMAT_UNDEFINED;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t components = 0;
  std::vector<float> values;

  float at(std::uint32_t x, std::uint32_t y, std::uint32_t component) const {
    return values[(static_cast<std::size_t>(y) * width + x) * components + component];
  }
};

struct RunResult {
  std::map<std::uint32_t, Bytes> buffers;  // binding -> final contents (read_back buffers only)
  std::vector<Attachment> attachments;     // fragment runs: one per color format, in order
  Timing timing;

  // The buffer at `binding` as an array of T; throws if it was not read back.
  template <typename T>
  std::vector<T> buffer_as(std::uint32_t binding) const {
    return from_bytes<T>(buffer(binding));
  }
  const Bytes& buffer(std::uint32_t binding) const;
};

class ComputeProgram {
 public:
  ComputeProgram(VulkanContext& context, const ComputeRun& run);
  ~ComputeProgram();
  ComputeProgram(const ComputeProgram&) = delete;
  ComputeProgram& operator=(const ComputeProgram&) = delete;

  // Overwrites the start of the buffer at `binding` (must fit); the rest keeps its contents.
  void write_buffer(std::uint32_t binding, std::span<const std::byte> bytes);
  void set_push_constants(Bytes bytes);  // same size as the description's push constants
  void set_groups(DispatchSize groups);
  RunResult run(const RunOptions& options = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class FragmentProgram {
 public:
  FragmentProgram(VulkanContext& context, const FragmentRun& run);
  ~FragmentProgram();
  FragmentProgram(const FragmentProgram&) = delete;
  FragmentProgram& operator=(const FragmentProgram&) = delete;

  void write_buffer(std::uint32_t binding, std::span<const std::byte> bytes);
  void set_push_constants(Bytes bytes);
  RunResult run(const RunOptions& options = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

RunResult run_compute(VulkanContext& context, const ComputeRun& run, const RunOptions& options = {});
RunResult run_fragment(VulkanContext& context, const FragmentRun& run, const RunOptions& options = {});

}  // namespace saagen::harness

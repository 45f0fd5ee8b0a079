// Prints the Vulkan device the harness selects (or all devices with --list).
// Usage: saagen_harness_info [--device NAME] [--list]
#include <fmt/format.h>

#include <cstring>
#include <exception>
#include <saagen/harness/context.hpp>
#include <saagen/harness/error.hpp>

int main(int argc, char** argv) {
  using namespace saagen::harness;
  try {
    const std::string device = take_device_flag(argc, argv);
    if (argc > 1 && std::strcmp(argv[1], "--list") == 0) {
      for (const std::string& name : VulkanContext::available_devices()) fmt::print("{}\n", name);
      return 0;
    }
    VulkanContext context(ContextOptions{device});
    fmt::print("{}\n", context.info().summary());
    return 0;
  } catch (const NullHardwareDevice& null_device) {
    // RADV_FORCE_FAMILY: a compiler without a GPU. Described, never opened as a device.
    fmt::print(
        "{}\nnull hardware (RADV_FORCE_FAMILY): compiles only, never used for a dispatch; its ISA statistics: "
        "`saagen bench --isa FAMILY --isa-only`\n",
        null_device.summary());
    return 0;
  } catch (const std::exception& error) {
    fmt::print(stderr, "saagen_harness_info: {}\n", error.what());
    return 1;
  }
}

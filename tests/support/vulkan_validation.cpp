// Linked into every vulkan-labelled test binary (tests/CMakeLists.txt): with the Khronos
// validation layer on (SAAGEN_VK_VALIDATION=1, set by ctest for every device), the run fails when
// the layer reported any warning or error. Each message is also printed as one
// "[validation] ..." line, which ctest's FAIL_REGULAR_EXPRESSION catches as well.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <saagen/harness/compare.hpp>
#include <saagen/harness/context.hpp>

namespace {

class ValidationEnvironment : public ::testing::Environment {
 public:
  void TearDown() override {
    const std::size_t count = saagen::harness::validation_message_count();
    if (saagen::harness::validation_requested()) {
      std::cout << "[validation] layer " << saagen::harness::validation_layer_name << " on: " << count << " messages\n";
    }
    // One line per run for scripts/gpu_table.sh: the worst error as a fraction of its bound.
    std::error_code error;
    const std::string suite = std::filesystem::read_symlink("/proc/self/exe", error).filename().string();
    std::cout << "[ bound    ] " << suite << ": " << saagen::harness::compare_totals().summary() << "\n";
    EXPECT_EQ(count, 0u) << "the Vulkan validation layer reported " << count << " warnings/errors (see the [validation] lines)";
  }
};

const bool registered = [] {
  ::testing::AddGlobalTestEnvironment(new ValidationEnvironment);
  return true;
}();

}  // namespace

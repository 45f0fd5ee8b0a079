// libFuzzer target: the KTX2 reader (read_ktx2). Accepted files must write back (write_ktx2) and
// read again to the same image; rejected ones must fail with one "KTX2: ..." line.
#include "fuzz_support.hpp"

#include "saagen/error.hpp"
#include "saagen/products/glints.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using saagen::fuzz::finding;
  constexpr const char* target = "ktx2_fuzzer";
  saagen::Ktx2Image image;
  try {
    image = saagen::read_ktx2(std::span<const std::uint8_t>(data, size));
  } catch (const saagen::Error& error) {
    saagen::fuzz::check_message(target, error.what(), "KTX2: ");
    return 0;
  }
  try {
    const auto again = saagen::read_ktx2(saagen::write_ktx2(image));
    if (again.levels != image.levels || again.width != image.width || again.height != image.height || again.layers != image.layers ||
        again.vk_format != image.vk_format) {
      finding(target, "the image does not read back after write_ktx2", "levels or header differ");
    }
  } catch (const saagen::Error& error) {
    finding(target, "an accepted image does not write back", error.what());
  }
  return 0;
}

// libFuzzer target: the binary PPM reader (slopes_from_ppm) and the LEAN moment chain built from
// what it accepts (lean_moments, lean_ktx2, write_ktx2, read back). Rejected input must fail with
// one "normal map: ..." line; accepted input must give a full MIP chain down to 1x1.
#include "fuzz_support.hpp"

#include "saagen/error.hpp"
#include "saagen/products/glints.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using saagen::fuzz::finding;
  constexpr const char* target = "ppm_lean_fuzzer";
  saagen::glints::SlopeMap map;
  try {
    map = saagen::glints::slopes_from_ppm(std::span<const std::uint8_t>(data, size));
  } catch (const saagen::Error& error) {
    saagen::fuzz::check_message(target, error.what(), "normal map: ");
    return 0;
  }
  if (map.width <= 0 || map.height <= 0 || map.slopes.size() != static_cast<std::size_t>(map.width) * map.height * 2) {
    finding(target, "accepted map has inconsistent size", "width x height x 2 != slopes");
  }
  try {
    const auto levels = saagen::glints::lean_moments(map);
    if (levels.back().width != 1 || levels.back().height != 1) finding(target, "MIP chain does not end at 1x1", "lean_moments");
    const auto image = saagen::read_ktx2(saagen::write_ktx2(saagen::glints::lean_ktx2(levels)));
    if (image.levels.size() != levels.size()) finding(target, "LEAN KTX2 does not read back", "level count differs");
  } catch (const saagen::Error& error) {
    finding(target, "an accepted normal map fails later", error.what());
  }
  return 0;
}

// Byte-vector helpers for building test descriptions (buffer contents, push constants, texel
// data) and reading results, plus IEEE binary16 conversion for fp16 formats.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace saagen::harness {

using Bytes = std::vector<std::byte>;

template <typename T>
Bytes to_bytes(std::span<const T> values) {
  static_assert(std::is_trivially_copyable_v<T>);
  Bytes bytes(values.size_bytes());
  if (!bytes.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

template <typename T>
Bytes to_bytes(const std::vector<T>& values) {
  return to_bytes(std::span<const T>(values));
}

// One trivially copyable value, e.g. a push-constant struct.
template <typename T>
requires std::is_trivially_copyable_v<T> Bytes value_bytes(const T& value) {
  Bytes bytes(sizeof(T));
  std::memcpy(bytes.data(), &value, sizeof(T));
  return bytes;
}

// Reinterprets bytes as an array of T; the byte count must be a multiple of sizeof(T).
template <typename T>
std::vector<T> from_bytes(std::span<const std::byte> bytes) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (bytes.size() % sizeof(T) != 0) throw std::invalid_argument("from_bytes: size is not a multiple of the element size");
  std::vector<T> values(bytes.size() / sizeof(T));
  if (!values.empty()) std::memcpy(values.data(), bytes.data(), bytes.size());
  return values;
}

// IEEE 754 binary16 <-> binary32. float_to_half rounds to nearest even and keeps NaN, Inf and
// subnormals; half_to_float is exact.
std::uint16_t float_to_half(float value);
float half_to_float(std::uint16_t bits);

}  // namespace saagen::harness

// Element-wise comparison of shader outputs against a double-precision reference, with a
// one-line report that names the worst element.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <string>

namespace saagen::harness {

// An element passes when |got - expected| <= abs_tol + rel_tol * |expected|. Non-finite values:
// NaN passes only against NaN, an infinity only against the same infinity.
struct Tolerance {
  double abs_tol = 0.0;
  double rel_tol = 0.0;
};

struct CompareReport {
  std::size_t compared = 0;
  std::size_t failing = 0;
  // The element with the largest normalised error |got - expected| / (abs_tol + rel_tol*|expected|)
  // (infinite for a non-finite mismatch or any mismatch under a zero tolerance). Only
  // meaningful when compared > 0.
  std::size_t worst_index = 0;
  double worst_got = 0.0;
  double worst_expected = 0.0;
  double worst_normalised_error = 0.0;
  std::string worst_label;  // from the describe callback, if any
  Tolerance tolerance;
  bool per_element_bounds = false;  // compared against a bound per element instead of `tolerance`
  double max_relative_error = 0.0;  // max |got - expected| / |expected| over finite |expected| > 1e-30
  std::string what;                 // caption given by the caller

  bool ok() const { return failing == 0; }
  // e.g. "sqrt: 0 of 100000 failing (tol abs 0 + rel 0); worst #17 x=2: got 1.41421354,
  //       expected 1.41421354, err 0 x tol"
  std::string summary() const;
};

// All comparisons made in this process so far (except those captioned as a device-specific
// model): the largest normalised error, i.e. the worst error as a fraction of its bound.
struct CompareTotals {
  std::size_t reports = 0;
  std::size_t elements = 0;
  std::size_t failing = 0;
  double worst = 0.0;
  std::string worst_what;
  std::string summary() const;
};
const CompareTotals& compare_totals();

// Called for the worst element only, to label it (e.g. with its inputs).
using DescribeElement = std::function<std::string(std::size_t index)>;

// got and expected must have the same length (std::invalid_argument otherwise).
CompareReport compare(std::span<const float> got, std::span<const double> expected, Tolerance tolerance, const std::string& what = {},
                      const DescribeElement& describe = {});
CompareReport compare(std::span<const double> got, std::span<const double> expected, Tolerance tolerance, const std::string& what = {},
                      const DescribeElement& describe = {});
// Element i passes when |got - expected| <= bounds[i] (an error bound derived per element, e.g.
// from a condition number); non-finite values as above.
CompareReport compare_with_bounds(std::span<const float> got, std::span<const double> expected, std::span<const double> bounds,
                                  const std::string& what = {}, const DescribeElement& describe = {});
// Device against device (e.g. two shader variants), or against an fp32 CPU model.
CompareReport compare(std::span<const float> got, std::span<const float> expected, Tolerance tolerance, const std::string& what = {},
                      const DescribeElement& describe = {});

}  // namespace saagen::harness

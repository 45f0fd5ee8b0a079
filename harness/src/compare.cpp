#include "saagen/harness/compare.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace saagen::harness {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// |got - expected| in units of the allowed error; 0 for an exact match, infinity for a
// non-finite mismatch or any mismatch under a zero tolerance. Fails when > 1.
double normalised_error(double got, double expected, Tolerance tolerance) {
  if (std::isnan(expected) || std::isnan(got)) return std::isnan(expected) && std::isnan(got) ? 0.0 : infinity;
  if (std::isinf(expected) || std::isinf(got)) return got == expected ? 0.0 : infinity;
  const double difference = std::fabs(got - expected);
  if (difference == 0.0) return 0.0;
  const double allowed = tolerance.abs_tol + tolerance.rel_tol * std::fabs(expected);
  return allowed > 0.0 ? difference / allowed : infinity;
}

CompareTotals& totals() {
  static CompareTotals all;
  return all;
}

// Every comparison of the process, for the per-suite "worst error / bound" line. The tighter,
// device-specific checks (lavapipe's LOD model) say so in their caption and are left out: the
// figure is against bounds that hold on any conforming implementation.
void record(const CompareReport& report) {
  if (report.what.find("lavapipe LOD model") != std::string::npos || report.compared == 0) return;
  CompareTotals& t = totals();
  ++t.reports;
  t.elements += report.compared;
  t.failing += report.failing;
  if (report.worst_normalised_error > t.worst || t.reports == 1) {
    t.worst = report.worst_normalised_error;
    t.worst_what = report.what;
  }
}

template <typename Got, typename Expected, typename ToleranceAt>
CompareReport compare_impl(std::span<const Got> got, std::span<const Expected> expected, ToleranceAt tolerance_at, const std::string& what,
                           const DescribeElement& describe) {
  if (got.size() != expected.size()) {
    throw std::invalid_argument(
        fmt::format("compare{}: {} values but {} expected values", what.empty() ? "" : " (" + what + ")", got.size(), expected.size()));
  }
  CompareReport report;
  report.what = what;
  report.compared = got.size();
  double worst = -1.0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    const double value = static_cast<double>(got[i]), reference = static_cast<double>(expected[i]);
    const double error = normalised_error(value, reference, tolerance_at(i));
    if (error > 1.0) ++report.failing;
    if (std::isfinite(value) && std::isfinite(reference) && std::fabs(reference) > 1e-30) {
      report.max_relative_error = std::max(report.max_relative_error, std::fabs(value - reference) / std::fabs(reference));
    }
    if (error > worst) {
      worst = error;
      report.worst_index = i;
    }
  }
  if (report.compared > 0) {
    report.worst_got = static_cast<double>(got[report.worst_index]);
    report.worst_expected = static_cast<double>(expected[report.worst_index]);
    report.worst_normalised_error = worst;
    if (describe) report.worst_label = describe(report.worst_index);
  }
  record(report);
  return report;
}

}  // namespace

const CompareTotals& compare_totals() { return totals(); }

std::string CompareTotals::summary() const {
  if (reports == 0) return "no bounded comparisons";
  return fmt::format("{} comparisons, {} elements, {} failing; worst |got - expected| / bound = {:.3g} ({})", reports, elements, failing,
                     worst, worst_what);
}

std::string CompareReport::summary() const {
  const std::string bounds =
      per_element_bounds ? std::string("per-element bounds") : fmt::format("tol abs {:g} + rel {:g}", tolerance.abs_tol, tolerance.rel_tol);
  std::string line = fmt::format("{}{} of {} failing ({})", what.empty() ? "" : what + ": ", failing, compared, bounds);
  if (compared == 0) return line;
  return line + fmt::format("; worst #{}{}: got {:.9g}, expected {:.17g}, err {:.3g} x tol; max relative error {:.3g}", worst_index,
                            worst_label.empty() ? "" : " " + worst_label, worst_got, worst_expected, worst_normalised_error,
                            max_relative_error);
}

namespace {
template <typename Got, typename Expected>
CompareReport compare_with_tolerance(std::span<const Got> got, std::span<const Expected> expected, Tolerance tolerance,
                                     const std::string& what, const DescribeElement& describe) {
  CompareReport report = compare_impl(
      got, expected, [tolerance](std::size_t) { return tolerance; }, what, describe);
  report.tolerance = tolerance;
  return report;
}
}  // namespace

CompareReport compare(std::span<const float> got, std::span<const double> expected, Tolerance tolerance, const std::string& what,
                      const DescribeElement& describe) {
  return compare_with_tolerance(got, expected, tolerance, what, describe);
}

CompareReport compare(std::span<const double> got, std::span<const double> expected, Tolerance tolerance, const std::string& what,
                      const DescribeElement& describe) {
  return compare_with_tolerance(got, expected, tolerance, what, describe);
}

CompareReport compare(std::span<const float> got, std::span<const float> expected, Tolerance tolerance, const std::string& what,
                      const DescribeElement& describe) {
  return compare_with_tolerance(got, expected, tolerance, what, describe);
}

CompareReport compare_with_bounds(std::span<const float> got, std::span<const double> expected, std::span<const double> bounds,
                                  const std::string& what, const DescribeElement& describe) {
  if (bounds.size() != expected.size()) {
    throw std::invalid_argument(fmt::format("compare ({}): {} bounds for {} values", what, bounds.size(), expected.size()));
  }
  CompareReport report = compare_impl(
      got, expected,
      [bounds](std::size_t i) {
        return Tolerance{bounds[i], 0.0};
      },
      what, describe);
  report.per_element_bounds = true;
  return report;
}

}  // namespace saagen::harness

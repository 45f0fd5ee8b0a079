#include "saagen/decision.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <string>

namespace saagen::decision {
namespace {

bool better(const Difference& d) { return d.high < 0.0; }
bool worse(const Difference& d) { return d.low > 0.0; }

// Whether a is more accurate than b: the temporal mean (the video metric, which judges the
// animation as a viewer sees it), then the image mean.
bool more_accurate(const Candidate& a, const Candidate& b) {
  if (a.against_none.temporal.mean != b.against_none.temporal.mean) return a.against_none.temporal.mean < b.against_none.temporal.mean;
  return a.against_none.image.mean < b.against_none.image.mean;
}

bool within_budget(const Candidate& c, const Preference& p) { return !p.budget || (c.cost_ratio && *c.cost_ratio <= *p.budget); }

// "1 usable configuration", "3 usable configurations".
std::string usable_count(std::size_t n) { return fmt::format("{} usable configuration{}", n, n == 1 ? "" : "s"); }

// "; 1.17x no SAA's shading cost at 1 light" (`digits` significant digits), or nothing where the
// candidate carries no cost (a choice by accuracy alone, as among one variant's feeds and bakes).
std::string cost_text(const Candidate& c, std::string_view basis, int digits) {
  if (!c.cost_ratio) return "";
  return fmt::format("; {:.{}g}x no SAA's shading cost{}{}", *c.cost_ratio, digits, basis.empty() ? "" : " ", basis);
}

std::string figures(const Candidate& c, std::string_view basis, std::string_view baseline, int cost_digits = 3) {
  return fmt::format("{} (image {}, temporal {} against {}{})", c.configuration, describe(c.against_none.image),
                     describe(c.against_none.temporal), baseline, cost_text(c, basis, cost_digits));
}

// The value a cost reads as when printed with `digits` significant digits (fmt and from_chars
// both ignore the locale, so "1.33" reads as 1.33 wherever the plan runs).
double as_printed(double value, int digits) {
  const std::string text = fmt::format("{:.{}g}", value, digits);
  double read = value;
  std::from_chars(text.data(), text.data() + text.size(), read);
  return read;
}

// A cost over a budget, which is printed as given: with as many significant digits as it takes
// to read above it (1.333x against the budget 1.33, not 1.33x), up to 6.
int digits_against_budget(std::span<const Candidate> candidates, const std::vector<std::size_t>& listed, double budget) {
  int digits = 3;
  for (std::size_t i : listed)
    while (candidates[i].cost_ratio && *candidates[i].cost_ratio > budget && digits < 6 &&
           as_printed(*candidates[i].cost_ratio, digits) <= budget)
      ++digits;
  return digits;
}

// The largest known cost among the usable candidates, and how many candidates are usable.
std::pair<std::optional<double>, std::size_t> usable_cost_range(std::span<const Candidate> candidates) {
  std::optional<double> most;
  std::size_t usable = 0;
  for (const Candidate& c : candidates) {
    if (!c.usable) continue;
    ++usable;
    if (c.cost_ratio && (!most || *c.cost_ratio > *most)) most = c.cost_ratio;
  }
  return {most, usable};
}

bool is_most_expensive(const Candidate& c, std::optional<double> most) {
  return most && c.cost_ratio && *c.cost_ratio * (1.0 + kCostTieTolerance) >= *most;
}

std::optional<std::size_t> most_accurate(std::span<const Candidate> candidates, const std::vector<std::size_t>& pool) {
  std::optional<std::size_t> best;
  for (std::size_t i : pool)
    if (!best || more_accurate(candidates[i], candidates[*best])) best = i;
  return best;
}

// Whether `c` ties with `best`: their paired comparison is worse beyond the interval in neither metric.
bool ties_with(const Candidate& c, const Candidate& best) {
  return std::find(c.not_worse_than.begin(), c.not_worse_than.end(), best.configuration) != c.not_worse_than.end();
}

// The lowest-cost candidates of the pool: those with a known cost within kCostTieTolerance of the lowest.
std::vector<std::size_t> lowest_cost(std::span<const Candidate> candidates, const std::vector<std::size_t>& pool) {
  std::optional<double> lowest;
  for (std::size_t i : pool)
    if (candidates[i].cost_ratio && (!lowest || *candidates[i].cost_ratio < *lowest)) lowest = candidates[i].cost_ratio;
  std::vector<std::size_t> equal;
  for (std::size_t i : pool)
    if (candidates[i].cost_ratio && *candidates[i].cost_ratio <= *lowest * (1.0 + kCostTieTolerance)) equal.push_back(i);
  return equal;
}

// Whether `a` beats `b` in their paired comparison: worse beyond the interval in neither metric,
// while `b` is worse than `a` beyond it in one (the pairing of b with a is not a tie).
bool dominates(const Candidate& a, const Candidate& b) { return ties_with(a, b) && !ties_with(b, a); }

// The members of a tie group that no other member beats in their paired comparison; all of them
// where the pairings go round in a circle.
std::vector<std::size_t> undominated(std::span<const Candidate> candidates, const std::vector<std::size_t>& group) {
  std::vector<std::size_t> kept;
  for (std::size_t i : group)
    if (std::none_of(group.begin(), group.end(), [&](std::size_t j) { return dominates(candidates[j], candidates[i]); })) kept.push_back(i);
  return kept.empty() ? group : kept;
}

// The most accurate candidate of the pool by the mean and the candidates that tie with it (worse
// than it beyond the interval in neither metric): as accurate as it.
std::vector<std::size_t> tie_group(std::span<const Candidate> candidates, const std::vector<std::size_t>& pool, std::size_t best) {
  std::vector<std::size_t> tied{best};
  for (std::size_t i : pool)
    if (i != best && ties_with(candidates[i], candidates[best])) tied.push_back(i);
  return tied;
}

// For accuracy: the most accurate of the pool by the mean and its ties, less any that another of
// them beats in their paired comparison, and of the rest the cheapest (equal costs: the more
// accurate by the mean). Where the most accurate one's cost is unknown, nothing is known to be
// cheaper: the best of the group by the pairing.
std::optional<std::size_t> most_accurate_for_its_cost(std::span<const Candidate> candidates, const std::vector<std::size_t>& pool) {
  const std::optional<std::size_t> best = most_accurate(candidates, pool);
  if (!best) return best;
  const std::vector<std::size_t> kept = undominated(candidates, tie_group(candidates, pool, *best));
  if (!candidates[*best].cost_ratio) return most_accurate(candidates, kept);
  const std::vector<std::size_t> priced = lowest_cost(candidates, kept);
  return most_accurate(candidates, priced.empty() ? kept : priced);
}

// The cheapest of the pool, skipping the most expensive usable form unless it is the only usable
// candidate; of equal costs, the one accuracy takes among them (a tie another of them beats in
// the pairing is set aside, as for accuracy).
std::optional<std::size_t> cheapest(std::span<const Candidate> candidates, const std::vector<std::size_t>& pool) {
  const auto [most, usable] = usable_cost_range(candidates);
  std::vector<std::size_t> affordable;
  for (std::size_t i : pool)
    if (candidates[i].cost_ratio && (usable == 1 || !is_most_expensive(candidates[i], most))) affordable.push_back(i);
  if (affordable.empty()) return std::nullopt;
  return most_accurate_for_its_cost(candidates, lowest_cost(candidates, affordable));
}

// Where accuracy took another candidate than the one with the largest temporal improvement on the
// mean: "; it beats X, ... in their paired comparison" when the chosen one does, else "; it ties
// with X, ..., at lower cost".
std::string tie_text(const Candidate& chosen, const Candidate& best, std::string_view basis, std::string_view baseline) {
  if (dominates(chosen, best))
    return fmt::format(
        "; paired with {}, the largest temporal improvement on the mean, it is better beyond the 95 % interval in one metric and "
        "worse in neither",
        figures(best, basis, baseline));
  return fmt::format(
      "; it ties with {}, the largest temporal improvement on the mean (paired with it, worse beyond the 95 % interval in neither "
      "metric), at lower cost",
      figures(best, basis, baseline));
}

// "; set aside: X, which beats no SAA on the mean but loses on S": the more accurate candidates
// (by the mean) that the decision did not take because they lose on one of the pooled scenes.
std::string set_aside(std::span<const Candidate> candidates, const std::vector<std::size_t>& beating, const Candidate& chosen,
                      std::string_view baseline) {
  std::vector<std::string> listed;
  for (std::size_t i : beating)
    if (!candidates[i].loses_on.empty() && !late(candidates[i].against_none) && more_accurate(candidates[i], chosen))
      listed.push_back(fmt::format("{} (loses on {})", candidates[i].configuration, fmt::join(candidates[i].loses_on, ", ")));
  if (listed.empty()) return "";
  return fmt::format("; set aside, more accurate on the mean but losing to {} on a scene of the content: {}", baseline,
                     fmt::join(listed, ", "));
}

std::string no_filter_reason(std::span<const Candidate> candidates, const std::vector<Outcome>& outcomes,
                             const std::vector<std::size_t>& beating, const Preference& preference, std::string_view basis) {
  std::size_t usable = 0;
  std::vector<std::size_t> tried;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (candidates[i].usable) ++usable, tried.push_back(i);
  const std::string_view baseline = preference.baseline;
  if (candidates.empty()) return fmt::format("no filter: no configuration was measured against {} here", baseline);
  if (usable == 0) return fmt::format("no filter: none of the {} measured configurations can be used here", candidates.size());
  // What beats the baseline: on time (not late), and of those, what loses on none of the pooled scenes.
  std::vector<std::size_t> on_time, holding;
  for (std::size_t i : beating)
    if (!late(candidates[i].against_none)) on_time.push_back(i);
  for (std::size_t i : on_time)
    if (candidates[i].loses_on.empty()) holding.push_back(i);
  if (!on_time.empty() && holding.empty()) {
    std::vector<std::string> listed;
    for (std::size_t i : on_time)
      listed.push_back(fmt::format("{} loses on {}", candidates[i].configuration, fmt::join(candidates[i].loses_on, ", ")));
    return fmt::format("no filter: what beats {} on the mean loses to it beyond the interval on a scene of the same content ({})", baseline,
                       fmt::join(listed, "; "));
  }
  if (!beating.empty() && on_time.empty()) {
    std::vector<std::string> listed;
    for (std::size_t i : beating)
      listed.push_back(fmt::format("{} (lag {})", figures(candidates[i], basis, baseline), describe(candidates[i].against_none.lag)));
    return fmt::format(
        "no filter: what beats {} is late (its frames are closer to the ground truth's previous frames than to their own): {}", baseline,
        fmt::join(listed, ", "));
  }
  if (beating.empty()) {
    const std::size_t best = *most_accurate(candidates, tried);
    return fmt::format("no filter: none of the {} beats {}; the lowest temporal error, {}, {}", usable_count(usable), baseline,
                       figures(candidates[best], basis, baseline), name(outcomes[best]));
  }
  std::vector<std::string> listed;
  const int cost_digits = preference.budget ? digits_against_budget(candidates, holding, *preference.budget) : 3;
  for (std::size_t i : holding) listed.push_back(figures(candidates[i], basis, baseline, cost_digits));
  if (preference.budget) {
    bool any_in_budget = false;
    for (std::size_t i : holding) any_in_budget = any_in_budget || within_budget(candidates[i], preference);
    if (!any_in_budget)
      return fmt::format("no filter: what beats {} costs more than the budget {}: {}", baseline, *preference.budget,
                         fmt::join(listed, ", "));
  }
  return fmt::format(
      "no filter: what beats {} is the most expensive form here (prefer = \"speed\" never takes it; prefer = \"accuracy\" "
      "does): {}",
      baseline, fmt::join(listed, ", "));
}

}  // namespace

std::string_view name(Outcome outcome) {
  switch (outcome) {
    case Outcome::beats:
      return "beats";
    case Outcome::ties:
      return "ties";
    case Outcome::loses:
      return "loses";
    case Outcome::mixed:
      return "mixed";
  }
  return "?";
}

Outcome outcome(const Comparison& c) {
  if (c.unconverged) return Outcome::ties;
  const int better_count = better(c.image) + better(c.temporal);
  const int worse_count = worse(c.image) + worse(c.temporal);
  if (better_count && worse_count) return Outcome::mixed;
  if (better_count) return Outcome::beats;
  if (worse_count) return Outcome::loses;
  return Outcome::ties;
}

bool late(const Comparison& c) { return worse(c.lag); }

std::string describe(const Difference& d) {
  if (d.low == d.mean && d.high == d.mean) return fmt::format("{:+.4g}", d.mean);
  return fmt::format("{:+.4g} [{:+.4g}, {:+.4g}]", d.mean, d.low, d.high);
}

Decision decide(std::span<const Candidate> candidates, const Preference& preference, std::string_view cost_basis) {
  Decision decision;
  std::vector<std::size_t> beating, eligible;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    decision.outcomes.push_back(outcome(candidates[i].against_none));
    if (!candidates[i].usable || decision.outcomes[i] != Outcome::beats) continue;
    beating.push_back(i);
    if (!late(candidates[i].against_none) && candidates[i].loses_on.empty() && within_budget(candidates[i], preference))
      eligible.push_back(i);
  }
  const bool speed = preference.prefer == Prefer::speed;
  decision.chosen = speed ? cheapest(candidates, eligible) : most_accurate_for_its_cost(candidates, eligible);
  if (!decision.chosen) {
    decision.reason = no_filter_reason(candidates, decision.outcomes, beating, preference, cost_basis);
    return decision;
  }
  const Candidate& chosen = candidates[*decision.chosen];
  // Where accuracy took a cheaper tie of the most accurate candidate, that candidate.
  const std::size_t best = *most_accurate(candidates, eligible);
  const bool tie = !speed && best != *decision.chosen;
  const std::string among =
      eligible.size() == 1 ? std::string("the only usable configuration that does")
      : tie
          ? fmt::format("the lowest cost of the {} that do, as accurate as the most accurate and beaten by none of its ties",
                        usable_count(eligible.size()))
          : fmt::format("the {} of the {} that do", speed ? "lowest cost" : "largest temporal improvement", usable_count(eligible.size()));
  decision.reason = fmt::format("{} beats {}: {}{}{}{}", figures(chosen, cost_basis, preference.baseline), preference.baseline, among,
                                preference.budget ? fmt::format(" within the budget {}", *preference.budget) : "",
                                tie ? tie_text(chosen, candidates[best], cost_basis, preference.baseline) : "",
                                set_aside(candidates, beating, chosen, preference.baseline));
  return decision;
}

}  // namespace saagen::decision

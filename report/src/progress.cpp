// The progress bar (see progress.hpp).
#include "saagen/report/progress.hpp"

#include <fmt/format.h>

#include <iostream>
#include <string>

#include <unistd.h>

namespace saagen::report {

measure::TradeProgressFn progress_bar() {
  // On a terminal, one redrawn line; in a log (stderr not a terminal), one line per stage.
  if (!::isatty(STDERR_FILENO)) {
    return [last_stage = std::string()](const measure::TradeProgress& progress) mutable {
      if (progress.stage == last_stage) return;
      last_stage = progress.stage;
      const double fraction = progress.total ? static_cast<double>(progress.done) / static_cast<double>(progress.total) : 0.0;
      std::cerr << fmt::format("[{:3.0f}%] {}\n", fraction * 100.0, progress.stage) << std::flush;
    };
  }
  return [](const measure::TradeProgress& progress) {
    const double fraction = progress.total ? static_cast<double>(progress.done) / static_cast<double>(progress.total) : 0.0;
    const int filled = static_cast<int>(fraction * 30.0);
    std::cerr << fmt::format("\r[{:<30}] {:3.0f}%  {:<40}", std::string(static_cast<std::size_t>(filled), '#'), fraction * 100.0,
                             progress.stage.substr(0, 40))
              << std::flush;
    if (progress.total && progress.done >= progress.total) std::cerr << "\n";
  };
}

}  // namespace saagen::report

// `saagen score --frames DIR`: the trade's verdict metrics on clips rendered elsewhere, in the
// format `saagen bench --frames` writes (saagen/report/score.hpp). Kept apart from main.cpp,
// which only registers and dispatches it.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace saagen::cli {

class ScoreCommand {
 public:
  explicit ScoreCommand(CLI::App& app);
  bool requested() const { return score_->parsed(); }
  int run() const;

 private:
  CLI::App* score_ = nullptr;
  std::string frames_;
  std::vector<std::string> baselines_{"none"};
  std::string json_;
  int threads_ = 0;
  bool force_ = false;
};

}  // namespace saagen::cli

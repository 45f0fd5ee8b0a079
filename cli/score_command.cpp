// `saagen score` (see score_command.hpp): parses its options and calls the report library.
#include "score_command.hpp"

#include "arguments.hpp"

#include "saagen/error.hpp"
#include "saagen/io/output.hpp"
#include "saagen/report/score.hpp"

#include <fmt/format.h>

#include <iostream>

namespace saagen::cli {

ScoreCommand::ScoreCommand(CLI::App& app) {
  score_ =
      app.add_subcommand("score",
                         "Score clips rendered elsewhere (in the format `saagen bench --frames` writes) with the trade's verdict metrics "
                         "and compare each with the baselines");
  score_->add_option("--frames", frames_, "The clips' directory: its index.json, a ground truth with two seeds per group, and the results")
      ->required()
      ->check(value_given());
  score_->add_option("--baseline", baselines_, "The configuration every other result is compared with (repeatable; default: none)")
      ->check(value_given())
      ->capture_default_str();
  score_->add_option("--json", json_, "Also write the scores and comparisons as JSON")->check(value_given());
  score_->add_option("--threads", threads_, "Threads (0: all cores)")->check(value_given())->capture_default_str();
  score_->add_flag("--force", force_, "Overwrite the --json file");
}

int ScoreCommand::run() const {
  check_named_once("--baseline", baselines_);
  if (threads_ < 0) throw Error(fmt::format("--threads {}: must be 0 (all cores) or a positive count", threads_));
  if (!json_.empty()) check_output_paths({json_}, force_);
  const report::ClipSetInput input = report::read_clip_set(frames_);
  const report::ScoreTable table = report::score_clip_set(input, baselines_, threads_);
  const std::string text = report::format_score_table(table);
  if (!json_.empty()) write_outputs({{json_, report::score_json(table).dump(1) + "\n"}}, force_);
  std::cout << text;
  return 0;
}

}  // namespace saagen::cli

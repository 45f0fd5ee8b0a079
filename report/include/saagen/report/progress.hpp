// The trade's progress on the terminal while `saagen bench` and `saagen report` compute it.
#pragma once

#include "saagen/measure/trade.hpp"

namespace saagen::report {

// A progress callback drawing a one-line bar on stderr ("\r[#####.....]  42%  ground truth sphere");
// when stderr is not a terminal, one line per stage instead ("[ 42%] ground truth sphere").
measure::TradeProgressFn progress_bar();

}  // namespace saagen::report

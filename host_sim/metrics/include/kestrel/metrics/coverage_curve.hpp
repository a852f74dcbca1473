#pragma once
// Coverage against time (issue 6, paper 002's comparison of the blend with wall following and
// SRT-Star alone): the coverage_vs_time.csv record of a kestrel-sim explore run, and the mean of
// several runs (seeds) on one time grid, so explorers can be drawn on the same axes.
//
// A run's coverage between and after its samples is its last sample at or before that time: the
// laser's coverage never decreases, and a run that ended early (a collision ends the flight; a
// finished mission lands) keeps what it had seen. Before its first sample a run has covered 0.
#include <string>
#include <vector>

#include "kestrel/core/status.hpp"

namespace kestrel::metrics {

struct CoverageCurve {
  std::vector<double> t_s;       // increasing
  std::vector<double> coverage;  // fraction of the reachable free area, 0..1
};

// Parses the text of coverage_vs_time.csv: the header `t_s,coverage`, then one `t,c` row per
// sample (blank lines ignored). kMalformed for another header, a row that is not two numbers,
// a time going backwards or a coverage outside [0, 1]; kNoData for no rows.
Result<CoverageCurve> parse_coverage_csv(const std::string& text);

// The coverage of `run` at time t (see above).
double coverage_at(const CoverageCurve& run, double t_s);

// At most this many steps on mean_coverage's grid: a plot is 1000 pixels wide, and a mistyped
// step or end (1e-6 s to 1e6 s, or a record ending at 1e9 s) would otherwise ask for 10^12
// samples, and one of 1e300 s overflows the count.
inline constexpr double kMaxCoverageSteps = 1e5;

// The mean over `runs` at t = 0, step_s, 2 step_s, ... up to end_s (inclusive, within half a
// step). kNoData for no runs; kInvalidArgument for a step or end that is not positive and finite,
// or for more than kMaxCoverageSteps steps.
Result<CoverageCurve> mean_coverage(const std::vector<CoverageCurve>& runs, double step_s, double end_s);

}  // namespace kestrel::metrics

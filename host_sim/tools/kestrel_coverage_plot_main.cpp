// kestrel-coverage-plot: coverage against time of several explorers on the same axes (issue 6,
// paper 002's comparison of the blend with wall following and SRT-Star alone), each curve the
// mean over runs (seeds) of their coverage_vs_time.csv records (metrics::mean_coverage: a run
// that ended early keeps its last coverage). One panel per world and laser.
//
//   kestrel-coverage-plot --out PNG [--step S] [--end S]
//       --panel TITLE --series LABEL=CSV[,CSV...] [--series ...] [--panel TITLE ...]
//
// Exit status 0 on success, 2 for a usage error, 1 for a record that cannot be read or parsed
// or a picture that cannot be written.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "kestrel/cli/arg_reader.hpp"
#include "kestrel/metrics/coverage_curve.hpp"
#include "kestrel/output/plot.hpp"
#include "kestrel/output/png_writer.hpp"

using namespace kestrel;

namespace {

constexpr output::Rgb kPalette[] = {output::colors::kBlue, output::colors::kOrange, output::colors::kGreen,
                                    output::colors::kRed,  output::colors::kPurple, output::colors::kCyan};

struct SeriesSpec {
  std::string label;
  std::vector<std::string> files;
};
struct PanelSpec {
  std::string title;
  std::vector<SeriesSpec> series;
};

constexpr const char* kUsage =
    "usage: kestrel-coverage-plot --out PNG [--step S] [--end S]\n"
    "           --panel TITLE --series LABEL=CSV[,CSV...] [--series ...] [--panel ...]\n";

int usage(const std::string& msg) {
  std::fprintf(stderr, "kestrel-coverage-plot: %s\n%s", msg.c_str(), kUsage);
  return 2;
}

int help() {
  std::fputs(kUsage, stdout);
  std::fputs(
      "Coverage against time, one curve per --series (the mean over its runs' coverage_vs_time.csv\n"
      "files, as kestrel-sim writes them; a run that ended early keeps its last coverage), one\n"
      "panel per --panel.\n"
      "  --out PNG      the picture to write\n"
      "  --step S       sampling step of the curves, seconds (default 1)\n"
      "  --end S        end of the time axis (default: where the longest run ends); at most\n"
      "                 100000 steps of --step\n"
      "  --panel TITLE  starts a panel; the --series after it belong to it\n"
      "  --series LABEL=CSV[,CSV...]  a curve and the runs it averages\n"
      "  --help         this text\n"
      "Exit status 0 done, 1 a record or the picture failed, 2 bad usage.\n",
      stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out;
  double step = 1.0, end = 0.0;
  std::vector<PanelSpec> panels;
  cli::ArgReader args(argc, argv);
  while (args.next()) {
    std::string v;
    if (args.is("--help") || args.is("-h")) {
      return help();
    } else if (args.is("--out")) {
      args.take(out);
    } else if (args.is("--step")) {
      args.take_double(step, 1e-6, 1e9);
    } else if (args.is("--end")) {
      args.take_double(end, 1e-6, 1e9);
    } else if (args.is("--panel")) {
      if (args.take(v)) panels.push_back({v, {}});
    } else if (args.is("--series")) {
      if (!args.take(v)) break;
      const std::size_t eq = v.find('=');
      if (panels.empty()) {
        args.fail("--series before any --panel");
      } else if (eq == std::string::npos || eq == 0 || eq + 1 == v.size()) {
        args.fail("--series wants LABEL=CSV[,CSV...], got '" + v + "'");
      } else {
        SeriesSpec sp{v.substr(0, eq), {}};
        std::stringstream files(v.substr(eq + 1));
        for (std::string f; std::getline(files, f, ',');)
          if (!f.empty()) sp.files.push_back(f);
        panels.back().series.push_back(sp);
      }
    } else {
      args.unknown();
    }
  }
  if (!args.ok()) return usage(args.error());
  if (out.empty()) return usage("--out is required");
  if (panels.empty()) return usage("no --panel");
  const bool end_given = end > 0.0;

  // Read every record first: the time axis ends where the longest run ends (or at --end).
  std::vector<std::vector<std::vector<metrics::CoverageCurve>>> runs(panels.size());
  double last_t = 0.0;
  for (std::size_t p = 0; p < panels.size(); ++p) {
    if (panels[p].series.empty()) return usage("panel '" + panels[p].title + "' has no --series");
    for (const SeriesSpec& s : panels[p].series) {
      runs[p].emplace_back();
      for (const std::string& f : s.files) {
        std::ifstream in(f);
        std::stringstream text;
        text << in.rdbuf();
        if (!in) {
          std::fprintf(stderr, "kestrel-coverage-plot: %s: cannot be read\n", f.c_str());
          return 1;
        }
        Result<metrics::CoverageCurve> c = metrics::parse_coverage_csv(text.str());
        if (!c.ok()) {
          std::fprintf(stderr, "kestrel-coverage-plot: %s: %s\n", f.c_str(), to_string(c.status()));
          return 1;
        }
        last_t = std::max(last_t, c.value().t_s.back());
        runs[p].back().push_back(std::move(c.value()));
      }
    }
  }
  if (!end_given) end = last_t > 0.0 ? last_t : 1.0;
  // The one bound on the time axis's samples, however its end was set (mean_coverage refuses
  // more too, but only as an invalid argument): a usage error when --end asked for them, a
  // record's fault when the longest run's end did.
  if (!(end / step <= metrics::kMaxCoverageSteps)) {
    if (end_given) {
      char msg[160];
      std::snprintf(msg, sizeof msg, "--end %g / --step %g is more than %g steps", end, step,
                    metrics::kMaxCoverageSteps);
      return usage(msg);
    }
    std::fprintf(stderr,
                 "kestrel-coverage-plot: the longest run ends at %g s, more than %g steps of %g s; "
                 "give a shorter --end or a larger --step\n",
                 end, metrics::kMaxCoverageSteps, step);
    return 1;
  }

  std::vector<output::Panel> plot;
  for (std::size_t p = 0; p < panels.size(); ++p) {
    output::Panel panel{panels[p].title + ": coverage", "%", {}};
    for (std::size_t k = 0; k < panels[p].series.size(); ++k) {
      const Result<metrics::CoverageCurve> m = metrics::mean_coverage(runs[p][k], step, end);
      if (!m.ok()) {
        std::fprintf(stderr, "kestrel-coverage-plot: series '%s': %s\n", panels[p].series[k].label.c_str(),
                     to_string(m.status()));
        return 1;
      }
      output::Series s{panels[p].series[k].label, kPalette[k % std::size(kPalette)], m.value().t_s, {}};
      for (double c : m.value().coverage) s.y.push_back(100.0 * c);
      panel.series.push_back(std::move(s));
    }
    // The 90 % that coverage_t90_s reports crossing, and 0 so every panel starts from the floor.
    panel.series.push_back({"90 %", output::colors::kGrey, {0.0, end}, {90.0, 90.0}});
    panel.series.push_back({"", output::colors::kWhite, {0.0}, {0.0}});
    plot.push_back(std::move(panel));
  }
  const output::Canvas canvas = output::plot_panels(plot, "time [s]", 1000, 320);
  if (output::write_png(out, canvas) != Status::kOk) {
    std::fprintf(stderr, "kestrel-coverage-plot: %s: cannot be written\n", out.c_str());
    return 1;
  }
  return 0;
}

#include "kestrel/metrics/coverage_curve.hpp"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace kestrel::metrics {
namespace {

bool parse_number(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(out);
}

std::string trimmed(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const std::size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

}  // namespace

Result<CoverageCurve> parse_coverage_csv(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  bool header = false;
  CoverageCurve c;
  while (std::getline(in, line)) {
    line = trimmed(line);
    if (line.empty()) continue;
    if (!header) {
      if (line != "t_s,coverage") return Status::kMalformed;
      header = true;
      continue;
    }
    const std::size_t comma = line.find(',');
    if (comma == std::string::npos) return Status::kMalformed;
    double t = 0, v = 0;
    if (!parse_number(trimmed(line.substr(0, comma)), t) || !parse_number(trimmed(line.substr(comma + 1)), v))
      return Status::kMalformed;
    if (v < 0.0 || v > 1.0) return Status::kMalformed;
    if (!c.t_s.empty() && t < c.t_s.back()) return Status::kMalformed;
    c.t_s.push_back(t);
    c.coverage.push_back(v);
  }
  if (!header) return Status::kMalformed;
  if (c.t_s.empty()) return Status::kNoData;
  return c;
}

double coverage_at(const CoverageCurve& run, double t_s) {
  double v = 0.0;
  for (std::size_t i = 0; i < run.t_s.size() && run.t_s[i] <= t_s; ++i) v = run.coverage[i];
  return v;
}

Result<CoverageCurve> mean_coverage(const std::vector<CoverageCurve>& runs, double step_s, double end_s) {
  if (!(step_s > 0.0) || !std::isfinite(step_s) || !(end_s > 0.0) || !std::isfinite(end_s))
    return Status::kInvalidArgument;
  if (!(end_s / step_s <= kMaxCoverageSteps)) return Status::kInvalidArgument;  // before lround can overflow
  if (runs.empty()) return Status::kNoData;
  CoverageCurve mean;
  const long steps = std::lround(std::floor(end_s / step_s + 0.5));
  for (long k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) * step_s;
    double sum = 0.0;
    for (const CoverageCurve& r : runs) sum += coverage_at(r, t);
    mean.t_s.push_back(t);
    mean.coverage.push_back(sum / static_cast<double>(runs.size()));
  }
  return mean;
}

}  // namespace kestrel::metrics

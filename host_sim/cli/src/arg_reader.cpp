#include "kestrel/cli/arg_reader.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace kestrel::cli {

bool to_double(const std::string& s, double& out) {
  if (s.empty() || std::isspace(static_cast<unsigned char>(s.front()))) return false;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v)) return false;
  out = v;
  return true;
}

bool to_u64(const std::string& s, uint64_t& out) {
  // strtoull accepts a sign and wraps "-1" to 2^64 - 1: digits only.
  if (s.empty() || s.size() > 20) return false;
  for (const char c : s) {
    if (c < '0' || c > '9') return false;
  }
  errno = 0;
  const unsigned long long v = std::strtoull(s.c_str(), nullptr, 10);
  if (errno == ERANGE) return false;
  out = v;
  return true;
}

bool to_u64_list(const std::string& s, std::vector<uint64_t>& out) {
  std::vector<uint64_t> list;
  std::stringstream ss(s);
  for (std::string tok; std::getline(ss, tok, ',');) {
    const auto dash = tok.find('-');
    uint64_t a = 0, b = 0;
    if (dash == std::string::npos) {
      if (!to_u64(tok, a)) return false;
      list.push_back(a);
      continue;
    }
    if (!to_u64(tok.substr(0, dash), a) || !to_u64(tok.substr(dash + 1), b) || b < a || b - a > 100000) return false;
    for (uint64_t v = a; v <= b; ++v) list.push_back(v);
  }
  if (list.empty() || s.back() == ',') return false;
  out = std::move(list);
  return true;
}

bool ArgReader::next() {
  if (!ok() || i_ + 1 >= argc_) return false;
  option_ = argv_[++i_];
  return true;
}

bool ArgReader::take(std::string& out) {
  // "--out --record" is a forgotten value, not a directory named "--record".
  if (i_ + 1 >= argc_ || std::string(argv_[i_ + 1]).rfind("--", 0) == 0) {
    fail("option " + option_ + " needs a value");
    return false;
  }
  out = argv_[++i_];
  return true;
}

bool ArgReader::take_number(double& out, double lo, double hi, bool integer) {
  std::string v;
  if (!take(v)) return false;
  double d = 0;
  if (!to_double(v, d) || d < lo || d > hi || (integer && d != std::floor(d))) {
    std::ostringstream why;
    why.precision(15);  // bounds as written: 1000000, not 1e+06
    why << option_ << ": '" << v << "' is not " << (integer ? "an integer" : "a number") << " in [" << lo << ", " << hi
        << "]";
    fail(why.str());
    return false;
  }
  out = d;
  return true;
}

bool ArgReader::take_double(double& out, double lo, double hi) { return take_number(out, lo, hi, false); }

bool ArgReader::take_float(float& out, double lo, double hi) {
  double d = 0;
  if (!take_number(d, lo, hi, false)) return false;
  out = static_cast<float>(d);
  return true;
}

bool ArgReader::take_int(int& out, int lo, int hi) {
  double d = 0;
  if (!take_number(d, lo, hi, true)) return false;
  out = static_cast<int>(d);
  return true;
}

bool ArgReader::take_u64(uint64_t& out) {
  std::string v;
  if (!take(v)) return false;
  if (!to_u64(v, out)) {
    fail(option_ + ": '" + v + "' is not a non-negative integer");
    return false;
  }
  return true;
}

bool ArgReader::take_u64_list(std::vector<uint64_t>& out) {
  std::string v;
  if (!take(v)) return false;
  if (!to_u64_list(v, out)) {
    fail(option_ + ": '" + v + "' is not a list of non-negative integers (e.g. 1,2,5-8)");
    return false;
  }
  return true;
}

void ArgReader::unknown() { fail("unknown option '" + option_ + "'"); }

void ArgReader::fail(const std::string& why) {
  if (error_.empty()) error_ = why;
}

}  // namespace kestrel::cli

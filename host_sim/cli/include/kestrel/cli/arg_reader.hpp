#pragma once
// Reading a host tool's command line, option by option:
//
//   ArgReader args(argc, argv);
//   while (args.next()) {
//     if (args.is("--seed")) { if (!args.take_u64(o.seed)) break; }
//     else if (...) ...
//     else { args.unknown(); break; }
//   }
//   if (!args.ok()) { print args.error(); exit 2; }
//
// Values are converted strictly: the whole argument must be the number ("12abc", "", "-3" for
// a count, "nan" are errors), so a typo never becomes a silent zero. Each error names the
// option and the value.
#include <cstdint>
#include <string>
#include <vector>

namespace kestrel::cli {

// Whole-string conversions; false on anything else.
bool to_double(const std::string& s, double& out);   // finite decimal number
bool to_u64(const std::string& s, uint64_t& out);    // non-negative decimal integer
// Comma-separated non-negative integers and inclusive ranges: "1,2,5-8" -> 1 2 5 6 7 8.
bool to_u64_list(const std::string& s, std::vector<uint64_t>& out);

class ArgReader {
 public:
  ArgReader(int argc, char** argv) : argc_(argc), argv_(argv) {}

  // Moves to the next argument, the option to handle; false at the end or after an error.
  bool next();
  const std::string& option() const { return option_; }
  bool is(const char* name) const { return option_ == name; }

  // The option's value, the argument after it; false (and an error) when there is none or
  // it is the next option ("--...").
  bool take(std::string& out);
  // The value converted, within [lo, hi]; false with an error naming the option otherwise.
  bool take_double(double& out, double lo, double hi);
  bool take_float(float& out, double lo, double hi);
  bool take_int(int& out, int lo, int hi);
  bool take_u64(uint64_t& out);
  bool take_u64_list(std::vector<uint64_t>& out);

  // The current option is not one the tool knows.
  void unknown();
  // Any other mistake, for the tool's own checks.
  void fail(const std::string& why);

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }

 private:
  bool take_number(double& out, double lo, double hi, bool integer);

  int argc_;
  char** argv_;
  int i_ = 0;
  std::string option_;
  std::string error_;
};

}  // namespace kestrel::cli

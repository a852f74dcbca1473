#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "kestrel/cli/arg_reader.hpp"

namespace kestrel::cli {
namespace {

// argv for a test: owns the strings, hands out the char* array main() would get.
struct Argv {
  std::vector<std::string> words;
  std::vector<char*> ptrs;
  explicit Argv(std::vector<std::string> w) : words(std::move(w)) {
    words.insert(words.begin(), "tool");
    for (auto& s : words) ptrs.push_back(s.data());
  }
  int argc() const { return static_cast<int>(ptrs.size()); }
  char** argv() { return ptrs.data(); }
};

TEST(ToNumber, AcceptsOnlyWholeNumbers) {
  double d = -1;
  EXPECT_TRUE(to_double("2.5", d));
  EXPECT_EQ(d, 2.5);
  EXPECT_TRUE(to_double("-1e-3", d));
  for (const char* bad : {"", "abc", "2.5s", " 2", "nan", "inf", "1e999"}) {
    d = 7;
    EXPECT_FALSE(to_double(bad, d)) << bad;
    EXPECT_EQ(d, 7) << bad;  // untouched on failure
  }
  uint64_t u = 9;
  EXPECT_TRUE(to_u64("18446744073709551615", u));
  EXPECT_EQ(u, 18446744073709551615ull);
  for (const char* bad : {"", "-1", "+1", "1.0", "12abc", "18446744073709551616", "0x10"}) {
    EXPECT_FALSE(to_u64(bad, u)) << bad;
  }
}

TEST(ToNumber, ListsAndRanges) {
  std::vector<uint64_t> v;
  ASSERT_TRUE(to_u64_list("1,2,5-8", v));
  EXPECT_EQ(v, (std::vector<uint64_t>{1, 2, 5, 6, 7, 8}));
  ASSERT_TRUE(to_u64_list("21", v));
  EXPECT_EQ(v, (std::vector<uint64_t>{21}));
  for (const char* bad : {"", ",", "1,", "1,,2", "8-5", "1-", "-3", "a,b", "1-2-3"}) {
    v = {42};
    EXPECT_FALSE(to_u64_list(bad, v)) << bad;
    EXPECT_EQ(v, (std::vector<uint64_t>{42})) << bad;
  }
}

TEST(ArgReader, WalksOptionsAndValues) {
  Argv a({"--out", "dir", "--seed", "7", "--flag", "--dt", "0.01", "--seeds", "1-3"});
  ArgReader r(a.argc(), a.argv());
  std::string out;
  uint64_t seed = 0;
  double dt = 0;
  bool flag = false;
  std::vector<uint64_t> seeds;
  while (r.next()) {
    if (r.is("--out")) {
      r.take(out);
    } else if (r.is("--seed")) {
      r.take_u64(seed);
    } else if (r.is("--flag")) {
      flag = true;
    } else if (r.is("--dt")) {
      r.take_double(dt, 0, 1);
    } else if (r.is("--seeds")) {
      r.take_u64_list(seeds);
    } else {
      r.unknown();
    }
  }
  EXPECT_TRUE(r.ok()) << r.error();
  EXPECT_EQ(out, "dir");
  EXPECT_EQ(seed, 7u);
  EXPECT_TRUE(flag);
  EXPECT_EQ(dt, 0.01);
  EXPECT_EQ(seeds, (std::vector<uint64_t>{1, 2, 3}));
}

// Each mistake stops the walk with an error naming the option and the value.
TEST(ArgReader, ReportsTheFirstMistake) {
  const auto first_error = [](std::vector<std::string> words) {
    Argv a(std::move(words));
    ArgReader r(a.argc(), a.argv());
    int seen = 0;
    while (r.next()) {
      ++seen;
      int n = 0;
      uint64_t u = 0;
      std::string s;
      if (r.is("--n")) {
        r.take_int(n, 1, 10);
      } else if (r.is("--seed")) {
        r.take_u64(u);
      } else if (r.is("--out")) {
        r.take(s);
      } else {
        r.unknown();
      }
    }
    EXPECT_FALSE(r.ok());
    EXPECT_FALSE(r.next()) << "the walk goes on after a mistake";
    return std::make_pair(r.error(), seen);
  };
  using R = std::pair<std::string, int>;  // the error, and how many options were walked
  EXPECT_EQ(first_error({"--seed", "abc", "--bogus"}), R("--seed: 'abc' is not a non-negative integer", 1));
  EXPECT_EQ(first_error({"--n", "11"}), R("--n: '11' is not an integer in [1, 10]", 1));
  EXPECT_EQ(first_error({"--n", "2.5"}), R("--n: '2.5' is not an integer in [1, 10]", 1));
  EXPECT_EQ(first_error({"--out"}), R("option --out needs a value", 1));
  EXPECT_EQ(first_error({"--out", "--seed", "3"}), R("option --out needs a value", 1));
  EXPECT_EQ(first_error({"--out", "d", "--bogus", "--seed", "x"}), R("unknown option '--bogus'", 2));
}

}  // namespace
}  // namespace kestrel::cli

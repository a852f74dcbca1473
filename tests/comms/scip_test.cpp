#include "kestrel/comms/scip.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace kestrel::comms {
namespace {

int feed(ScipDecoder& d, const std::string& s) {
  int scans = 0;
  for (char c : s) scans += d.push(static_cast<uint8_t>(c)) ? 1 : 0;
  return scans;
}

TEST(Scip, SumIsLowSixBitsPlus0x30) {
  // From the SCIP 2.0 specification's PP example: "DMIN:20;" ends with sum '4'.
  const std::string s = "DMIN:20";
  EXPECT_EQ(scip_sum(reinterpret_cast<const uint8_t*>(s.data()), s.size()), '4');
}

TEST(Scip, MdRequestFormat) {
  char buf[32];
  ASSERT_EQ(scip_md_request(44, 725, 1, 0, 0, buf, sizeof(buf)), 16u);
  EXPECT_STREQ(buf, "MD0044072501000\n");
  EXPECT_EQ(scip_md_request(44, 725, 1, 0, 0, buf, 8), 0u);
  EXPECT_EQ(scip_md_request(44, 725, 100, 0, 0, buf, sizeof(buf)), 0u);
}

TEST(Scip, UrgScanRoundTripsThroughEncoderAndDecoder) {
  static uint16_t ranges[682];
  for (int i = 0; i < 682; ++i) ranges[i] = static_cast<uint16_t>(i % 7 == 0 ? 0 : 20 + (i * 37) % 5500);
  static uint8_t wire[4096];
  const std::size_t n = scip_encode_md_scan(44, 725, 0xABCDE, ranges, 682, wire, sizeof(wire));
  ASSERT_GT(n, 0u);
  // 682 values x 3 characters = 2046 characters: 31 full blocks of 64 and one of 62.
  ScipDecoder d;
  EXPECT_EQ(feed(d, std::string(reinterpret_cast<char*>(wire), n)), 1);
  EXPECT_EQ(d.scan().count, 682);
  EXPECT_EQ(d.scan().start_step, 44);
  EXPECT_EQ(d.scan().sensor_time_ms, 0xABCDEu);
  EXPECT_EQ(std::memcmp(d.scan().range_mm.data(), ranges, sizeof(ranges)), 0);
  EXPECT_EQ(d.sum_errors(), 0u);
}

// Steps are four digits on the wire, as scip_md_request refuses: a step beyond 9999 cannot be
// written, and a response with a garbled echo ("MD1000010001010") is not one to send.
TEST(Scip, EncoderRefusesStepsBeyondFourDigits) {
  const uint16_t ranges[2] = {1000, 1001};
  uint8_t wire[64];
  EXPECT_EQ(scip_encode_md_scan(9999, 10000, 0, ranges, 2, wire, sizeof(wire)), 0u);
  EXPECT_EQ(scip_encode_md_scan(10000, 10001, 0, ranges, 2, wire, sizeof(wire)), 0u);
  EXPECT_GT(scip_encode_md_scan(9998, 9999, 0, ranges, 2, wire, sizeof(wire)), 0u);
}

TEST(Scip, CorruptLineDropsTheScanThenRecovers) {
  static uint16_t ranges[1081];
  for (int i = 0; i < 1081; ++i) ranges[i] = static_cast<uint16_t>(100 + i);
  static uint8_t wire[4096];
  const std::size_t n = scip_encode_md_scan(0, 1080, 7, ranges, 1081, wire, sizeof(wire));
  ASSERT_GT(n, 0u);
  std::string good(reinterpret_cast<char*>(wire), n);
  std::string bad = good;
  bad[40] = bad[40] == '0' ? '1' : '0';  // a flipped data character
  std::string truncated = good.substr(0, good.size() / 2) + "\n\n";
  ScipDecoder d;
  EXPECT_EQ(feed(d, bad), 0);
  EXPECT_EQ(d.sum_errors(), 1u);
  EXPECT_EQ(feed(d, truncated), 0);
  EXPECT_EQ(feed(d, good), 1);
  EXPECT_EQ(d.scan().range_mm[1080], 1180);
}

TEST(Scip, ErrorStatusAndForeignEchoesAreSkipped) {
  ScipDecoder d;
  const uint8_t st[2] = {'0', '4'};
  const std::string err = std::string("MD0044072501000\n04") + scip_sum(st, 2) + "\n\n";
  EXPECT_EQ(feed(d, err), 0);
  EXPECT_EQ(d.status_errors(), 1u);
  EXPECT_EQ(feed(d, "VV\n00P\nVEND:Hokuyo;[\n\n"), 0);
  EXPECT_EQ(feed(d, std::string(200, 'x') + "\n\n"), 0);  // an over-long line
}

// A decoder fed a byte stream, remembering every scan it completed.
struct Collector {
  ScipDecoder d;
  std::vector<ScipScan> scans;
  void feed(const std::string& s) {
    for (char c : s)
      if (d.push(static_cast<uint8_t>(c))) scans.push_back(d.scan());
  }
  uint32_t errors() const { return d.sum_errors() + d.format_errors() + d.status_errors(); }
};

bool same_scan(const ScipScan& a, const ScipScan& b) {
  return a.sensor_time_ms == b.sensor_time_ms && a.start_step == b.start_step && a.count == b.count &&
         std::memcmp(a.range_mm.data(), b.range_mm.data(), a.count * sizeof(uint16_t)) == 0;
}

// An independent check of the response's line sums: every line after the echo, up to the first
// blank line, must end with the sum of the characters before it (CRs are ignored, as by the decoder).
bool all_sums_hold(const std::string& response) {
  std::string text;
  for (char c : response)
    if (c != '\r') text += c;
  std::size_t pos = text.find('\n');
  if (pos == std::string::npos) return false;
  for (;;) {
    const std::size_t next = text.find('\n', pos + 1);
    if (next == std::string::npos) return false;  // no blank line: the response never ended
    const std::size_t len = next - pos - 1;
    if (len == 0) return true;
    const auto* line = reinterpret_cast<const uint8_t*>(text.data() + pos + 1);
    if (len < 2 || scip_sum(line, len - 1) != static_cast<char>(line[len - 1])) return false;
    pos = next;
  }
}

// A 91-beam response (4 full data blocks and one of 17 characters) and the scan it carries.
std::string small_frame(ScipScan& expected) {
  expected = ScipScan{};
  expected.sensor_time_ms = 0xABCDE;
  expected.start_step = 300;
  expected.count = 91;
  for (int i = 0; i < 91; ++i)
    expected.range_mm[i] = static_cast<uint16_t>(i % 13 == 0 ? i % 20 : 20 + (i * 911) % 60000);
  uint8_t wire[512];
  const std::size_t n = scip_encode_md_scan(300, 390, expected.sensor_time_ms, expected.range_mm.data(), 91, wire,
                                            sizeof(wire));
  return std::string(reinterpret_cast<char*>(wire), n);
}

void expect_scan_in_bounds(const ScipScan& s) {
  EXPECT_LE(s.count, kMaxBeams);
  EXPECT_LE(s.start_step + s.count, 10000);   // steps are four decimal digits
  EXPECT_LT(s.sensor_time_ms, 1u << 24);      // four 6-bit characters
}

TEST(Scip, EveryTruncationIsReportedAndTheNextResponseDecodes) {
  ScipScan expected;
  const std::string good = small_frame(expected);
  ASSERT_GT(good.size(), 300u);
  const std::size_t echo_len = good.find('\n') + 1;
  for (std::size_t k = 1; k < good.size(); ++k) {
    Collector c;
    c.feed(good.substr(0, k));
    c.feed(good);
    c.feed(good);
    // Past the echo every cut is reported. A cut inside the echo (which carries no sum) merges with
    // the next echo: the line is skipped as foreign or read as that next echo, harmlessly.
    if (k >= echo_len) {
      EXPECT_GT(c.errors(), 0u) << "cut at " << k;
    }
    // The truncated response never yields a scan; the stream resynchronises on a blank line.
    ASSERT_GE(c.scans.size(), 1u) << "cut at " << k;
    ASSERT_LE(c.scans.size(), 2u) << "cut at " << k;
    for (const ScipScan& s : c.scans) EXPECT_TRUE(same_scan(s, expected)) << "cut at " << k;
  }
}

TEST(Scip, RandomlyMutatedResponsesAreCaughtAndTheStreamRecovers) {
  ScipScan expected;
  const std::string good = small_frame(expected);
  const std::size_t echo_len = good.find('\n') + 1;
  std::mt19937 rng(11);
  const char special[] = "\n\n\r 0O09;/p\x7f";
  int detected = 0, unchanged = 0, foreign_echo = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::string text = good;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t pos = rng() % text.size();
      // Mostly characters of the encoding itself (the hardest to catch), some control and stray bytes.
      const uint32_t pick = rng() % 4;
      const char c = pick == 0   ? special[rng() % (sizeof special - 1)]
                     : pick == 1 ? static_cast<char>(rng() % 256)
                                 : static_cast<char>(0x30 + rng() % 0x40);
      switch (rng() % 3) {
        case 0: text[pos] = c; break;
        case 1: text.erase(pos, 1); break;
        default: text.insert(pos, 1, c); break;
      }
    }
    Collector c;
    c.feed(text);
    const std::size_t from_mutated = c.scans.size();
    c.feed(good);
    c.feed(good);
    const std::size_t total = c.scans.size();
    // The last good response always decodes: a damaged response costs at most the one after it.
    ASSERT_GE(total, from_mutated + 1) << "trial " << trial;
    EXPECT_TRUE(same_scan(c.scans.back(), expected)) << "trial " << trial;
    for (const ScipScan& s : c.scans) expect_scan_in_bounds(s);

    const bool sums_hold = all_sums_hold(text);
    const bool echo_intact = text.compare(0, echo_len, good, 0, echo_len) == 0;
    // A scan that differs from the one sent may only come out of a response whose every sum still holds.
    for (const ScipScan& s : c.scans)
      if (!same_scan(s, expected)) {
        EXPECT_TRUE(sums_hold) << "trial " << trial << ": wrong scan with broken sums";
      }
    // Every corruption that breaks a sum is reported, unless the echo no longer names a scan (an echo
    // carries no sum; a foreign one is skipped as a reply to some other command).
    if (!sums_hold && echo_intact) {
      EXPECT_GT(c.errors(), 0u) << "trial " << trial;
    }
    if (c.errors() > 0) ++detected;
    else if (text == good || (from_mutated == 1 && same_scan(c.scans.front(), expected))) ++unchanged;
    else ++foreign_echo;
  }
  // Most mutations are caught; the rest left the scan intact (a CR, an echo field the decoder does not
  // use) or hit the echo line, which is skipped.
  EXPECT_GT(detected, 250);
  EXPECT_EQ(detected + unchanged + foreign_echo, 300);
}

// Regression: the time stamp's characters were not checked against the encoding (0x30-0x6F), so a
// line whose sum held but whose characters did not (here a space) decoded to a time far beyond the
// scanner's 24-bit clock.
TEST(Scip, TimeStampCharactersOutsideTheEncodingAreRejected) {
  ScipScan expected;
  const std::string good = small_frame(expected);
  const std::size_t time_at = good.find('\n', good.find('\n') + 1) + 1;
  std::string bad = good;
  bad[time_at] = ' ';
  bad[time_at + 4] = scip_sum(reinterpret_cast<const uint8_t*>(bad.data() + time_at), 4);
  ASSERT_TRUE(all_sums_hold(bad));
  Collector c;
  c.feed(bad);
  EXPECT_TRUE(c.scans.empty());
  EXPECT_EQ(c.d.format_errors(), 1u);
  c.feed(good);
  ASSERT_EQ(c.scans.size(), 1u);
  EXPECT_TRUE(same_scan(c.scans[0], expected));
}

TEST(Scip, RangeCodesMapToCoreConvention) {
  EXPECT_EQ(scip_to_range_mm(0, 4000), range_code::kNoReturn);
  EXPECT_EQ(scip_to_range_mm(7, 4000), range_code::kDropout);
  EXPECT_EQ(scip_to_range_mm(4500, 4000), range_code::kNoReturn);
  EXPECT_EQ(scip_to_range_mm(1234, 4000), 1234);
}

}  // namespace
}  // namespace kestrel::comms

#include "kestrel/comms/scip.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

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

TEST(Scip, RangeCodesMapToCoreConvention) {
  EXPECT_EQ(scip_to_range_mm(0, 4000), range_code::kNoReturn);
  EXPECT_EQ(scip_to_range_mm(7, 4000), range_code::kDropout);
  EXPECT_EQ(scip_to_range_mm(4500, 4000), range_code::kNoReturn);
  EXPECT_EQ(scip_to_range_mm(1234, 4000), 1234);
}

}  // namespace
}  // namespace kestrel::comms

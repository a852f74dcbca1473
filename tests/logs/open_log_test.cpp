#include "kestrel/logs/open_log.hpp"

#include <gtest/gtest.h>

#include <string>

#include "log_test_files.hpp"

namespace kestrel::logs {
namespace {

using test::TempLogFile;

TEST(OpenLog, FormatNames) {
  LogFormat f = LogFormat::kAuto;
  EXPECT_EQ(parse_log_format("carmen", f), Status::kOk);
  EXPECT_EQ(f, LogFormat::kCarmen);
  EXPECT_EQ(parse_log_format("mines", f), Status::kOk);
  EXPECT_EQ(f, LogFormat::kMines);
  EXPECT_EQ(parse_log_format("auto", f), Status::kOk);
  EXPECT_EQ(f, LogFormat::kAuto);
  EXPECT_EQ(parse_log_format("rosbag", f), Status::kInvalidArgument);
  EXPECT_STREQ(to_string(LogFormat::kMines), "mines");
}

TEST(OpenLog, PicksTheReaderByExtensionOrByName) {
  TempLogFile carmen("a.log");
  carmen.write("FLASER 2 1 2 0 0 0 0 0 0 1.0 h 1.0\nFLASER 2 1 2 0 0 0 0 0 0 0.5 h 0.5\n");
  OpenLogOptions opt;
  opt.time_order = TimeOrder::kDrop;
  LogError err;
  auto src = open_log(carmen.c_str(), LogFormat::kAuto, opt, err);
  ASSERT_NE(src, nullptr) << err.reason;
  LogRecord rec;
  EXPECT_EQ(src->next(rec), Status::kOk);
  EXPECT_EQ(rec.scan.beam_count, 2);
  EXPECT_EQ(src->next(rec), Status::kNoData);  // the older scan was dropped, as asked
  EXPECT_EQ(src->stats().backward_stamps, 1u);

  TempLogFile mines("b.dat");
  std::string line = "5";
  for (int i = 1; i < 706; ++i) line.append(" 100");
  line.append("\n");
  mines.write(line);
  src = open_log(mines.c_str(), LogFormat::kAuto, {}, err);
  ASSERT_NE(src, nullptr) << err.reason;
  ASSERT_EQ(src->next(rec), Status::kOk) << src->error().reason;
  EXPECT_EQ(rec.scan.beam_count, 682);
  // Forced to CARMEN, a Mines file does not parse: its first word is a number.
  src = open_log(mines.c_str(), LogFormat::kCarmen, {}, err);
  ASSERT_NE(src, nullptr);
  EXPECT_EQ(src->next(rec), Status::kMalformed);
  EXPECT_EQ(src->error().line, 1u);

  src = open_log("/nonexistent/x.dat", LogFormat::kAuto, {}, err);
  EXPECT_EQ(src, nullptr);
  EXPECT_EQ(err.status, Status::kIoError);
}

}  // namespace
}  // namespace kestrel::logs

#include "kestrel/logs/mines_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "log_test_files.hpp"
#include "text_mutation.hpp"

namespace kestrel::logs {
namespace {

using test::TempLogFile;

// A line in the Mines layout: stamp, 23 other fields, 682 ranges (beam i = 1000 + i mm, except
// beam 0 = no return and beam 1 = error code 7), and the trailing field.
// `bad_beam`/`bad_text` replace one range; `fields` cuts the line short.
std::string mines_line(long long stamp_us, bool trailing = true, int bad_beam = -1, const char* bad_text = "",
                       int fields = 707) {
  std::string s = std::to_string(stamp_us);
  for (int i = 1; i < 24 && i < fields; ++i) s.append(" ").append(std::to_string(i));
  for (int i = 0; i < 682 && 24 + i < fields; ++i) {
    s.append(" ");
    if (i == bad_beam) {
      s.append(bad_text);
    } else {
      s.append(std::to_string(i == 0 ? 0 : i == 1 ? 7 : 1000 + i));
    }
  }
  if (trailing && fields == 707) s.append(" 0");
  s.append("\n");
  return s;
}

TEST(MinesReader, ReadsTheUrg04lxLayout) {
  TempLogFile file("exp.dat");
  file.write(mines_line(361431443) + mines_line(361528520, false));
  MinesReader reader;
  ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
  LogRecord rec;
  ASSERT_EQ(reader.next(rec), Status::kOk) << reader.error().reason;
  EXPECT_EQ(rec.kind, LogRecord::Kind::kLaser);
  EXPECT_FALSE(rec.has_pose);
  EXPECT_EQ(rec.scan.stamp.us, 361431443);
  EXPECT_DOUBLE_EQ(rec.timestamp_s, 361.431443);
  EXPECT_EQ(rec.scan.beam_count, 682);
  EXPECT_EQ(rec.scan.range_mm[0], range_code::kNoReturn);
  EXPECT_EQ(rec.scan.range_mm[1], 7);
  EXPECT_EQ(rec.scan.range_mm[681], 1681);
  EXPECT_NEAR(rec.scan.first_angle_rad, -340 * 2 * M_PI / 1024, 1e-6);
  EXPECT_NEAR(rec.scan.angle_of(681), 341 * 2 * M_PI / 1024, 1e-5);
  EXPECT_EQ(rec.scan.scan_period.us, 100000);
  EXPECT_EQ(rec.scan.beam_interval.us, 98);
  EXPECT_EQ(rec.scan.max_range_mm, 5600);
  ASSERT_EQ(reader.next(rec), Status::kOk) << reader.error().reason;
  EXPECT_EQ(rec.line, 2u);
  EXPECT_EQ(reader.next(rec), Status::kNoData);
}

TEST(MinesReader, BadLinesGiveStatusAndLineNumber) {
  const std::string good = mines_line(1000);
  const std::string short_line = mines_line(2000, true, -1, "", 705);
  const std::string bad_number = mines_line(3000, true, 100, "11x0");
  const std::string negative = mines_line(3000, true, 100, "-110");
  std::string bad_stamp = "x";
  bad_stamp.append(good);
  std::string two_good = good;
  two_good.append(good);
  std::string truncated = good;
  truncated.append(good, 0, 1000);
  std::string backwards = mines_line(5000);
  backwards.append(mines_line(4000));
  struct Case {
    const char* name;
    std::string text;
    Status status;
    uint32_t line;
  } cases[] = {
      {"short line", std::string(good).append(short_line), Status::kMalformed, 2},
      {"bad number", std::string(good).append(bad_number), Status::kMalformed, 2},
      {"negative range", std::string(good).append(negative), Status::kMalformed, 2},
      {"bad stamp", bad_stamp, Status::kMalformed, 1},
      {"backwards", backwards, Status::kTimeJump, 2},
      {"truncated", truncated, Status::kMalformed, 2},
  };
  for (const Case& c : cases) {
    TempLogFile file("bad.dat");
    file.write(c.text);
    MinesReader reader;
    ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
    LogRecord rec;
    Status s;
    while (ok(s = reader.next(rec))) {
    }
    EXPECT_EQ(s, c.status) << c.name << ": " << reader.error().reason;
    EXPECT_EQ(reader.error().line, c.line) << c.name;
  }
}

// Every message names a field the same way (FieldCursor's 1-based count, as awk's $N): beam
// 100 is field 125 whether it is not a number or a number out of range.
TEST(MinesReader, BadRangesNameTheSameField) {
  for (const char* bad : {"11x0", "-110", "70000"}) {
    TempLogFile file("bad.dat");
    file.write(mines_line(1000, true, 100, bad));
    MinesReader reader;
    ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
    LogRecord rec;
    EXPECT_EQ(reader.next(rec), Status::kMalformed) << bad;
    EXPECT_EQ(std::string(reader.error().reason).rfind("field 125: ", 0), 0u) << bad << ": " << reader.error().reason;
  }
}

TEST(MinesReader, RandomlyMutatedLogsNeverCrash) {
  const std::string base = mines_line(361431443) + mines_line(361528520, false) + mines_line(361625000);
  std::mt19937 rng(13);
  const char alphabet[] = "0123456789 -+.xe\n\t#\r";
  TempLogFile file("mutated.dat");
  int errors = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const std::string text = test::mutate_text(base, alphabet, rng);
    file.write(text);
    MinesReader reader;
    ASSERT_EQ(reader.open(file.c_str()), Status::kOk);
    LogRecord rec;
    Status s;
    int records = 0;
    long long last_us = 0;
    while (ok(s = reader.next(rec)) && records < 100) {
      ++records;
      ASSERT_EQ(rec.kind, LogRecord::Kind::kLaser);
      ASSERT_EQ(rec.scan.beam_count, MinesReader::kBeams);
      for (int i = 0; i < MinesReader::kBeams; ++i) ASSERT_LE(rec.scan.range_mm[i], rec.scan.max_range_mm);
      if (records > 1) {
        ASSERT_GE(rec.scan.stamp.us, last_us);  // TimeOrder::kError: never out of order
      }
      last_us = rec.scan.stamp.us;
    }
    // A line has 706 or 707 fields, so an inserted newline cannot make a fourth record.
    ASSERT_LE(records, 3);
    if (s != Status::kNoData) {
      ++errors;
      EXPECT_GT(reader.error().line, 0u);
      EXPECT_NE(reader.error().reason[0], '\0');
    } else {
      // A clean end: every line was a record, a comment or blank.
      EXPECT_EQ(reader.stats().lines, reader.stats().laser_records + reader.stats().skipped_lines);
      EXPECT_EQ(reader.stats().laser_records, static_cast<uint64_t>(records));
    }
  }
  // Most mutations must be caught; the rest changed a number into another valid number, or a
  // separator into another separator.
  EXPECT_GT(errors, 110);
}

}  // namespace
}  // namespace kestrel::logs

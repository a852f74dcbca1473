#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "kestrel/output/canvas.hpp"
#include "kestrel/output/json_writer.hpp"
#include "kestrel/output/pgm_map.hpp"
#include "kestrel/output/plot.hpp"
#include "kestrel/output/tum_writer.hpp"
#if defined(KESTREL_HAS_PNG)
#include "kestrel/output/png_writer.hpp"
#endif

namespace kestrel::output {
namespace {

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "kestrel_output_" + name;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(Canvas, LinesAreClippedAndWorldViewHasYUp) {
  Canvas c(10, 10);
  c.line(-5, 5, 20, 5, colors::kBlack);  // crosses the whole canvas, ends outside
  for (int x = 0; x < 10; ++x) EXPECT_EQ(c.at(x, 5), colors::kBlack);
  c.set_world_view(0, 0, 2);  // 2 px per metre, origin at the bottom-left
  EXPECT_EQ(c.wx(1.0), 2);
  EXPECT_EQ(c.wy(0.0), 9);
  EXPECT_EQ(c.wy(1.0), 7);
  c.world_line(std::nan(""), 0, 1, 1, colors::kRed);  // NaN must neither crash nor hang
}

TEST(Canvas, TextDrawsGlyphPixels) {
  Canvas c(40, 10);
  const int w = c.text(0, 0, "1", colors::kBlack);
  EXPECT_EQ(w, 6);
  int dark = 0;
  for (int y = 0; y < 7; ++y)
    for (int x = 0; x < 5; ++x) dark += c.at(x, y) == colors::kBlack;
  EXPECT_EQ(dark, 10);  // the "1" glyph has ten set pixels
}

TEST(Json, NestedObjectsNumbersAndNull) {
  JsonWriter j;
  j.begin_object().number("a", 1.5).integer("n", 3).begin_object("tasks").number("x", std::nan("")).end_object();
  j.begin_array("v").number(1).number(2).end_array().string("s", "q\"uote").boolean("ok", true).end_object();
  EXPECT_EQ(j.text(),
            "{\n  \"a\": 1.5,\n  \"n\": 3,\n  \"tasks\": {\n    \"x\": null\n  },\n  \"v\": [\n    1,\n    2],\n"
            "  \"s\": \"q\\\"uote\",\n  \"ok\": true\n}\n");
}

TEST(Tum, WritesQuaternionOfYaw) {
  const std::string path = temp_path("traj.tum");
  {
    TumWriter w;
    ASSERT_EQ(w.open(path), Status::kOk);
    ASSERT_EQ(w.write(1.25, 1, 2, 0.5, M_PI / 2), Status::kOk);
  }
  const std::string text = slurp(path);
  double t, x, y, z, qx, qy, qz, qw;
  const std::size_t nl = text.find('\n');
  ASSERT_EQ(std::sscanf(text.c_str() + nl + 1, "%lf %lf %lf %lf %lf %lf %lf %lf", &t, &x, &y, &z, &qx, &qy, &qz, &qw),
            8);
  EXPECT_DOUBLE_EQ(t, 1.25);
  EXPECT_NEAR(qz, std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(qw, std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(qx, 0, 1e-12);
}

TEST(PgmMap, WritesTopRowFirstAndYaml) {
  GridImage m;
  m.width = 2;
  m.height = 2;
  m.resolution_m = 0.1;
  m.origin_x_m = -1;
  m.cells = {kPgmOccupied, kPgmFree, kPgmUnknown, kPgmFree};  // bottom row, then top row
  const std::string stem = temp_path("map");
  ASSERT_EQ(write_map(stem, m), Status::kOk);
  const std::string pgm = slurp(stem + ".pgm");
  ASSERT_GE(pgm.size(), 4u);
  EXPECT_EQ(pgm.substr(pgm.size() - 4),
            std::string({char(kPgmUnknown), char(kPgmFree), char(kPgmOccupied), char(kPgmFree)}));
  const std::string yaml = slurp(stem + ".yaml");
  EXPECT_NE(yaml.find("image: kestrel_output_map.pgm"), std::string::npos);
  EXPECT_NE(yaml.find("resolution: 0.100000"), std::string::npos);
  EXPECT_NE(yaml.find("origin: [-1.000000, 0.000000, 0.0]"), std::string::npos);
  m.cells.pop_back();
  EXPECT_EQ(write_map(stem, m), Status::kInvalidArgument);
}

TEST(Plot, DrawsSeriesInsideThePanel) {
  Panel p{"x", "m", {{"truth", colors::kBlue, {0, 1, 2}, {0, 1, 0}}}};
  const Canvas c = plot_panels({p}, "time [s]", 400, 200);
  int blue = 0;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) blue += c.at(x, y) == colors::kBlue;
  EXPECT_GT(blue, 100);
}

#if defined(KESTREL_HAS_PNG)
TEST(Png, WritesAValidSignature) {
  Canvas c(4, 3, colors::kRed);
  const std::string path = temp_path("img.png");
  ASSERT_EQ(write_png(path, c), Status::kOk);
  const std::string bytes = slurp(path);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  EXPECT_EQ(write_png("/nonexistent-dir/x.png", c), Status::kIoError);
}
#endif

}  // namespace
}  // namespace kestrel::output

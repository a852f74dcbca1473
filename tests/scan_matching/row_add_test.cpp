#include <gtest/gtest.h>

#include <array>
#include <random>
#include <type_traits>

#include "kestrel/scan_matching/params.hpp"
#include "kestrel/scan_matching/row_add.hpp"

namespace kestrel::scan_matching {
namespace {

// A map-like buffer of random cells (including the cap) and random row offsets into it.
struct Data {
  static constexpr int kDim = 96;
  std::array<uint8_t, kDim * kDim> cells{};
  std::array<int32_t, 300> offsets{};
  explicit Data(unsigned seed, int width, int rows) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> cell(0, kCellMax), x(0, kDim - width), y(0, kDim - rows);
    for (auto& c : cells) c = static_cast<uint8_t>(cell(rng));
    for (auto& o : offsets) o = y(rng) * kDim + x(rng);
  }
};

// The SIMD row kernel (NEON on Overo, SSE2 on the host) adds exactly what the scalar one does.
TEST(RowAdd, LanesEqualScalar) {
  for (int width = kRowLanes; width <= 64; width += kRowLanes) {
    const Data d(static_cast<unsigned>(width), width, 1);
    std::array<uint16_t, 64> lanes{}, scalar{};
    for (int i = 0; i < 300; ++i) {
      add_row_lanes(lanes.data(), d.cells.data() + d.offsets[static_cast<std::size_t>(i)], width);
      add_row_scalar(scalar.data(), d.cells.data() + d.offsets[static_cast<std::size_t>(i)], width);
    }
    EXPECT_EQ(lanes, scalar) << width;
  }
}

// Register-held rows of lane groups equal the scalar sum over the same points, for every width
// the search uses, starting from a non-zero image (the edge points' share added first).
TEST(RowAdd, RegisterRowsEqualScalar) {
  if constexpr (kRowLanes == 8) {
    const auto check = [](auto groups_tag) {
      constexpr int G = decltype(groups_tag)::value;
      const Data d(100 + G, 8 * G, 1);
      std::array<uint16_t, 8 * G> lanes{}, scalar{};
      for (int j = 0; j < 8 * G; ++j)
        lanes[static_cast<std::size_t>(j)] = scalar[static_cast<std::size_t>(j)] = static_cast<uint16_t>(j * 7);
      sum_rows_lanes<G>(lanes.data(), d.cells.data(), d.offsets.data(), 300);
      sum_rows_scalar(scalar.data(), d.cells.data(), d.offsets.data(), 300, 8 * G);
      EXPECT_EQ(lanes, scalar) << G;
    };
    check(std::integral_constant<int, 1>{});
    check(std::integral_constant<int, 2>{});
    check(std::integral_constant<int, 3>{});
    check(std::integral_constant<int, 4>{});
  } else {
    GTEST_SKIP() << "no SIMD lanes on this target: the search uses the scalar kernel only";
  }
}

#if defined(__ARM_NEON) || defined(__SSE2__)
// The 8-lane block kernel: each of R rows, a map row apart, equals its scalar sum.
template <int R>
void check_block() {
  const Data d(200 + R, 8, R);
  std::array<uint16_t, 8 * 8> lanes{}, scalar{};
  lanes.fill(3);
  scalar.fill(3);
  sum_block_lanes<R>(lanes.data(), 8, d.cells.data(), Data::kDim, d.offsets.data(), 300);
  for (int r = 0; r < R; ++r) {
    for (int i = 0; i < 300; ++i) {
      add_row_scalar(scalar.data() + 8 * r, d.cells.data() + d.offsets[static_cast<std::size_t>(i)] + r * Data::kDim,
                     8);
    }
  }
  EXPECT_EQ(lanes, scalar) << R;
}

TEST(RowAdd, BlockEqualsScalar) {
  check_block<1>();
  check_block<2>();
  check_block<3>();
  check_block<4>();
  check_block<5>();
  check_block<6>();
  check_block<7>();
  check_block<8>();
}
#endif

}  // namespace
}  // namespace kestrel::scan_matching

#include "kestrel/core/mode_names.hpp"

#include <gtest/gtest.h>

namespace kestrel {
namespace mode_names_test {

enum class Colour : uint8_t { kRed, kGreen, kBlue };
// kBlue is left off the list, as a mode not yet offered would be.
inline constexpr Colour kOfferedColours[] = {Colour::kRed, Colour::kGreen};

const char* to_string(Colour c) {
  switch (c) {
    case Colour::kRed:
      return "red";
    case Colour::kGreen:
      return "green";
    case Colour::kBlue:
      return "blue";
  }
  return "unknown";
}

TEST(ModeNames, EveryListedModeParsesBackFromItsName) {
  for (const Colour c : kOfferedColours) {
    const Result<Colour> parsed = parse_by_name(to_string(c), kOfferedColours);
    ASSERT_TRUE(parsed.ok());
    EXPECT_EQ(parsed.value(), c);
  }
}

TEST(ModeNames, OnlyTheListDecidesWhatIsKnown) {
  EXPECT_TRUE(listed(Colour::kGreen, kOfferedColours));
  EXPECT_FALSE(listed(Colour::kBlue, kOfferedColours));
  EXPECT_FALSE(listed(static_cast<Colour>(7), kOfferedColours));  // a corrupted config byte
  EXPECT_EQ(parse_by_name("blue", kOfferedColours).status(), Status::kInvalidArgument);
}

TEST(ModeNames, NamesMatchExactlyAndNullIsRefused) {
  EXPECT_EQ(parse_by_name("Red", kOfferedColours).status(), Status::kInvalidArgument);
  EXPECT_EQ(parse_by_name("red ", kOfferedColours).status(), Status::kInvalidArgument);
  EXPECT_EQ(parse_by_name("", kOfferedColours).status(), Status::kInvalidArgument);
  EXPECT_EQ(parse_by_name(nullptr, kOfferedColours).status(), Status::kInvalidArgument);
}

}  // namespace mode_names_test
}  // namespace kestrel

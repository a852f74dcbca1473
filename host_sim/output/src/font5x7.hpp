#pragma once
// A 5x7 bitmap font for labels in run pictures: printable ASCII, lower case drawn as upper.
#include <cstdint>

namespace kestrel::output {

// Seven rows of five bits (bit 4 = leftmost column) for character c; unknown characters give
// a hollow box so a missing glyph is visible rather than silently blank.
const uint8_t* glyph5x7(char c);

}  // namespace kestrel::output

#pragma once
// Randomly mutated copies of a valid text, for the parsers' mutation tests (logs, world files,
// configurations, parameter files): one to four edits, each a character replaced, deleted or
// inserted, drawn from an alphabet of the format's own characters so that most mutants still
// look like the format and reach deep into the parser. Deterministic for a seeded generator.
#include <cstddef>
#include <random>
#include <string>
#include <string_view>

namespace kestrel::test {

// Where an edit lands: given the text and a position drawn uniformly, the position to edit
// (a test may steer edits into the values, say, when the keys are most of the text).
using EditPosition = std::size_t (*)(const std::string& text, std::size_t drawn, std::mt19937& rng);

inline std::size_t anywhere(const std::string&, std::size_t drawn, std::mt19937&) { return drawn; }

inline std::string mutate_text(std::string_view base, std::string_view alphabet, std::mt19937& rng,
                               EditPosition where = anywhere) {
  std::string text(base);
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits && !text.empty(); ++e) {
    std::size_t pos = where(text, rng() % text.size(), rng);
    if (pos >= text.size()) pos = text.size() - 1;  // a picker may return the end of the text
    const char c = alphabet[rng() % alphabet.size()];
    switch (rng() % 3) {
      case 0: text[pos] = c; break;
      case 1: text.erase(pos, 1); break;
      default: text.insert(pos, 1, c); break;
    }
  }
  return text;
}

}  // namespace kestrel::test

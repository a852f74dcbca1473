#pragma once
// Test-only: a small text file (a parameter file, a waypoint list) in gtest's temporary
// directory. Returns its path; a file that cannot be written fails the calling test.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace kestrel::test {

inline std::string write_temp_file(const char* name, const char* text) {
  const std::string path = testing::TempDir() + name;
  std::FILE* f = std::fopen(path.c_str(), "w");
  EXPECT_NE(f, nullptr) << path;
  if (f != nullptr) {
    std::fputs(text, f);
    std::fclose(f);
  }
  return path;
}

}  // namespace kestrel::test

#pragma once
// Small log files written by the tests themselves: plain or gzip, in a per-process temporary
// folder, removed when the object goes out of scope.
#include <zlib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace kestrel::test {

class TempLogFile {
 public:
  explicit TempLogFile(const std::string& name) {
    static int counter = 0;
    const auto dir = std::filesystem::temp_directory_path() /
                     ("kestrel-logs-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    path_ = (dir / (std::to_string(counter++) + "-" + name)).string();
  }
  ~TempLogFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
    // Removes the per-process folder once its last file is gone (remove() spares a non-empty one).
    std::filesystem::remove(std::filesystem::path(path_).parent_path(), ec);
  }
  TempLogFile(const TempLogFile&) = delete;
  TempLogFile& operator=(const TempLogFile&) = delete;

  const std::string& path() const { return path_; }
  const char* c_str() const { return path_.c_str(); }

  void write(const std::string& content) const {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out << content;
  }
  void write_gz(const std::string& content) const {
    gzFile f = gzopen(path_.c_str(), "wb");
    gzwrite(f, content.data(), static_cast<unsigned>(content.size()));
    gzclose(f);
  }
  std::string read() const {
    std::ifstream in(path_, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }

 private:
  std::string path_;
};

}  // namespace kestrel::test

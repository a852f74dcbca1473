#pragma once
// Where tests find the repository's files and the shared real-data folder (../shared/data).
#include <string>

namespace kestrel::test {

inline std::string source_path(const std::string& rel) { return std::string(KESTREL_SOURCE_DIR) + "/" + rel; }
inline std::string shared_data_path(const std::string& rel) { return std::string(KESTREL_SHARED_DATA_DIR) + "/" + rel; }

}  // namespace kestrel::test

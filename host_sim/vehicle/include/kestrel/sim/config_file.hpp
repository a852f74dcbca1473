#pragma once
// The simulator's configuration files: one `key = value` per line, `#` comments, numbers in
// SI units. Each component (vehicle, IMU, laser) binds its Params fields to key names in a
// table; unknown keys and malformed lines are errors naming the line, so a typo is never
// silently ignored.
#include <string>
#include <string_view>
#include <vector>

namespace kestrel::sim {

struct ConfigEntry {
  std::string key;
  double value = 0;
  int line = 0;
};

// One field a component accepts: `key` (e.g. "vehicle.k_pitch") and where it lives.
struct ConfigBinding {
  const char* key;
  double* field;
};

class ConfigFile {
 public:
  // Parses text; returns "" or "SOURCE:LINE: reason".
  std::string parse(std::string_view text, std::string_view source_name);
  std::string load(const std::string& path);

  // Writes every entry whose key is in `bindings`; entries not bound by any of the calls
  // are reported by unknown_keys().
  void apply(const ConfigBinding* bindings, std::size_t count);
  // "" when every entry was used by some apply(), else "SOURCE:LINE: unknown key 'x'".
  std::string unknown_keys() const;
  const std::vector<ConfigEntry>& entries() const { return entries_; }

 private:
  std::string source_;
  std::vector<ConfigEntry> entries_;
  std::vector<bool> used_;
};

}  // namespace kestrel::sim

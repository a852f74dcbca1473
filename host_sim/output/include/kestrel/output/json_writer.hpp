#pragma once
// A small JSON writer for metrics.json: nested objects of numbers, strings, booleans and
// arrays, written in insertion order with stable number formatting so that two identical
// runs give identical bytes. Non-finite numbers are written as null (JSON has no NaN).
#include <cstdint>
#include <string>

#include "kestrel/core/status.hpp"

namespace kestrel::output {

class JsonWriter {
 public:
  JsonWriter& begin_object(const char* key = nullptr);
  JsonWriter& end_object();
  JsonWriter& begin_array(const char* key = nullptr);
  JsonWriter& end_array();
  JsonWriter& number(const char* key, double v);
  JsonWriter& integer(const char* key, int64_t v);
  JsonWriter& boolean(const char* key, bool v);
  JsonWriter& string(const char* key, const std::string& v);
  // Array elements.
  JsonWriter& number(double v) { return number(nullptr, v); }

  const std::string& text() const { return out_; }
  Status write_file(const std::string& path) const;

 private:
  void key_prefix(const char* key);
  void escaped(const std::string& s);
  std::string out_;
  int depth_ = 0;
  bool first_ = true;
};

}  // namespace kestrel::output

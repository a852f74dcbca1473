#pragma once
// Parameter files: plain text, one `key = value` per line, `#` starts a comment (units go in
// the comments the writer emits). A module describes its parameters once as a table of
// ParamField (key, where the value lives, allowed range, unit); the same table parses, checks
// and writes a file, so the file format and the Params struct cannot drift apart.
//
// API
//   Status parse_params(text, fields, error)     text -> values, all-or-nothing
//   Status load_params_file(path, fields, error) reads a file (<= kMaxParamFileBytes) and parses it
//   Status load_params_struct(path, out, fields_of, validate, inconsistent, error)  the same into a
//                                                whole Params struct, checked as one
//   Status check_ranges(fields)                  every value within its [min, max]
//   Result<size_t> write_params(fields, header, buf, cap)  values -> text
//   Status save_params_file(path, fields, header, error)
//
// Parsing rules (every violation is an error naming the line and the key):
//   unknown key, duplicate key, missing '=', empty or non-numeric value, trailing garbage,
//   non-finite value, value outside [min, max]. Keys absent from the file keep their current
//   (default) values. On any error no value is changed: fields are written only after the
//   whole text has been checked.
#include <cstddef>
#include <cstdio>
#include <span>
#include <string_view>

#include "kestrel/core/status.hpp"

namespace kestrel::params {

inline constexpr std::size_t kMaxParamFileBytes = 8192;
inline constexpr std::size_t kMaxParamFields = 64;

struct ParamField {
  const char* key;    // [a-z0-9_]+
  float* value;       // where the value is read from and stored to
  float min;          // inclusive bounds of a valid value
  float max;
  const char* unit;   // written as a comment, e.g. "(m/s^2)^2/Hz"
  const char* help;   // one line, written as a comment
};

struct ParamError {
  int line = 0;         // 1-based line of the error, 0 when not tied to a line
  char message[160] = {};
};

// The error as a tool prints it after its own name: "PATH:LINE: message" for a line's error;
// the message alone when it names PATH itself ("cannot open 'PATH'"), else "PATH: message".
// The number of characters snprintf would write (no terminating zero counted).
int describe(const char* path, const ParamError& error, char* buf, std::size_t cap);

Status parse_params(std::string_view text, std::span<const ParamField> fields, ParamError& error);
// kOk when every field's value lies in its [min, max] (NaN does not): the range check a
// module's validate() shares with the parser.
Status check_ranges(std::span<const ParamField> fields);
Status load_params_file(const char* path, std::span<const ParamField> fields, ParamError& error);

// Loads a file over a copy of `out` (fields_of(copy) gives its ParamField table), checks the
// copy with validate(copy), and only then commits it: a file is taken all or nothing, also
// when each value is in range but the set is inconsistent; `inconsistent` is then the error
// message, which says what validate() needs beyond the ranges.
template <typename Params, typename FieldsOf, typename Validate>
Status load_params_struct(const char* path, Params& out, FieldsOf fields_of, Validate validate,
                          const char* inconsistent, ParamError& error) {
  Params staged = out;
  const auto fields = fields_of(staged);
  if (const Status s = load_params_file(path, fields, error); !ok(s)) return s;
  if (!ok(validate(staged))) {
    error.line = 0;
    std::snprintf(error.message, sizeof(error.message), "%s", inconsistent);
    return Status::kInvalidArgument;
  }
  out = staged;
  return Status::kOk;
}

// Writes every field as `# help [unit]` then `key = value` (9 significant digits, so a float
// survives the round trip). Returns the number of characters written (no terminating zero
// counted), or kCapacityExceeded.
Result<std::size_t> write_params(std::span<const ParamField> fields, const char* header, char* buf,
                                 std::size_t cap);
Status save_params_file(const char* path, std::span<const ParamField> fields, const char* header,
                        ParamError& error);

}  // namespace kestrel::params

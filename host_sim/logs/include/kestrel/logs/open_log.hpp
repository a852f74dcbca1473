#pragma once
// Opens a log of either supported format behind the LogSource interface, for tools such as
// kestrel-replay (`--format carmen|mines`). Allocates the reader once, at start-up.
#include <memory>
#include <string_view>

#include "kestrel/logs/carmen_reader.hpp"
#include "kestrel/logs/mines_reader.hpp"

namespace kestrel::logs {

enum class LogFormat : uint8_t {
  kAuto,    // ".dat" (BreezySLAM/Mines) is kMines, anything else kCarmen
  kCarmen,
  kMines,
};

// Parses "auto", "carmen", "mines": kOk or kInvalidArgument.
Status parse_log_format(std::string_view name, LogFormat& out);
const char* to_string(LogFormat f);

struct OpenLogOptions {
  TimeOrder time_order = TimeOrder::kError;
  CarmenReaderOptions carmen;  // its time_order is overridden by the one above
  MinesReaderOptions mines;    // likewise
};

// The open reader, or nullptr with `error` filled (kIoError for a file that cannot be opened).
std::unique_ptr<LogSource> open_log(const char* path, LogFormat format, const OpenLogOptions& options,
                                    LogError& error);

}  // namespace kestrel::logs

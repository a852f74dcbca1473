#pragma once
// PNG files through libpng (host builds only: KESTREL_HAS_PNG).
#include <string>

#include "kestrel/core/status.hpp"
#include "kestrel/output/canvas.hpp"

namespace kestrel::output {

// Writes the canvas as an 8-bit RGB PNG. kIoError if the file cannot be written.
Status write_png(const std::string& path, const Canvas& canvas);

}  // namespace kestrel::output

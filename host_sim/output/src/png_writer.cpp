#include "kestrel/output/png_writer.hpp"

#include <png.h>

#include <cstdio>
#include <vector>

namespace kestrel::output {

Status write_png(const std::string& path, const Canvas& canvas) {
  FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return Status::kIoError;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return Status::kIoError;
  }
  // libpng reports errors by longjmp; nothing with a destructor lives across this point.
  std::vector<png_bytep> rows(static_cast<std::size_t>(canvas.height()));
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return Status::kIoError;
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, static_cast<png_uint_32>(canvas.width()), static_cast<png_uint_32>(canvas.height()), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  static_assert(sizeof(Rgb) == 3, "Rgb must be packed for libpng rows");
  auto* base = reinterpret_cast<png_bytep>(const_cast<Rgb*>(canvas.pixels().data()));
  for (int y = 0; y < canvas.height(); ++y)
    rows[static_cast<std::size_t>(y)] =
        base + static_cast<std::size_t>(y) * static_cast<std::size_t>(canvas.width()) * 3;
  png_write_info(png, info);
  png_write_image(png, rows.data());
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return std::fclose(f) == 0 ? Status::kOk : Status::kIoError;
}

}  // namespace kestrel::output

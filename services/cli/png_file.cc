// Copyright 2026 The DCS Authors.
#include "services/cli/png_file.h"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <vector>

#include "absl/strings/str_cat.h"

namespace dcs::services::cli {

absl::Status WritePng(const std::string& path, std::span<const uint8_t> rgb, int width,
                      int height, int scale) {
  FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) {
    return absl::UnavailableError(absl::StrCat("cannot write ", path, ": ", std::strerror(errno)));
  }
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png == nullptr ? nullptr : png_create_info_struct(png);
  const int out_width = width * scale;
  std::vector<uint8_t> row(static_cast<size_t>(3) * out_width);
  // libpng reports errors by longjmp; nothing here needs unwinding.
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
    return absl::InternalError(absl::StrCat("libpng failed while writing ", path));
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, out_width, height * scale, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y) {
    const uint8_t* source = rgb.data() + static_cast<size_t>(3) * width * y;
    for (int x = 0; x < out_width; ++x) {
      std::memcpy(&row[3 * static_cast<size_t>(x)], source + 3 * (x / scale), 3);
    }
    for (int repeat = 0; repeat < scale; ++repeat) png_write_row(png, row.data());
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(file) != 0) {
    return absl::ResourceExhaustedError(
        absl::StrCat("cannot finish ", path, ": ", std::strerror(errno)));
  }
  return absl::OkStatus();
}

}  // namespace dcs::services::cli

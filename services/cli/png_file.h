// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_PNG_FILE_H_
#define DCS_SERVICES_CLI_PNG_FILE_H_

// PNG files of RGB images (libpng), for `dcs env render`. Thread-safe.

#include <cstdint>
#include <span>
#include <string>

#include "absl/status/status.h"

namespace dcs::services::cli {

// Writes `rgb` (row-major, 3 bytes per pixel, width x height) to `path` as an 8-bit RGB PNG,
// each pixel repeated `scale` x `scale` times (nearest neighbour: small observations stay
// crisp). Errors name the path. REQUIRES: rgb.size() == 3 * width * height; scale >= 1.
absl::Status WritePng(const std::string& path, std::span<const uint8_t> rgb, int width,
                      int height, int scale = 1);

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_PNG_FILE_H_

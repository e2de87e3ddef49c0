// Copyright 2026 The DCS Authors.
#ifndef DCS_TESTS_INTEGRATION_BROWSER_H_
#define DCS_TESTS_INTEGRATION_BROWSER_H_

// Pages looked at as a person would, in headless Chromium (Debian's `chromium`): whether every
// image of a page loaded, and a screenshot read back as pixels. Chromium runs without a display,
// dbus or its sandbox (--headless=new --disable-gpu --no-sandbox), with a profile of its own
// beside the page. Thread-compatible; failures are reported as test failures.

#include <cstdint>
#include <string>
#include <vector>

namespace dcs::integration {

// The chromium program on PATH; empty if it is not installed.
std::string ChromiumPath();

// Each <img> of the page `html_path` (a file), in document order, once the page has loaded:
// "<src> loaded <width>x<height>" (complete, with a natural size) or "<src> broken 0x0". Reads
// a copy of the page, written beside it as `check-<name>`, with a script that lists them.
std::vector<std::string> LoadedImages(const std::string& html_path);

struct Screenshot {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;  // row-major, 3 bytes per pixel
};

// The page `html_path` in a window of `width` x `height` pixels, saved as `png_path` and read
// back (empty if it could not be taken).
Screenshot TakeScreenshot(const std::string& html_path, const std::string& png_path, int width,
                          int height);

}  // namespace dcs::integration

#endif  // DCS_TESTS_INTEGRATION_BROWSER_H_

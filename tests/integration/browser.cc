// Copyright 2026 The DCS Authors.
#include "tests/integration/browser.h"

#include <png.h>

#include <cstdlib>
#include <filesystem>
#include <regex>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "absl/strings/str_split.h"
#include "common/atomic_file.h"
#include "gtest/gtest.h"
#include "tests/integration/test_util.h"

namespace dcs::integration {
namespace {

namespace fs = std::filesystem;

// Replaces the page's </body>: after loading, lists each image as
// "<src> loaded|broken <width>x<height>" in <pre id="image-check">.
constexpr char kImageCheck[] = R"(<script>
window.addEventListener('load', () => {
  const lines = [...document.images].map(i => i.getAttribute('src') + ' ' +
      (i.complete && i.naturalWidth > 0 ? 'loaded' : 'broken') + ' ' +
      i.naturalWidth + 'x' + i.naturalHeight);
  const pre = document.createElement('pre');
  pre.id = 'image-check';
  pre.textContent = lines.join('\n');
  document.body.appendChild(pre);
});
</script>
</body>)";

RunResult RunChromium(const fs::path& page, std::vector<std::string> args) {
  const fs::path profile = page.parent_path() / ".chromium-profile";
  std::vector<std::string> all = {
      "--headless=new", "--disable-gpu", "--no-sandbox", "--no-first-run", "--hide-scrollbars",
      // Lets the page's load handlers run before the DOM is dumped or the screenshot taken.
      "--virtual-time-budget=10000", absl::StrCat("--user-data-dir=", profile.string())};
  all.insert(all.end(), args.begin(), args.end());
  all.push_back(absl::StrCat("file://", fs::absolute(page).string()));
  RunResult result = RunProgram(ChromiumPath(), all, absl::Seconds(90));
  std::error_code ignored;
  fs::remove_all(profile, ignored);
  return result;
}

}  // namespace

std::string ChromiumPath() {
  const char* path = std::getenv("PATH");
  for (const auto dir : absl::StrSplit(path != nullptr ? path : "/usr/bin", ':')) {
    const fs::path candidate = fs::path(std::string(dir)) / "chromium";
    if (fs::exists(candidate)) return candidate.string();
  }
  return "";
}

std::vector<std::string> LoadedImages(const std::string& html_path) {
  const absl::StatusOr<std::string> page = ReadFile(html_path);
  if (!page.ok()) {
    ADD_FAILURE() << page.status();
    return {};
  }
  const fs::path check =
      fs::path(html_path).parent_path() / ("check-" + fs::path(html_path).filename().string());
  const absl::Status written =
      WriteFileAtomically(check.string(), absl::StrReplaceAll(*page, {{"</body>", kImageCheck}}));
  if (!written.ok()) {
    ADD_FAILURE() << written;
    return {};
  }
  const RunResult dom = RunChromium(check, {"--dump-dom"});
  EXPECT_EQ(dom.exit_code, 0) << dom.output;
  std::smatch match;
  if (!std::regex_search(dom.output, match,
                         std::regex(R"(<pre id="image-check">([^<]*)</pre>)"))) {
    ADD_FAILURE() << "no image check in Chromium's DOM of " << check << ":\n" << dom.output;
    return {};
  }
  return Lines(match[1].str());
}

Screenshot TakeScreenshot(const std::string& html_path, const std::string& png_path, int width,
                          int height) {
  const RunResult shot =
      RunChromium(html_path, {absl::StrCat("--window-size=", width, ",", height),
                              absl::StrCat("--screenshot=", png_path)});
  EXPECT_EQ(shot.exit_code, 0) << shot.output;
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  Screenshot screenshot;
  if (!png_image_begin_read_from_file(&png, png_path.c_str())) {
    ADD_FAILURE() << "cannot read " << png_path << ": " << png.message << "\n" << shot.output;
    return screenshot;
  }
  png.format = PNG_FORMAT_RGB;
  screenshot.rgb.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, screenshot.rgb.data(), 0, nullptr)) {
    ADD_FAILURE() << "cannot decode " << png_path << ": " << png.message;
    return {};
  }
  screenshot.width = static_cast<int>(png.width);
  screenshot.height = static_cast<int>(png.height);
  return screenshot;
}

}  // namespace dcs::integration

// Copyright 2026 The DCS Authors.
#include "common/pinned_kernels.h"

#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"

namespace dcs {
namespace {

std::string Assignment(const KernelVariable& variable) {
  return absl::StrCat(variable.name, "=", variable.value);
}

}  // namespace

std::vector<std::string> PinnedKernelEnvironment(const char* const* environment) {
  std::vector<std::string> result;
  bool placed[std::size(kPinnedKernels)] = {};
  for (; *environment != nullptr; ++environment) {
    const absl::string_view entry = *environment;
    const size_t equals = entry.find('=');
    const auto pinned = std::find_if(
        std::begin(kPinnedKernels), std::end(kPinnedKernels), [&](const KernelVariable& v) {
          return equals != absl::string_view::npos && entry.substr(0, equals) == v.name;
        });
    if (pinned == std::end(kPinnedKernels)) {
      result.emplace_back(entry);
      continue;
    }
    // A second entry of one name is dropped: getenv would read the first, but another reader
    // might take the last.
    const size_t i = pinned - std::begin(kPinnedKernels);
    if (!placed[i]) result.push_back(Assignment(*pinned));
    placed[i] = true;
  }
  for (size_t i = 0; i < std::size(kPinnedKernels); ++i) {
    if (!placed[i]) result.push_back(Assignment(kPinnedKernels[i]));
  }
  return result;
}

}  // namespace dcs

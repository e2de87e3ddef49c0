// Copyright 2026 The DCS Authors.
#include "run/config_errors.h"

#include "absl/strings/str_cat.h"

namespace dcs::run {

absl::Status ConfigErrors::At(absl::string_view path, absl::string_view message) const {
  std::string text;
  if (!where_.empty()) absl::StrAppend(&text, where_, ": ");
  const bool mapped = shown_path_ != nullptr && *shown_path_;
  absl::StrAppend(&text, mapped ? (*shown_path_)(path) : std::string(path), ": ");
  if (lines_ != nullptr) {
    if (auto it = lines_->find(std::string(path)); it != lines_->end()) {
      absl::StrAppend(&text, "line ", it->second, ": ");
    }
  }
  absl::StrAppend(&text, message);
  return absl::InvalidArgumentError(text);
}

std::string ItemPath(absl::string_view path, size_t index) {
  return absl::StrCat(path, "[", index, "]");
}

std::string KeyPath(absl::string_view path, absl::string_view key) {
  return path.empty() ? std::string(key) : absl::StrCat(path, ".", key);
}

}  // namespace dcs::run

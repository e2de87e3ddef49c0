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

void ConfigProblems::Add(const absl::Status& status) {
  if (status.ok()) return;
  ++reported_;
  if (seen_.emplace(status.message()).second) problems_.push_back(status);
}

absl::Status ConfigProblems::ToStatus(absl::string_view where) const {
  if (problems_.empty()) return absl::OkStatus();
  if (problems_.size() == 1) return problems_[0];
  std::string text = absl::StrCat(problems_.size(), " problems",
                                  where.empty() ? "" : absl::StrCat(" in ", where), ":");
  for (const absl::Status& problem : problems_) absl::StrAppend(&text, "\n  ", problem.message());
  return absl::InvalidArgumentError(text);
}

std::string ItemPath(absl::string_view path, size_t index) {
  return absl::StrCat(path, "[", index, "]");
}

std::string KeyPath(absl::string_view path, absl::string_view key) {
  return path.empty() ? std::string(key) : absl::StrCat(path, ".", key);
}

}  // namespace dcs::run

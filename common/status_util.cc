// Copyright 2026 The DCS Authors.
#include "common/status_util.h"

#include "absl/strings/str_cat.h"

namespace dcs {
namespace {

constexpr char kFieldPayload[] = "type.dcs.dev/dcs.Field";

}  // namespace

absl::Status Annotate(const absl::Status& status, absl::string_view context) {
  if (status.ok()) return status;
  absl::Status annotated(status.code(), absl::StrCat(context, ": ", status.message()));
  status.ForEachPayload([&annotated](absl::string_view type_url, const absl::Cord& payload) {
    annotated.SetPayload(type_url, payload);
  });
  return annotated;
}

absl::Status ErrorInField(absl::Status status, absl::string_view field) {
  if (status.ok()) return status;
  const std::optional<std::string> inner = ErrorField(status);
  status.SetPayload(kFieldPayload,
                    absl::Cord(inner.has_value() ? absl::StrCat(field, ".", *inner)
                                                 : std::string(field)));
  return status;
}

std::optional<std::string> ErrorField(const absl::Status& status) {
  const auto field = status.GetPayload(kFieldPayload);  // absl::optional: Debian's abseil
  if (!field.has_value()) return std::nullopt;
  return std::string(*field);
}

}  // namespace dcs

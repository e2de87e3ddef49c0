// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_PIECES_H_
#define DCS_SERVICES_PIECES_H_

// Payloads larger than one gRPC message (its limit is 4 MiB: an image policy's weights, a slot's
// rollout of images, a checkpoint) travel over a stream in pieces of at most kPieceBytes. A
// streamed message carries a `bytes` field for them: the first message of the stream carries
// every other field (the header) and the first piece; each further message one more piece. The
// receiver joins the pieces in order (PieceJoiner) and parses the whole once the stream ends.
// Thread-compatible (plain functions and one class per stream).

#include <string>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"

namespace dcs::services {

inline constexpr size_t kPieceBytes = size_t{1} << 20;
// The most one stream's pieces may add up to.
inline constexpr size_t kMaxStreamedBytes = size_t{1} << 30;

// `bytes` in consecutive pieces of at most kPieceBytes; one empty piece for empty bytes.
std::vector<absl::string_view> SplitIntoPieces(absl::string_view bytes);

// The messages of a stream carrying `header` and `payload`: `piece` is the payload field's
// mutable accessor (e.g. &v1::PushRolloutRequest::mutable_data).
template <typename Message>
std::vector<Message> CutIntoMessages(Message header, absl::string_view payload,
                                     std::string* (Message::*piece)()) {
  std::vector<Message> messages;
  for (absl::string_view bytes : SplitIntoPieces(payload)) {
    Message& message = messages.emplace_back();
    if (messages.size() == 1) message = std::move(header);
    (message.*piece)()->assign(bytes.data(), bytes.size());
  }
  return messages;
}

// Joins the messages of one stream, in order: the first becomes the header, every piece is
// appended to the payload. `what` names the payload in errors.
template <typename Message>
class PieceJoiner {
 public:
  PieceJoiner(std::string* (Message::*piece)(), std::string what,
              size_t max_bytes = kMaxStreamedBytes)
      : piece_(piece), what_(std::move(what)), max_bytes_(max_bytes) {}

  // Takes the stream's next message. RESOURCE_EXHAUSTED once the pieces pass max_bytes.
  absl::Status Add(Message message) {
    std::string* bytes = (message.*piece_)();
    if (payload_.size() + bytes->size() > max_bytes_) {
      return absl::ResourceExhaustedError(
          absl::StrCat(what_, " is larger than ", max_bytes_, " bytes"));
    }
    payload_.append(*bytes);
    if (!started_) {
      bytes->clear();
      header_ = std::move(message);
      started_ = true;
    }
    return absl::OkStatus();
  }

  // Whether a message came.
  bool started() const { return started_; }
  // The first message, without its piece.
  Message& header() { return header_; }
  // The pieces so far, joined.
  std::string& payload() { return payload_; }

  // `payload()` parsed as `Whole`. INVALID_ARGUMENT, naming the payload, if it does not parse.
  template <typename Whole>
  absl::Status Parse(Whole& whole) const {
    if (!whole.ParseFromString(payload_)) {
      return absl::InvalidArgumentError(absl::StrCat(what_, " (", payload_.size(),
                                                     " bytes in pieces) does not parse"));
    }
    return absl::OkStatus();
  }

 private:
  std::string* (Message::*const piece_)();
  const std::string what_;
  const size_t max_bytes_;
  bool started_ = false;
  Message header_;
  std::string payload_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_PIECES_H_

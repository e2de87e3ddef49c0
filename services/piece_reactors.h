// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_PIECE_REACTORS_H_
#define DCS_SERVICES_PIECE_REACTORS_H_

// The server side of the streams that carry a message in pieces (services/pieces.h): a writer
// of pieces made ahead, and a reader that joins a client's pieces and hands the whole to the
// service's work pool (services/served_calls.h). Each is owned by gRPC from construction until
// OnDone, and deletes itself there.

#include <grpcpp/support/server_callback.h>

#include <functional>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "services/grpc_status.h"
#include "services/pieces.h"
#include "services/served_calls.h"

namespace dcs::services {

// A server stream writing pieces made after the call came (on the pool, or by a parked call)
// in order, or finishing at once with an error.
template <typename Piece>
class PiecesWriter final : public grpc::ServerWriteReactor<Piece> {
 public:
  // Writes nothing until Start, which may come from any thread. REQUIRES: called once.
  void Start(absl::StatusOr<std::vector<Piece>> pieces) {
    if (!pieces.ok()) {
      this->Finish(ToGrpcStatus(pieces.status()));
      return;
    }
    pieces_ = *std::move(pieces);
    WriteNext();
  }

  void OnWriteDone(bool ok) override {
    if (!ok) {
      this->Finish(grpc::Status(grpc::StatusCode::CANCELLED, "the stream broke"));
      return;
    }
    WriteNext();
  }

  void OnDone() override { delete this; }

 private:
  void WriteNext() {
    if (next_ == pieces_.size()) {
      this->Finish(grpc::Status::OK);
      return;
    }
    this->StartWrite(&pieces_[next_++]);
  }

  std::vector<Piece> pieces_;
  size_t next_ = 0;
};

// A server stream of the pieces `make` (absl::StatusOr<std::vector<Piece>>()) returns on
// `calls`' pool; `count` sees their status (or the pool's refusal) first. Both must be
// copyable and hold what they read by value.
template <typename Piece, typename Make, typename Count>
PiecesWriter<Piece>* WritePiecesFromPool(ServedCalls& calls, Make make, Count count) {
  auto* writer = new PiecesWriter<Piece>();
  calls.Offload(std::move(make), [writer, count](absl::StatusOr<std::vector<Piece>> pieces) {
    count(pieces.status());
    writer->Start(std::move(pieces));
  });
  return writer;
}

// A client stream of a header and a payload in pieces, handed whole to `complete` on the
// pool once the client has sent them all; `count` sees the call's status before it finishes.
template <typename Request>
class JoiningReader final : public grpc::ServerReadReactor<Request> {
 public:
  using Complete = std::function<absl::Status(PieceJoiner<Request>&)>;
  using Count = std::function<void(const absl::Status&)>;

  // Borrows `calls` (must outlive the call).
  JoiningReader(ServedCalls& calls, PieceJoiner<Request> joiner, Complete complete, Count count)
      : calls_(calls),
        joiner_(std::move(joiner)),
        complete_(std::move(complete)),
        count_(std::move(count)) {
    this->StartRead(&request_);
  }

  void OnReadDone(bool ok) override {
    if (ok) {  // a piece
      const absl::Status added = joiner_.Add(std::move(request_));
      if (added.ok()) {
        this->StartRead(&request_);
      } else {
        End(added);
      }
      return;
    }
    // The client sent every piece. An empty stream is also what a stream looks like here when
    // gRPC ended it for a message over its limit (the client is told RESOURCE_EXHAUSTED).
    if (!joiner_.started()) {
      End(absl::InvalidArgumentError("the stream was empty"));
      return;
    }
    calls_.Offload([this] { return complete_(joiner_); },
                   [this](const absl::Status& status) { End(status); });
  }

  void OnDone() override { delete this; }

 private:
  void End(const absl::Status& status) {
    count_(status);
    this->Finish(ToGrpcStatus(status));
  }

  ServedCalls& calls_;
  PieceJoiner<Request> joiner_;
  const Complete complete_;
  const Count count_;
  Request request_;
};

}  // namespace dcs::services

#endif  // DCS_SERVICES_PIECE_REACTORS_H_

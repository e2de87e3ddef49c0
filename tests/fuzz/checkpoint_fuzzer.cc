// Copyright 2026 The DCS Authors.
// Fuzzes the checkpoint loader (run/run_checkpoint.h) as a checkpoint reaches it: a packed
// checkpoint arriving from a learner (UnpackCheckpoint), and a checkpoint directory read back
// from disk (ReadLatestCheckpoint). The input is the checkpoint's name (its first line) and its
// run.yaml (the rest); the learner state, opaque to the loader, is fixed, and the SHA-256s are
// computed here so that the input reaches the decoder rather than the checksum test. The seeds
// are real checkpoints' run.yaml.
// Asserts: every input unpacks or gives DATA_LOSS or INVALID_ARGUMENT (the header's errors);
// what unpacks packs and unpacks again to the same run state (what a learner stores is what
// the next one loads); written to a directory, it reads back the same, and what does not
// unpack but has a checkpoint's name reads back only as DATA_LOSS.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "absl/status/statusor.h"
#include "absl/strings/str_cat.h"
#include "run/run_checkpoint.h"
#include "tests/fuzz/fuzz_check.h"
#include "tests/fuzz/scratch_dir.h"

namespace dcs::fuzz {
namespace {

// What the run state of `checkpoint` reads as, to compare two.
std::string StateText(const run::Checkpoint& checkpoint) {
  return run::EncodeRunState(checkpoint.state);
}

void FuzzCheckpoint(const std::string& input) {
  const size_t newline = input.find('\n');
  run::PackedCheckpoint packed{
      .name = input.substr(0, newline),
      .learner = "learner state",
      .run_state = newline == std::string::npos ? "" : input.substr(newline + 1)};
  packed.learner_sha256 = run::Sha256Hex(packed.learner);
  packed.run_state_sha256 = run::Sha256Hex(packed.run_state);

  const absl::StatusOr<run::Checkpoint> unpacked = run::UnpackCheckpoint(packed);
  if (!unpacked.ok()) {
    DCS_FUZZ_CHECK(
        absl::IsDataLoss(unpacked.status()) || absl::IsInvalidArgument(unpacked.status()),
        unpacked.status());
  } else {
    const absl::StatusOr<run::Checkpoint> again =
        run::UnpackCheckpoint(run::PackCheckpoint(*unpacked));
    DCS_FUZZ_CHECK(again.ok(), again.status());
    DCS_FUZZ_CHECK(StateText(*again) == StateText(*unpacked), absl::OkStatus());
  }

  // The directory: only a checkpoint's name can be written (WritePackedCheckpoint REQUIRES it).
  if (!run::CheckPackedCheckpoint(packed).ok()) return;
  const std::string run_dir = absl::StrCat(ScratchDir(), "/run");
  std::error_code error;
  std::filesystem::remove_all(run_dir, error);
  const absl::Status written = run::WritePackedCheckpoint(run_dir, packed, /*keep=*/1);
  DCS_FUZZ_CHECK(written.ok(), written);
  const absl::StatusOr<run::Checkpoint> read = run::ReadLatestCheckpoint(run_dir);
  if (unpacked.ok()) {
    DCS_FUZZ_CHECK(read.ok(), read.status());
    DCS_FUZZ_CHECK(StateText(*read) == StateText(*unpacked), absl::OkStatus());
  } else if (!read.ok()) {
    DCS_FUZZ_CHECK(absl::IsDataLoss(read.status()), read.status());
  }
}

}  // namespace
}  // namespace dcs::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  dcs::fuzz::FuzzCheckpoint(std::string(reinterpret_cast<const char*>(data), size));
  return 0;
}

// Copyright 2026 The DCS Authors.
#include "services/cli/detach.h"

#include <atomic>
#include <csignal>

namespace dcs::services::cli {
namespace {

std::atomic<bool> detach_requested{false};
extern "C" void RequestDetach(int) { detach_requested = true; }

}  // namespace

DetachOnInterrupt::DetachOnInterrupt() {
  detach_requested = false;
  std::signal(SIGINT, RequestDetach);
  std::signal(SIGTERM, RequestDetach);
}

DetachOnInterrupt::~DetachOnInterrupt() {
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

bool DetachOnInterrupt::requested() const { return detach_requested.load(); }

}  // namespace dcs::services::cli

// Copyright 2026 The DCS Authors.
#include "learner/torch_runtime.h"

#include <ATen/Context.h>
#include <ATen/Parallel.h>
#include <ATen/Version.h>
#include <c10/util/Exception.h>
#include <dlfcn.h>
#include <torch/version.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "common/atomic_file.h"
#include "common/exec_array.h"
#include "common/status_macros.h"

namespace dcs::learner {
namespace {

constexpr absl::string_view kNoMatch = "results will not match other machines' bit for bit";

std::string OrUnknown(std::string name) { return name.empty() ? "unknown" : name; }

// The arguments this process was started with, empty ones included.
absl::StatusOr<std::vector<std::string>> OwnArguments() {
  DCS_ASSIGN_OR_RETURN(std::string text, ReadFile("/proc/self/cmdline"));
  // Each argument ends with a NUL.
  if (!text.empty() && text.back() == '\0') text.pop_back();
  return std::vector<std::string>(absl::StrSplit(text, '\0'));
}

std::string FormatVariables(const std::vector<KernelVariable>& variables) {
  return absl::StrJoin(variables, " ", [](std::string* out, const KernelVariable& variable) {
    absl::StrAppend(out, variable.name, "=", variable.value);
  });
}

// Runs this program again with the pinned kernels set, silently (what it runs with is in every
// run's summary and a learner's registration). Returns only if that failed, with the reason.
std::string RestartPinned() {
  absl::StatusOr<std::vector<std::string>> arguments = OwnArguments();
  if (!arguments.ok()) return std::string(arguments.status().message());
  std::vector<std::string> environment = PinnedKernelEnvironment(environ);
  const std::vector<char*> argv = ExecArray(*arguments);
  const std::vector<char*> envp = ExecArray(environment);
  execve("/proc/self/exe", argv.data(), envp.data());
  return std::strerror(errno);
}

// OpenBLAS's function `name`, or null if the BLAS is not OpenBLAS. Looked up rather than linked:
// libtorch reaches OpenBLAS through the libblas.so.3 alternative, which may be another BLAS.
template <typename Function>
Function* OpenBlasFunction(const char* name) {
  return reinterpret_cast<Function*>(dlsym(RTLD_DEFAULT, name));
}

// OpenBLAS's build: "serial", "pthread" or "openmp"; empty if the BLAS is not OpenBLAS.
std::string BlasBuild() {
  const auto parallel = OpenBlasFunction<int()>("openblas_get_parallel");  // 0, 1 or 2
  if (parallel == nullptr) return "";
  switch (parallel()) {
    case 0:
      return "serial";
    case 1:
      return "pthread";
    default:
      return "openmp";
  }
}

}  // namespace

absl::Status PinTorchThreads(int threads) {
  if (threads < 1) {
    return absl::InvalidArgumentError(
        absl::StrCat("torch threads must be at least 1, got ", threads));
  }
  // libtorch reports misuse with c10::Error; no exception leaves this library.
  try {
    // Inter-op first: it is the call that can be refused, and a refused call changes nothing.
    at::set_num_interop_threads(threads);
    at::set_num_threads(threads);
  } catch (const c10::Error& e) {
    return absl::FailedPreconditionError(
        absl::StrCat("cannot size libtorch's thread pools: ", e.what_without_backtrace()));
  }
  return absl::OkStatus();
}

std::vector<KernelVariable> UnpinnedKernelVariables() {
  std::vector<KernelVariable> unpinned;
  for (const KernelVariable& pinned : kPinnedKernels) {
    const char* value = std::getenv(pinned.name);
    if (value == nullptr || std::strcmp(value, pinned.value) != 0) unpinned.push_back(pinned);
  }
  return unpinned;
}

void PinNumericKernels(absl::FunctionRef<void(absl::string_view)> note) {
  const std::vector<KernelVariable> unpinned = UnpinnedKernelVariables();
  if (unpinned.empty()) return;
  const std::string failure = RestartPinned();
  note(absl::StrCat("cannot restart with ", FormatVariables(unpinned), " (", failure,
                    "); going on with the kernels the libraries chose: ", kNoMatch));
}

absl::Mutex* BlasMutex() {
  ABSL_CONST_INIT static absl::Mutex mutex(absl::kConstInit);
  static const bool locks_itself = [] {
    const std::string build = BlasBuild();
    return build == "pthread" || build == "openmp";
  }();
  return locks_itself ? nullptr : &mutex;
}

std::string BlasCoreName() {
  const auto core_name = OpenBlasFunction<char*()>("openblas_get_corename");
  return core_name == nullptr ? "" : core_name();
}

std::string AtenCpuCapability() {
  // libtorch 1.13 exports no reader of its dispatch level (at::native::get_cpu_capability,
  // declared in ATen/native/DispatchStub.h, is hidden in libtorch_cpu.so), but show_config
  // prints the level dispatch uses, once computed from ATEN_CPU_CAPABILITY and the CPU:
  // "CPU capability usage: AVX2" ("NO AVX", "AVX2" or "AVX512").
  constexpr absl::string_view kLabel = "CPU capability usage: ";
  const std::string config = at::show_config();
  absl::string_view usage = config;
  const size_t start = usage.find(kLabel);
  if (start == absl::string_view::npos) return "";
  usage.remove_prefix(start + kLabel.size());
  usage = usage.substr(0, usage.find('\n'));
  if (usage == "NO AVX") return "default";
  return absl::AsciiStrToLower(usage);
}

std::string NumericFingerprint() {
  return absl::StrCat("libtorch ", TORCH_VERSION, ", openblas ", OrUnknown(BlasCoreName()),
                      ", aten ", OrUnknown(AtenCpuCapability()));
}

std::vector<LibraryVersion> LibraryVersions() {
  std::vector<LibraryVersion> versions = {{"libtorch", TORCH_VERSION}};
  if (const std::string core = BlasCoreName(); !core.empty()) {
    versions.push_back({"openblas core", core});
    const int threads = OpenBlasFunction<int()>("openblas_get_num_threads")();
    versions.push_back({"openblas build", absl::StrCat(BlasBuild(), ", ", threads, " thread",
                                                       threads == 1 ? "" : "s")});
  }
  if (const std::string capability = AtenCpuCapability(); !capability.empty()) {
    versions.push_back({"aten cpu capability", capability});
  }
  return versions;
}

}  // namespace dcs::learner

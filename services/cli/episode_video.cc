// Copyright 2026 The DCS Authors.
#include "services/cli/episode_video.h"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_replace.h"
#include "absl/strings/strip.h"
#include "absl/time/time.h"
#include "common/atomic_file.h"
#include "common/status_macros.h"

namespace dcs::services::cli {
namespace {

namespace fs = std::filesystem;

constexpr char kFrames[] = "frames.mkv";  // lossless (FFV1), in the temporary directory
constexpr char kSubtitles[] = "overlay.ass";
constexpr char kPalette[] = "palette.png";
constexpr char kLog[] = "ffmpeg.log";
constexpr size_t kMaxQuotedOutput = 2000;  // bytes of ffmpeg's output an error quotes
constexpr absl::Duration kFfmpegTimeout = absl::Minutes(10);

// White text on a box of 75% opaque black (BorderStyle 3 draws OutlineColour as a box), top
// left (Alignment 7), in pixels of the frame (PlayRes is the frame's size).
constexpr char kSubtitleHeader[] = R"([Script Info]
ScriptType: v4.00+
PlayResX: %d
PlayResY: %d
WrapStyle: 2
ScaledBorderAndShadow: yes

[V4+ Styles]
Format: Name, Fontname, Fontsize, PrimaryColour, SecondaryColour, OutlineColour, BackColour, )"
    R"(Bold, Italic, Underline, StrikeOut, ScaleX, ScaleY, Spacing, Angle, BorderStyle, Outline, )"
    R"(Shadow, Alignment, MarginL, MarginR, MarginV, Encoding
Style: Overlay,DejaVu Sans Mono,20,&H00FFFFFF,&H00FFFFFF,&H40000000,&H40000000,0,0,0,0,100,100,)"
    R"(0,0,3,4,0,7,10,10,10,1

[Events]
Format: Layer, Start, End, Style, Name, MarginL, MarginR, MarginV, Effect, Text
)";

// A time in hundredths of a second as ASS writes it: H:MM:SS.cc.
std::string AssTime(int64_t centiseconds) {
  return absl::StrFormat("%d:%02d:%02d.%02d", centiseconds / 360000, centiseconds / 6000 % 60,
                         centiseconds / 100 % 60, centiseconds % 100);
}

std::string Quote(absl::string_view output) {
  output = absl::StripAsciiWhitespace(output);
  if (output.empty()) return "(no output)";
  if (output.size() <= kMaxQuotedOutput) return std::string(output);
  return absl::StrCat("...", output.substr(output.size() - kMaxQuotedOutput));
}

// `path`'s temporary name while ffmpeg writes it: hidden, beside it.
std::string PartialName(const std::string& path) {
  const fs::path p(path);
  return (p.parent_path() / absl::StrCat(".", p.filename().string(), ".partial")).string();
}

absl::Status CheckOutput(const std::string& path, absl::string_view flag,
                         std::initializer_list<absl::string_view> extensions) {
  for (absl::string_view extension : extensions) {
    if (absl::EndsWith(path, extension) && path.size() > extension.size()) {
      return absl::OkStatus();
    }
  }
  return absl::InvalidArgumentError(absl::StrCat(flag, ": '", path, "' should end in ",
                                                 absl::StrJoin(extensions, " or ")));
}

}  // namespace

absl::StatusOr<EpisodeVideo> EpisodeVideo::Start(EpisodeVideoOptions options) {
  if (options.video.empty() && options.strip.empty()) {
    return absl::InvalidArgumentError("nothing to write: give --out NAME.mp4 (or .gif), --strip "
                                      "NAME.png, or both");
  }
  if (!options.video.empty()) DCS_RETURN_IF_ERROR(CheckOutput(options.video, "--out",
                                                              {".mp4", ".gif"}));
  if (!options.strip.empty()) DCS_RETURN_IF_ERROR(CheckOutput(options.strip, "--strip",
                                                              {".png"}));
  if (options.width <= 0 || options.height <= 0 || options.width % 2 != 0 ||
      options.height % 2 != 0 || options.fps <= 0 || 100 % options.fps != 0 ||
      options.strip_frames < 2) {
    return absl::InvalidArgumentError(absl::StrCat(
        "cannot record ", options.width, "x", options.height, " frames at ", options.fps,
        " fps in a strip of ", options.strip_frames));
  }
  const std::optional<std::string> ffmpeg = FindProgram(options.ffmpeg);
  if (!ffmpeg.has_value()) {
    return absl::FailedPreconditionError(absl::StrCat(
        "ffmpeg ('", options.ffmpeg, "') is not installed or not on PATH: install Debian's "
        "ffmpeg package (apt-get install ffmpeg)"));
  }
  std::string work_dir = (fs::temp_directory_path() / "dcs-play-XXXXXX").string();
  if (::mkdtemp(work_dir.data()) == nullptr) {
    return absl::PermissionDeniedError(
        absl::StrCat("cannot make a temporary directory ", work_dir, ": ", std::strerror(errno)));
  }
  absl::StatusOr<ChildProcess> encoder = ChildProcess::Start(
      {.path = *ffmpeg,
       .args = {"-hide_banner", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgb24",
                "-video_size", absl::StrCat(options.width, "x", options.height), "-framerate",
                absl::StrCat(options.fps), "-i", "pipe:0", "-c:v", "ffv1", kFrames},
       .output_path = (fs::path(work_dir) / kLog).string(),
       .working_directory = work_dir,
       .pipe_input = true});
  if (!encoder.ok()) {
    std::error_code ignored;
    fs::remove_all(work_dir, ignored);
    return absl::FailedPreconditionError(absl::StrCat(
        encoder.status().message(), ": install Debian's ffmpeg package (apt-get install "
        "ffmpeg)"));
  }
  std::string subtitles = absl::StrFormat(kSubtitleHeader, options.width, options.height);
  EpisodeVideo video(std::move(options), *ffmpeg, std::move(work_dir), *std::move(encoder));
  video.subtitles_ = std::move(subtitles);
  return video;
}

EpisodeVideo::~EpisodeVideo() {
  encoder_.reset();
  if (!work_dir_.empty()) {
    std::error_code ignored;
    fs::remove_all(work_dir_, ignored);
  }
}

absl::Status EpisodeVideo::AddFrame(std::span<const uint8_t> rgb, const std::string& text) {
  if (!encoder_.has_value()) return absl::FailedPreconditionError("the video is finished");
  if (absl::Status written = encoder_->WriteInput(rgb); !written.ok()) {
    encoder_.reset();
    return absl::InternalError(
        absl::StrCat("ffmpeg stopped taking frames: ",
                     Quote(ReadFile((fs::path(work_dir_) / kLog).string()).value_or(""))));
  }
  const int64_t centiseconds_per_frame = 100 / options_.fps;
  absl::StrAppend(&subtitles_, "Dialogue: 0,", AssTime(frames_ * centiseconds_per_frame), ",",
                  AssTime((frames_ + 1) * centiseconds_per_frame), ",Overlay,,0,0,0,,",
                  absl::StrReplaceAll(text, {{"\n", "\\N"}}), "\n");
  ++frames_;
  return absl::OkStatus();
}

absl::Status EpisodeVideo::RunFfmpeg(const std::vector<std::string>& args,
                                     const std::string& what) const {
  const std::string log = (fs::path(work_dir_) / kLog).string();
  std::error_code ignored;
  fs::remove(log, ignored);
  std::vector<std::string> all = {"-nostdin", "-hide_banner", "-loglevel", "error", "-y"};
  all.insert(all.end(), args.begin(), args.end());
  DCS_ASSIGN_OR_RETURN(ChildProcess child,
                       ChildProcess::Start({.path = ffmpeg_,
                                            .args = std::move(all),
                                            .output_path = log,
                                            .working_directory = work_dir_}));
  const std::optional<int> status = child.Wait(kFfmpegTimeout);
  if (!status.has_value()) {
    return absl::DeadlineExceededError(absl::StrCat(
        "ffmpeg took more than ", absl::FormatDuration(kFfmpegTimeout), " writing ", what));
  }
  if (!WIFEXITED(*status) || WEXITSTATUS(*status) != 0) {
    return absl::InternalError(absl::StrCat("ffmpeg failed writing ", what, " (",
                                            DescribeExit(*status), "): ",
                                            Quote(ReadFile(log).value_or(""))));
  }
  return absl::OkStatus();
}

absl::Status EpisodeVideo::Finish() {
  if (!encoder_.has_value()) return absl::FailedPreconditionError("the video is finished");
  if (frames_ == 0) return absl::FailedPreconditionError("a video needs a frame");
  encoder_->CloseInput();
  const std::optional<int> encoded = encoder_->Wait(kFfmpegTimeout);
  encoder_.reset();
  if (!encoded.has_value() || !WIFEXITED(*encoded) || WEXITSTATUS(*encoded) != 0) {
    return absl::InternalError(
        absl::StrCat("ffmpeg failed encoding the frames: ",
                     Quote(ReadFile((fs::path(work_dir_) / kLog).string()).value_or(""))));
  }
  DCS_RETURN_IF_ERROR(
      WriteFileAtomically((fs::path(work_dir_) / kSubtitles).string(), subtitles_));
  // "null" passes the frames on unchanged.
  const std::string overlay = options_.overlay ? absl::StrCat("subtitles=", kSubtitles) : "null";

  std::vector<std::pair<std::string, std::string>> written;  // partial name, final name
  const auto write = [&](const std::string& output, std::vector<std::string> args) {
    written.emplace_back(PartialName(output), output);
    args.push_back(fs::absolute(written.back().first).string());
    return RunFfmpeg(args, output);
  };
  absl::Status status = absl::OkStatus();
  if (absl::EndsWith(options_.video, ".mp4")) {
    status = write(options_.video, {"-i", kFrames, "-vf", overlay, "-c:v", "libx264", "-preset",
                                    "veryfast", "-crf", "20", "-pix_fmt", "yuv420p", "-movflags",
                                    "+faststart", "-f", "mp4"});
  } else if (absl::EndsWith(options_.video, ".gif")) {
    // A palette of the whole episode first: palettegen in the same graph would hold every
    // frame in memory until the end.
    status = RunFfmpeg({"-i", kFrames, "-vf", absl::StrCat(overlay, ",palettegen"), kPalette},
                       "the GIF's palette");
    if (status.ok()) {
      status = write(options_.video,
                     {"-i", kFrames, "-i", kPalette, "-filter_complex",
                      absl::StrCat("[0:v]", overlay, "[v];[v][1:v]paletteuse"), "-f", "gif"});
    }
  }
  if (status.ok() && !options_.strip.empty()) {
    std::vector<std::string> chosen;  // frame n = round(k (frames - 1) / (strip_frames - 1))
    for (int k = 0; k < options_.strip_frames; ++k) {
      const int64_t n = (2 * int64_t{k} * (frames_ - 1) + options_.strip_frames - 1) /
                        (2 * (options_.strip_frames - 1));
      chosen.push_back(absl::StrCat("eq(n,", n, ")"));
    }
    status = write(options_.strip,
                   {"-i", kFrames, "-vf",
                    absl::StrCat("select='", absl::StrJoin(chosen, "+"), "',", overlay,
                                 ",tile=", options_.strip_frames, "x1"),
                    "-frames:v", "1", "-update", "1", "-c:v", "png", "-f", "image2"});
  }
  for (const auto& [partial, output] : written) {
    std::error_code error;
    if (status.ok()) {
      fs::rename(partial, output, error);
      if (error) {
        status = absl::PermissionDeniedError(
            absl::StrCat("cannot write ", output, ": ", error.message()));
      }
    }
    if (!status.ok()) fs::remove(partial, error);
  }
  return status;
}

}  // namespace dcs::services::cli

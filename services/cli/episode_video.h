// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_EPISODE_VIDEO_H_
#define DCS_SERVICES_CLI_EPISODE_VIDEO_H_

// An episode's frames made into a video and a frame strip by ffmpeg (Debian's package), for
// `dcs play`. Frames stream as raw RGB into an ffmpeg child that keeps them losslessly in a
// temporary directory; each frame's text goes into a subtitle file there (one ASS cue per
// frame, top left, white on a dark box), which Finish burns into every output with ffmpeg's
// `subtitles` filter (libass, its font found by fontconfig):
//   - the video: H.264 in MP4 (.mp4) or a GIF with a palette made for it (.gif), one frame per
//     frame added, at the frame rate given;
//   - the strip: `strip_frames` frames spread evenly over the episode (the first and the last
//     among them), side by side in one PNG, strip_frames x width by height.
// Each output is written under a temporary name beside it and renamed when complete, so an
// error leaves no partial file; the temporary directory goes with the recorder.
// Thread-compatible.

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "services/cli/child_process.h"

namespace dcs::services::cli {

struct EpisodeVideoOptions {
  std::string video;      // NAME.mp4 or NAME.gif; empty: none
  std::string strip;      // NAME.png; empty: none
  int strip_frames = 5;   // >= 2
  int width = 0;          // of every frame; even
  int height = 0;
  int fps = 50;           // a divisor of 100 (subtitle times are in hundredths of a second)
  bool overlay = true;    // false: the frames as added, their text ignored
  std::string ffmpeg = "ffmpeg";  // a path, or a name looked up on PATH
};

class EpisodeVideo {
 public:
  // Checks the options and starts ffmpeg. FAILED_PRECONDITION if ffmpeg cannot be found or
  // run, naming Debian's package; INVALID_ARGUMENT for no output, an output's extension other
  // than the above, or bad sizes; the error of making the temporary directory.
  static absl::StatusOr<EpisodeVideo> Start(EpisodeVideoOptions options);

  EpisodeVideo(EpisodeVideo&& other) noexcept = default;
  EpisodeVideo& operator=(EpisodeVideo&&) = delete;
  ~EpisodeVideo();  // stops ffmpeg if still running; removes the temporary directory

  // Adds the next frame: `rgb` holds width x height pixels, row by row; `text` is its overlay,
  // lines separated by '\n'. INTERNAL quoting ffmpeg's output if it has stopped.
  absl::Status AddFrame(std::span<const uint8_t> rgb, const std::string& text);

  // Writes the outputs from the frames added (at least one). INTERNAL quoting ffmpeg's output
  // if it fails; the error of renaming an output into place.
  absl::Status Finish();

 private:
  EpisodeVideo(EpisodeVideoOptions options, std::string ffmpeg, std::string work_dir,
               ChildProcess encoder)
      : options_(std::move(options)),
        ffmpeg_(std::move(ffmpeg)),
        work_dir_(std::move(work_dir)),
        encoder_(std::move(encoder)) {}

  // Runs ffmpeg with `args` in the temporary directory to completion.
  absl::Status RunFfmpeg(const std::vector<std::string>& args, const std::string& what) const;
  // Runs ffmpeg writing `output` from the lossless frames through `filter`: to a temporary
  // name beside `output`, renamed into place once ffmpeg succeeds.
  absl::Status WriteOutput(const std::string& output, const std::string& filter,
                           const std::vector<std::string>& encoding) const;

  EpisodeVideoOptions options_;
  std::string ffmpeg_;    // its absolute path
  std::string work_dir_;  // the lossless frames, the subtitles and ffmpeg's output
  std::optional<ChildProcess> encoder_;  // the ffmpeg taking frames; reset once finished
  std::string subtitles_;  // the ASS events so far
  int frames_ = 0;
};

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_EPISODE_VIDEO_H_

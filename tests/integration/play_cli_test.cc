// Copyright 2026 The DCS Authors.
//
// `dcs play` as a user runs it, on a tiny run of each environment trained by `dcs train`: the
// video holds one frame per step plus the reset's, 600x400, not blank, with the overlay drawn
// (the same frames without it differ in the overlay's box only); the strip is strip_frames
// frames wide. Bad input: ffmpeg missing names the package; an unknown feature or a value
// outside the feature's range is one error line, as `dcs train` words it, and writes nothing.
// Videos are read back with ffprobe and ffmpeg; without them the test is skipped.

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"
#include "common/atomic_file.h"
#include "gmock/gmock.h"
#include "gtest/gtest.h"
#include "services/cli/child_process.h"
#include "tests/integration/test_util.h"
#include "tests/testing/scoped_variable.h"
#include "tests/testing/temp_dir.h"

namespace dcs::integration {
namespace {

namespace fs = std::filesystem;
using dcs::testing::MakeTempDir;
using dcs::testing::ScopedVariable;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::SizeIs;

constexpr int kWidth = 600;
constexpr int kHeight = 400;
constexpr int kStripFrames = 4;
// Where the overlay's text box may be: the frame's top left (two lines of 20-pixel text).
constexpr int kBoxWidth = 420;
constexpr int kBoxHeight = 70;

RunResult Dcs(const std::vector<std::string>& args) {
  return RunProgram(BinaryPath("dcs"), args, absl::Minutes(3));
}

struct Image {
  int width = 0;
  int height = 0;
  std::string rgb;  // row by row

  int at(int x, int y, int channel) const {
    return static_cast<uint8_t>(rgb[3 * (static_cast<size_t>(y) * width + x) + channel]);
  }
};

// The episode's steps from `dcs play`'s line "... in T steps (T + 1 frames)".
int PlayedSteps(const std::string& output) {
  std::smatch match;
  if (!std::regex_search(output, match, std::regex("in (\\d+) steps \\((\\d+) frames\\)"))) {
    ADD_FAILURE() << "no episode length in: " << output;
    return -1;
  }
  return std::stoi(match[1]);
}

double StandardDeviation(const Image& image) {
  double sum = 0;
  double squares = 0;
  for (char c : image.rgb) {
    const double value = static_cast<uint8_t>(c);
    sum += value;
    squares += value * value;
  }
  const double n = static_cast<double>(image.rgb.size());
  return std::sqrt(std::max(0.0, squares / n - (sum / n) * (sum / n)));
}

class PlayCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ffmpeg_ = services::cli::FindProgram("ffmpeg");
    ffprobe_ = services::cli::FindProgram("ffprobe");
    if (!ffmpeg_.has_value() || !ffprobe_.has_value()) {
      GTEST_SKIP() << "needs Debian's ffmpeg package (ffmpeg and ffprobe)";
    }
    dir_ = MakeTempDir();
  }

  // A run of `env` trained for `steps` steps in rollouts of `rollout` steps, evaluated once at
  // `evaluated` (a value of the varied feature); `extra` adds to the config (the varied
  // feature and its range).
  std::string Train(const std::string& env, int steps, int rollout, double evaluated,
                    const std::string& extra = "") {
    const std::string config = absl::StrCat(dir_, "/", env, ".yaml");
    EXPECT_TRUE(WriteFileAtomically(config, absl::StrCat("env: ", env, "\nseed: 3\n",
                                                         "total_timesteps: ", steps, "\n", extra,
                                                         "evaluation: {freq: 1000000, episodes: 1, "
                                                         "contexts: {id: [", evaluated, "]}}\n",
                                                         "ppo: {n_steps: ", rollout,
                                                         ", batch_size: ", rollout,
                                                         ", n_epochs: 1}\n"))
                    .ok());
    const std::string run = absl::StrCat(dir_, "/", env, "-run");
    const RunResult train = Dcs({"train", "--config", config, "--out", run});
    EXPECT_EQ(train.exit_code, 0) << train.output;
    return run;
  }

  // Runs ffprobe for `entries` of the video's stream, as "key=value" lines.
  std::string Probe(const std::string& path, const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"-v", "error", "-select_streams", "v:0"};
    args.insert(args.end(), extra.begin(), extra.end());
    args.insert(args.end(), {"-of", "default=noprint_wrappers=1", path});
    const RunResult probe = RunProgram(*ffprobe_, args);
    EXPECT_EQ(probe.exit_code, 0) << probe.output;
    return probe.output;
  }

  // Frame `n` of a video or image, decoded to RGB.
  Image Decode(const std::string& path, int n) {
    Image image;
    const std::string size = Probe(path, {"-show_entries", "stream=width,height"});
    std::smatch match;
    if (!std::regex_search(size, match, std::regex("width=(\\d+)\\s+height=(\\d+)"))) {
      ADD_FAILURE() << "no size in " << size;
      return image;
    }
    image.width = std::stoi(match[1]);
    image.height = std::stoi(match[2]);
    const std::string raw = absl::StrCat(dir_, "/frame.rgb");
    const RunResult decode = RunProgram(
        *ffmpeg_, {"-nostdin", "-v", "error", "-y", "-i", path, "-vf",
                   absl::StrCat("select=eq(n\\,", n, ")"), "-frames:v", "1", "-f", "rawvideo",
                   "-pix_fmt", "rgb24", raw});
    EXPECT_EQ(decode.exit_code, 0) << decode.output;
    image.rgb = ReadFile(raw).value_or("");
    EXPECT_THAT(image.rgb, SizeIs(3 * image.width * image.height)) << path << " frame " << n;
    return image;
  }

  // Records `run` with `dcs play` and checks the video, the strip and the overlay.
  void CheckPlay(const std::string& run, const std::vector<std::string>& context) {
    const std::string video = dir_ + "/episode.mp4";
    const std::string strip = dir_ + "/strip.png";
    std::vector<std::string> args = {"play", run, "--seed", "7", "--out", video, "--strip", strip,
                                     "--strip-frames", absl::StrCat(kStripFrames)};
    for (const std::string& assignment : context) {
      args.insert(args.end(), {"--context", assignment});
    }
    const RunResult play = Dcs(args);
    ASSERT_EQ(play.exit_code, 0) << play.output;
    const int steps = PlayedSteps(play.output);
    ASSERT_GT(steps, 0);

    // One frame per step and the reset's, at the scene's size.
    EXPECT_EQ(Probe(video, {"-count_frames", "-show_entries",
                            "stream=width,height,r_frame_rate,nb_read_frames"}),
              absl::StrCat("width=", kWidth, "\nheight=", kHeight,
                           "\nr_frame_rate=50/1\nnb_read_frames=", steps + 1, "\n"));
    // Not blank: the middle frame's pixels vary.
    EXPECT_GT(StandardDeviation(Decode(video, steps / 2)), 10.0);
    // The last frame decodes (the count is not padded).
    EXPECT_THAT(Decode(video, steps).rgb, SizeIs(3 * kWidth * kHeight));

    // The strip: kStripFrames frames side by side.
    const Image with_overlay = Decode(strip, 0);
    EXPECT_EQ(with_overlay.width, kStripFrames * kWidth);
    EXPECT_EQ(with_overlay.height, kHeight);

    // The overlay: the same episode without it differs in each frame's text box, and only there.
    const std::string plain = dir_ + "/plain.png";
    std::vector<std::string> plain_args = {"play", run, "--seed", "7", "--strip", plain,
                                           "--strip-frames", absl::StrCat(kStripFrames),
                                           "--no-overlay"};
    for (const std::string& assignment : context) {
      plain_args.insert(plain_args.end(), {"--context", assignment});
    }
    const RunResult play_plain = Dcs(plain_args);
    ASSERT_EQ(play_plain.exit_code, 0) << play_plain.output;
    const Image without = Decode(plain, 0);
    ASSERT_EQ(without.rgb.size(), with_overlay.rgb.size());
    for (int tile = 0; tile < kStripFrames; ++tile) {
      int changed_in_box = 0;
      int changed_outside = 0;
      for (int y = 0; y < kHeight; ++y) {
        for (int x = tile * kWidth; x < (tile + 1) * kWidth; ++x) {
          int difference = 0;
          for (int c = 0; c < 3; ++c) {
            difference =
                std::max(difference, std::abs(with_overlay.at(x, y, c) - without.at(x, y, c)));
          }
          if (difference == 0) continue;
          (x - tile * kWidth < kBoxWidth && y < kBoxHeight ? changed_in_box : changed_outside) += 1;
        }
      }
      EXPECT_GT(changed_in_box, 1000) << "tile " << tile;
      EXPECT_EQ(changed_outside, 0) << "tile " << tile;
    }
  }

  std::string dir_;
  std::optional<std::string> ffmpeg_;
  std::optional<std::string> ffprobe_;
};

TEST_F(PlayCliTest, CartPoleVideoHasAFramePerStepAndTheOverlay) {
  const std::string run = Train("cartpole", 256, 64, 0.5);
  CheckPlay(run, {"length=0.9"});
}

TEST_F(PlayCliTest, BipedalWalkerVideoHasAFramePerStepAndTheOverlay) {
  const std::string run = Train("bipedal_walker", 128, 64, 0.0,
                                "feature: COM_X\ntraining_range: [-0.6, 0.6]\n");
  CheckPlay(run, {});
}

TEST_F(PlayCliTest, CarRacingVideoHasAFramePerStepAndTheOverlay) {
  const std::string run = Train("car_racing", 32, 16, 0.0,
                                "feature: COM_Y\ntraining_range: [-0.8, 0.8]\n");
  CheckPlay(run, {});
}

TEST_F(PlayCliTest, GifHasAFramePerStep) {
  const std::string run = Train("cartpole", 256, 64, 0.5);
  const std::string gif = dir_ + "/episode.gif";
  const RunResult play = Dcs({"play", run, "--out", gif});
  ASSERT_EQ(play.exit_code, 0) << play.output;
  EXPECT_EQ(Probe(gif, {"-count_frames", "-show_entries", "stream=width,nb_read_frames"}),
            absl::StrCat("width=600\nnb_read_frames=", PlayedSteps(play.output) + 1, "\n"));
}

TEST_F(PlayCliTest, BadInputIsOneLineAndWritesNothing) {
  const std::string run = Train("cartpole", 256, 64, 0.5);
  const std::string video = dir_ + "/episode.mp4";
  const RunResult unknown = Dcs({"play", run, "--context", "gravty=5", "--out", video});
  EXPECT_NE(unknown.exit_code, 0);
  EXPECT_THAT(unknown.output, HasSubstr("unknown context feature 'gravty' (known: gravity,"));
  EXPECT_THAT(unknown.output, Not(HasSubstr("type.dcs.dev")));  // no status payload
  EXPECT_THAT(Lines(unknown.output), SizeIs(1)) << unknown.output;
  // `dcs train`'s words for a value outside the feature's range.
  const RunResult outside = Dcs({"play", run, "--context", "gravity=-5", "--out", video});
  EXPECT_NE(outside.exit_code, 0);
  EXPECT_THAT(outside.output, HasSubstr("context feature 'gravity' must be in [0.1, inf], got -5"));
  EXPECT_THAT(Lines(outside.output), SizeIs(1)) << outside.output;
  const RunResult extension = Dcs({"play", run, "--out", dir_ + "/episode.avi"});
  EXPECT_THAT(extension.output, HasSubstr("should end in .mp4 or .gif"));
  // Nothing written, not even a partial file.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 2)
      << "only the config and the run";
}

TEST_F(PlayCliTest, MissingFfmpegNamesThePackage) {
  const std::string run = Train("cartpole", 256, 64, 0.5);
  const std::string empty = MakeTempDir();  // a PATH without ffmpeg
  const ScopedVariable path("PATH", empty);
  const std::string video = dir_ + "/episode.mp4";
  const RunResult play = Dcs({"play", run, "--out", video});
  EXPECT_NE(play.exit_code, 0);
  EXPECT_THAT(play.output, HasSubstr("install Debian's ffmpeg package (apt-get install ffmpeg)"));
  EXPECT_THAT(Lines(play.output), SizeIs(1)) << play.output;
  EXPECT_FALSE(fs::exists(video));
}

}  // namespace
}  // namespace dcs::integration

// Copyright 2026 The DCS Authors.
#ifndef DCS_SERVICES_CLI_FIGURE_RENDER_H_
#define DCS_SERVICES_CLI_FIGURE_RENDER_H_

// Figures rendered by gnuplot (report/gnuplot_figure.h): a figure's data files and script
// written into a directory, then `gnuplot <name>.gp` run there as a child process, which writes
// `<name>.<format>` beside them; the files stay, so the figure can be restyled and rendered
// again by hand. Thread-compatible (writes files; one call per directory and figure at a time).

#include <string>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "absl/time/time.h"
#include "report/gnuplot_figure.h"

namespace dcs::services::cli {

struct RenderOptions {
  // The gnuplot program: a path, or a name looked up on PATH.
  std::string gnuplot = "gnuplot";
  absl::Duration timeout = absl::Seconds(120);
};

// Writes each of the figure's data files and `<name>.gp` into `dir` (created if missing).
// INVALID_ARGUMENT for a figure or data file name that is not a plain file name; the error
// of writing a file, naming it.
absl::Status WriteFigureFiles(const report::GnuplotFigure& figure, const std::string& dir);

struct RenderedFigure {
  std::string path;            // `<dir>/<name>.<format>`
  std::string gnuplot_output;  // what gnuplot printed (warnings); empty when all went well
};

// WriteFigureFiles, then renders the figure as `format` (an image left from before is removed
// first). FAILED_PRECONDITION if gnuplot cannot be found or run (saying to
// install it; the files stay); INTERNAL naming the script and quoting gnuplot's output if it
// fails or writes no image; DEADLINE_EXCEEDED (gnuplot is killed) after `options.timeout`.
absl::StatusOr<RenderedFigure> RenderFigure(const report::GnuplotFigure& figure,
                                            report::FigureFormat format, const std::string& dir,
                                            const RenderOptions& options = {});

}  // namespace dcs::services::cli

#endif  // DCS_SERVICES_CLI_FIGURE_RENDER_H_

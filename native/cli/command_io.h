// What every command does around its computation: progress on a terminal,
// output paths checked before a long run, text files written whole.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <string>

#include "arguments.h"
#include "consistent_maps/progress.h"
#include "consistent_maps/spherical_parameterization.h"
#include "json_writer.h"

namespace cmaps::cli {

// A name in double quotes, as error messages cite features.
std::string in_quotes(const std::string& name);

// The extension of `path` in lower case, with its dot (".obj"), or "".
std::string lowercase_extension(const std::string& path);

// Progress on an interactive terminal only: logs and pipes get the result alone.
cmaps::ProgressCallback terminal_progress(bool enabled);

// Rejects an unusable output path before a long computation, not after it.
void check_output_path(const std::string& path);

// Rejects an unusable output directory before a long computation: it must
// be a directory, or not exist yet in an existing directory.
void check_output_directory(const std::string& dir);

// Writes `text` and a final newline to `path`, or throws IoError.
void write_text(const std::string& path, const std::string& text);

// The options every computation takes from the command line: seed, effort, threads.
cmaps::SphereOptions sphere_options(const Arguments& args);

// Appends the run's settings (seed, effort, threads, output) to a command's --json.
void add_settings(JsonObject& json, const Arguments& args);

// Runs `compute(progress)` with progress on an interactive terminal (and
// without --json), and clears the progress line however it ends.
template <class Compute>
auto with_terminal_progress(const Arguments& args, Compute&& compute) {
  const bool show = !args.json && isatty(STDERR_FILENO);
  try {
    auto result = compute(terminal_progress(show));
    if (show) std::fputs("\r\033[K", stderr);
    return result;
  } catch (...) {
    if (show) std::fputs("\r\033[K", stderr);
    throw;
  }
}

}  // namespace cmaps::cli

// The command line of `cmaps`, parsed and checked before any mesh is read:
// every option a command does not take is a usage error (exit code 2).
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "consistent_maps/intersurface_map.h"

namespace cmaps::cli {

extern const char* const kUsage;  // the text of `cmaps --help`

// A command-line mistake: reported like any error, but with exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Arguments {
  std::string command, input, output;
  std::vector<std::string> inputs;              // consistent: every input; otherwise just `input`
  std::string features, targets, refined_mesh;  // constrained only (features: consistent too)
  int remesh = 0;                               // consistent and intersurface
  int grid = 64, first = -1;                    // consistent only
  bool remesh_given = false, grid_given = false, first_given = false;
  // optimize, cross_sweeps, cross_turns, starts: intersurface and transfer only, defaults the library's
  int optimize = cmaps::IntersurfaceOptions{}.optimize_rounds, restarts = 1,
      cross_sweeps = cmaps::IntersurfaceOptions{}.cross_sweeps, cross_turns = cmaps::IntersurfaceOptions{}.cross_turns,
      starts = cmaps::IntersurfaceOptions{}.starts;
  bool optimize_given = false, restarts_given = false, cross_sweeps_given = false, cross_turns_given = false,
       starts_given = false;
  std::optional<cmaps::IntersurfaceMethod> method;  // intersurface and transfer only
  std::uint64_t seed = 1;
  int effort = 1;
  int threads = 2;
  bool json = false;
  bool positions = false;  // transfer only
  bool align = false;      // consistent only
};

// The arguments of one run (argv without the program name), or a UsageError.
Arguments parse(const std::vector<std::string>& args);

}  // namespace cmaps::cli

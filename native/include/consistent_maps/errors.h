// Typed exceptions thrown by the library. Every failure a caller can provoke
// with bad input surfaces as one of these, with a one-line human message.
#pragma once
#include <stdexcept>
#include <string>

namespace cmaps {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A file could not be read or written (missing, unreadable, unknown format).
struct IoError : Error {
  using Error::Error;
};

// Data that can never be processed: NaN coordinates, out-of-range indices, ...
struct InvalidInput : Error {
  using Error::Error;
};

// A well-formed mesh whose topology the requested operation does not support
// (wrong genus, boundaries, non-manifold, several components).
struct TopologyError : InvalidInput {
  using InvalidInput::InvalidInput;
};

// The caller's progress callback asked to stop.
struct Cancelled : Error {
  Cancelled() : Error("cancelled") {}
};

}  // namespace cmaps

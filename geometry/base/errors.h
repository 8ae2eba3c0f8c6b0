#pragma once
// The windplan exception hierarchy (house style rule 9). Bad input, I/O failures and broken
// invariants are exceptions; convergence problems are data in a solver's summary. Only the CLI's
// main() catches these and turns them into a one-line message and an exit code:
//   InputError and its subclasses -> exit 1 (the user's file, key or element is named),
//   UsageError                    -> exit 2 (bad command line),
//   anything else                 -> exit 3 (a bug: an invariant broke).
#include <stdexcept>
#include <string>

namespace windplan {

/// Base of all windplan errors.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The user's input is wrong: a file, a key, a value or a mesh element. The message names it.
class InputError : public Error {
 public:
  using Error::Error;
};

/// A file could not be opened, read or written (missing, empty, truncated, unknown format).
class IoError : public InputError {
 public:
  using InputError::InputError;
};

/// The mesh violates a topological requirement (non-manifold, open where closed is needed...).
class TopologyError : public InputError {
 public:
  using InputError::InputError;
};

/// A job file (YAML) is malformed: unknown key, wrong type, invalid value. Names file:line and key.
class ConfigError : public InputError {
 public:
  using InputError::InputError;
};

/// The command line is wrong (unknown flag, missing argument).
class UsageError : public Error {
 public:
  using Error::Error;
};

/// An internal invariant broke: a bug in windplan, not in the input.
class InvariantError : public Error {
 public:
  using Error::Error;
};

}  // namespace windplan

#pragma once
// Error kinds shared by the library and the command line (DESIGN.md: Command line).
// InputError -> exit code 2 (bad usage or bad input); ComputationError -> exit code 1.
#include <stdexcept>
#include <string>

namespace slipwalk::core {

/// Bad input: a value out of range, a malformed file, a non-number. `where` names the option or
/// `file:line:col`; the message says what was wrong.
class InputError : public std::runtime_error {
 public:
  InputError(std::string where, const std::string& what)
      : std::runtime_error(where + ": " + what), where_(std::move(where)) {}
  [[nodiscard]] const std::string& where() const { return where_; }

 private:
  std::string where_;
};

/// A computation that could not finish (a solver failure, a limit reached).
class ComputationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A computation stopped at a budget its caller set (a step, stroke or iteration cap): the
/// method did not misbehave; it was given less work than the answer needs. A study that sweeps
/// into such a cap records the point with its status instead of counting a failure.
class BudgetExhausted : public ComputationError {
 public:
  using ComputationError::ComputationError;
};

}  // namespace slipwalk::core

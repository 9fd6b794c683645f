// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file errors.h
/// Every failure the library reports is an `Error` with a code. Messages say what went wrong,
/// where (file, element index) and, when there is one, what to do about it.

#include <stdexcept>
#include <string>

namespace meshquilt {

enum class ErrorCode {
    InvalidInput,    ///< a mesh or an option violates a precondition (exit code 2)
    IoError,         ///< a file cannot be read or written (exit code 2)
    BackendFailure,  ///< a library we call (CGAL, Eigen, TetGen, OpenVDB) failed (exit code 1)
    Cancelled,       ///< the Reporter asked to stop (exit code 1)
    Internal,        ///< a bug: an invariant of ours does not hold (exit code 1)
};

class Error : public std::runtime_error {
public:
    Error(ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
    [[nodiscard]] ErrorCode code() const { return code_; }

private:
    ErrorCode code_;
};

/// Bad input or options. Thrown before any heavy work where possible.
struct InvalidInput : Error {
    explicit InvalidInput(const std::string& m) : Error(ErrorCode::InvalidInput, m) {}
};
struct IoError : Error {
    explicit IoError(const std::string& m) : Error(ErrorCode::IoError, m) {}
};
struct BackendFailure : Error {
    explicit BackendFailure(const std::string& m) : Error(ErrorCode::BackendFailure, m) {}
};
struct Cancelled : Error {
    explicit Cancelled(const std::string& m = "cancelled") : Error(ErrorCode::Cancelled, m) {}
};

/// The process exit code the CLI uses for an error code: 2 for bad input or usage, 1 otherwise.
inline int exit_code_for(ErrorCode code) {
    return (code == ErrorCode::InvalidInput || code == ErrorCode::IoError) ? 2 : 1;
}

}  // namespace meshquilt

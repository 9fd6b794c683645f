// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
/// \file reporter.h
/// The library never prints. Progress, cancellation and log messages go through a Reporter.

#include <functional>
#include <string>

namespace meshquilt {

enum class LogLevel { Debug, Info, Warning };

struct Reporter {
    /// Called with a stage name and its completed fraction in [0, 1]. Return false to cancel:
    /// the running call then throws `Cancelled`. May be empty. Mostly called on the calling
    /// thread, but while a print is voxelised OpenVDB calls it from its worker threads (one at a
    /// time): it must be thread-safe and must not wait for the calling thread.
    std::function<bool(const std::string& stage, double fraction)> progress;
    /// Receives log messages (on the calling thread). May be empty.
    std::function<void(LogLevel level, const std::string& text)> log;

    /// Forwards to `progress`; throws Cancelled when it returns false.
    void report(const std::string& stage, double fraction) const;
    void info(const std::string& text) const { if (log) log(LogLevel::Info, text); }
    void warn(const std::string& text) const { if (log) log(LogLevel::Warning, text); }
    void debug(const std::string& text) const { if (log) log(LogLevel::Debug, text); }
};

}  // namespace meshquilt

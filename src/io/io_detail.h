// SPDX-License-Identifier: AGPL-3.0-or-later
#pragma once
// Private pieces shared by the mesh readers: error helpers, a line-tracking text scanner and number
// parsing without iostreams. Nothing here is public API.

#include "meshquilt/errors.h"
#include "meshquilt/io.h"
#include "meshquilt/mesh.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace meshquilt::io_detail {

// One reader per format. `data` is the whole file; `path` starts every message.
Mesh read_obj(const std::string& path, std::string_view data);
Mesh read_off(const std::string& path, std::string_view data);
Mesh read_ply(const std::string& path, std::string_view data);
Mesh read_stl(const std::string& path, std::string_view data);
Mesh read_3mf(const std::string& path, std::string_view data);
/// The bytes of a 3MF file (lib3mf): millimetres, one object per element of `options`.
std::string format_3mf(const std::string& path, const Mesh& mesh, const WriteOptions& options);


/// Lower-cased extension including the dot ("" when there is none).
std::string lower_extension(const std::string& path);

[[noreturn]] inline void fail(const std::string& path, const std::string& what) {
    throw InvalidInput(path + ": " + what);
}
[[noreturn]] inline void fail_at(const std::string& path, long line, const std::string& what) {
    throw InvalidInput(path + ":" + std::to_string(line) + ": " + what);
}

/// A token quoted for a message: at most 24 characters, unprintable bytes shown as '?'.
inline std::string quoted(std::string_view token) {
    std::string s = "'";
    const std::size_t n = token.size() < 24 ? token.size() : 24;
    for (std::size_t i = 0; i < n; ++i) {
        const auto c = static_cast<unsigned char>(token[i]);
        s += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
    }
    if (token.size() > n) s += "...";
    return s + "'";
}

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
inline bool is_space_or_newline(char c) { return is_space(c) || c == '\n'; }

inline bool iequals(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        char x = a[i], y = b[i];
        if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
        if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
        if (x != y) return false;
    }
    return true;
}

enum class NumberStatus { Ok, Bad, NonFinite };

/// Parses a whole token as a double. Accepts a leading '+'. Overflow (1e999) and nan/inf are
/// NonFinite; underflow gives the nearest representable value, as strtod does.
inline NumberStatus parse_double(std::string_view token, double& out) {
    const char* p = token.data();
    const char* e = p + token.size();
    if (p < e && *p == '+') {
        ++p;
        if (p < e && (*p == '+' || *p == '-')) return NumberStatus::Bad;
    }
    if (p == e) return NumberStatus::Bad;
    auto [end, ec] = std::from_chars(p, e, out, std::chars_format::general);
    if (ec == std::errc::result_out_of_range) {
        // from_chars leaves `out` untouched on overflow and underflow; strtod tells them apart.
        const std::string copy(p, e);
        char* stop = nullptr;
        out = std::strtod(copy.c_str(), &stop);
        if (stop != copy.c_str() + copy.size()) return NumberStatus::Bad;
    } else if (ec != std::errc() || end != e) {
        return NumberStatus::Bad;
    }
    return std::isfinite(out) ? NumberStatus::Ok : NumberStatus::NonFinite;
}

/// Parses a whole token as a signed 64-bit integer (leading '+' accepted).
inline bool parse_int(std::string_view token, long long& out) {
    const char* p = token.data();
    const char* e = p + token.size();
    if (p < e && *p == '+') {
        ++p;
        if (p < e && *p == '-') return false;
    }
    if (p == e) return false;
    auto [end, ec] = std::from_chars(p, e, out);
    return ec == std::errc() && end == e;
}

/// Walks a text buffer token by token, across lines, counting lines. `#` starts a comment to the
/// end of the line when `hash_comments` is set.
class TextScanner {
public:
    TextScanner(std::string_view text, bool hash_comments, long first_line = 1)
        : p_(text.data()), e_(text.data() + text.size()), line_(first_line), hash_comments_(hash_comments) {}

    /// Next token on any line; empty at the end of the input. `line()` is the token's line then.
    std::string_view next() {
        skip_blank(true);
        return take();
    }
    /// Next token on the current line only; empty when the line has no more.
    std::string_view next_on_line() {
        skip_blank(false);
        if (p_ == e_ || *p_ == '\n') return {};
        return take();
    }
    /// Skips the rest of the current line, including its newline.
    void skip_line() {
        const void* nl = std::memchr(p_, '\n', static_cast<std::size_t>(e_ - p_));
        if (nl) {
            p_ = static_cast<const char*>(nl) + 1;
            ++line_;
        } else {
            p_ = e_;
        }
    }
    [[nodiscard]] bool at_end() {
        skip_blank(true);
        return p_ == e_;
    }
    [[nodiscard]] long line() const { return line_; }
    [[nodiscard]] const char* position() const { return p_; }

private:
    void skip_blank(bool newlines) {
        while (p_ < e_) {
            const char c = *p_;
            if (is_space(c)) {
                ++p_;
            } else if (c == '\n') {
                if (!newlines) return;
                ++p_;
                ++line_;
            } else if (c == '#' && hash_comments_) {
                while (p_ < e_ && *p_ != '\n') ++p_;
            } else {
                return;
            }
        }
    }
    std::string_view take() {
        const char* s = p_;
        while (p_ < e_ && !is_space_or_newline(*p_) && !(hash_comments_ && *p_ == '#')) ++p_;
        return {s, static_cast<std::size_t>(p_ - s)};
    }

    const char* p_;
    const char* e_;
    long line_;
    bool hash_comments_;
};

/// Largest vertex or face count a Mesh can index (Tri holds int).
inline constexpr long long kMaxElements = 0x7fffffffLL;

}  // namespace meshquilt::io_detail

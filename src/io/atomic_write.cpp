// SPDX-License-Identifier: AGPL-3.0-or-later
// write_file_atomic(): temporary file in the target's directory, every write and the close
// checked, then rename() over the target. A failure removes the temporary file and leaves the
// target as it was. No fsync: this protects against failed writes, not against power loss.
// A target that is neither a regular file nor a directory (a device such as /dev/null or
// /dev/stdout, a named pipe) is written in place: renaming over it would replace the device node
// with a regular file (as root) or fail for want of a writable /dev.

#include "meshquilt/errors.h"
#include "meshquilt/io.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace meshquilt {

namespace {

[[noreturn]] void write_failed(const std::string& path, const std::string& what, int err) {
    throw IoError(path + ": cannot write: " + what + std::strerror(err));
}

/// Writes all of `contents` to `fd` (retrying interrupted and short writes); false with errno set on failure.
bool write_all(int fd, const std::string& contents) {
    const char* p = contents.data();
    std::size_t left = contents.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        p += n;
        left -= static_cast<std::size_t>(n);
    }
    return true;
}

}  // namespace

void write_file_atomic(const std::string& path, const std::string& contents) {
    namespace fs = std::filesystem;
    if (path.empty()) throw IoError("cannot write: the output path is empty");
    fs::path target(path);
    // Write through a symbolic link to the file it names, rather than replacing the link.
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(target, ec))) {
        const fs::path resolved = fs::weakly_canonical(target, ec);
        if (!ec) target = resolved;
    }
    const std::string name = target.filename().string();
    if (name.empty() || name == "." || name == "..") throw IoError(path + ": cannot write: not a file name");
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    if (struct stat existing {}; ::stat(target.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode) && !S_ISDIR(existing.st_mode)) {
        const int fd = ::open(target.c_str(), O_WRONLY | O_CLOEXEC);
        if (fd < 0) write_failed(path, "", errno);
        if (!write_all(fd, contents)) {
            const int err = errno;
            ::close(fd);
            write_failed(path, "", err);
        }
        if (::close(fd) != 0) write_failed(path, "", errno);
        return;
    }

    static std::atomic<unsigned> counter{0};
    const fs::path temp =
        dir / ("." + name + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1)));
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) {
        const int err = errno;
        write_failed(path, "cannot create a file in '" + dir.string() + "': ", err);
    }
    // Keep the permissions of a file we replace.
    struct stat st {};
    if (::stat(target.c_str(), &st) == 0 && S_ISREG(st.st_mode)) (void)::fchmod(fd, st.st_mode & 07777);

    if (!write_all(fd, contents)) {
        const int err = errno;
        ::close(fd);
        ::unlink(temp.c_str());
        write_failed(path, "", err);
    }
    if (::close(fd) != 0) {
        const int err = errno;
        ::unlink(temp.c_str());
        write_failed(path, "", err);
    }
    if (::rename(temp.c_str(), target.c_str()) != 0) {
        const int err = errno;
        ::unlink(temp.c_str());
        write_failed(path, "", err);
    }
}

}  // namespace meshquilt

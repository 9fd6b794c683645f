// SPDX-License-Identifier: AGPL-3.0-or-later
// write_file_atomic(): temporary file in the target's directory, every write and the close
// checked, then rename() over the target. A failure removes the temporary file and leaves the
// target as it was. No fsync: this protects against failed writes, not against power loss.

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

    const char* p = contents.data();
    std::size_t left = contents.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            const int err = errno;
            ::close(fd);
            ::unlink(temp.c_str());
            write_failed(path, "", err);
        }
        p += n;
        left -= static_cast<std::size_t>(n);
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

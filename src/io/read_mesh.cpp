// SPDX-License-Identifier: AGPL-3.0-or-later
// read_mesh(): loads the whole file into memory and hands it to the reader its extension names.

#include "io/io_detail.h"
#include "meshquilt/io.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

namespace meshquilt {

namespace io_detail {

std::string lower_extension(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    const std::size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot);
    for (char& c : ext)
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return ext;
}

}  // namespace io_detail

namespace {

std::string errno_text(int err) { return std::strerror(err); }

/// The whole file; IoError when it cannot be opened or read.
std::string slurp(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw IoError(path + ": cannot open: " + errno_text(errno));
    struct FdCloser {
        int fd;
        ~FdCloser() { ::close(fd); }
    } closer{fd};
    struct stat st {};
    if (::fstat(fd, &st) != 0) throw IoError(path + ": cannot open: " + errno_text(errno));
    if (S_ISDIR(st.st_mode)) throw IoError(path + ": cannot open: " + errno_text(EISDIR));
    std::string data;
    if (S_ISREG(st.st_mode) && st.st_size > 0) data.reserve(static_cast<std::size_t>(st.st_size));
    char buffer[1 << 16];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw IoError(path + ": read error: " + errno_text(errno));
        }
        if (n == 0) break;
        data.append(buffer, static_cast<std::size_t>(n));
    }
    return data;
}

}  // namespace

namespace {

using Reader = Mesh (*)(const std::string&, std::string_view);

Reader reader_for(const std::string& path) {
    const std::string ext = io_detail::lower_extension(path);
    if (ext == ".obj") return io_detail::read_obj;
    if (ext == ".off") return io_detail::read_off;
    if (ext == ".ply") return io_detail::read_ply;
    if (ext == ".stl") return io_detail::read_stl;
    if (ext == ".3mf") return io_detail::read_3mf;
    throw IoError(path + ": cannot read: unknown mesh file extension " +
                  (ext.empty() ? std::string("(none)") : "'" + ext + "'") + " (supported: .obj, .off, .ply, .stl, .3mf)");
}

Mesh parse_with(Reader reader, const std::string& name, std::string_view data) {
    Mesh mesh = reader(name, data);
    if (mesh.faces.empty()) io_detail::fail(name, "no faces");
    return mesh;
}

}  // namespace

Mesh parse_mesh(const std::string& name, std::string_view data) { return parse_with(reader_for(name), name, data); }

Mesh read_mesh(const std::string& path) {
    const Reader reader = reader_for(path);  // before opening: an unknown extension fails fast
    return parse_with(reader, path, slurp(path));
}

}  // namespace meshquilt

// SPDX-License-Identifier: BSD-3-Clause
// Writing an output file atomically (POSIX): readers see either the old file or the complete new
// one, never a partial write, and a failure leaves no stray temporary behind.
//
// The content goes to a uniquely named temporary (mkstemp) in the target's own folder, so the final
// rename stays on one file system and is atomic. The target is refused up front when it exists and
// is not a regular file: renaming over a FIFO or a device would silently replace it, and a
// directory cannot be replaced at all. A new file gets mode 0644; an existing one keeps its mode.
#pragma once

#include <cerrno>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "camfollower/error.hpp"

namespace camfollower::detail {

namespace atomic_file {

// The folder holding `path` ("." for a bare name) and the name within it.
inline std::pair<std::string, std::string> split_path(const std::string& path) {
    const std::size_t slash = path.find_last_of('/');
    if (slash == std::string::npos) return {".", path};
    return {slash == 0 ? "/" : path.substr(0, slash), path.substr(slash + 1)};
}

// Owns the temporary until commit(): on any early exit it is closed and unlinked.
class Temporary {
public:
    Temporary(const std::string& folder, const std::string& name, const char* parameter) {
        std::string pattern = folder + "/." + name + ".tmp.XXXXXX";
        std::vector<char> buffer(pattern.begin(), pattern.end());
        buffer.push_back('\0');
        fd_ = ::mkstemp(buffer.data());
        if (fd_ < 0)
            fail(parameter, ": cannot create a temporary file in '", folder, "': ", std::strerror(errno));
        path_.assign(buffer.data());
    }
    Temporary(const Temporary&) = delete;
    Temporary& operator=(const Temporary&) = delete;
    ~Temporary() {
        if (fd_ >= 0) ::close(fd_);
        if (!committed_) ::unlink(path_.c_str());
    }

    int fd() const { return fd_; }
    const std::string& path() const { return path_; }
    // Closes the descriptor, reporting a late write error (some file systems report them here).
    bool close() {
        const int fd = fd_;
        fd_ = -1;
        return ::close(fd) == 0;
    }
    void commit() { committed_ = true; }

private:
    int fd_ = -1;
    std::string path_;
    bool committed_ = false;
};

}  // namespace atomic_file

// Replaces (or creates) `path` with exactly `content`. Throws std::invalid_argument naming
// `parameter` on a bad target or any I/O failure; the target is then untouched.
inline void write_file_atomically(const std::string& path, const std::string& content,
                                  const char* parameter = "path") {
    if (path.empty()) fail(parameter, " must name a file, got an empty string");
    mode_t mode = 0644;
    struct stat target {};
    if (::stat(path.c_str(), &target) == 0) {
        if (!S_ISREG(target.st_mode))
            fail(parameter, ": '", path, "' exists and is not a regular file (",
                 S_ISDIR(target.st_mode) ? "a directory" : "a FIFO, socket or device",
                 "); give a file name");
        mode = target.st_mode & 07777;
    } else if (errno != ENOENT) {
        fail(parameter, ": cannot inspect '", path, "': ", std::strerror(errno));
    }
    const auto [folder, name] = atomic_file::split_path(path);
    if (name.empty()) fail(parameter, ": '", path, "' names a folder, not a file");

    atomic_file::Temporary tmp(folder, name, parameter);
    const char* data = content.data();
    std::size_t left = content.size();
    while (left > 0) {
        const ssize_t n = ::write(tmp.fd(), data, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            fail(parameter, ": writing '", path, "' failed: ", std::strerror(errno));
        }
        data += n;
        left -= static_cast<std::size_t>(n);
    }
    if (::fchmod(tmp.fd(), mode) != 0 || ::fsync(tmp.fd()) != 0 || !tmp.close())
        fail(parameter, ": writing '", path, "' failed: ", std::strerror(errno));
    if (::rename(tmp.path().c_str(), path.c_str()) != 0)
        fail(parameter, ": cannot move the finished file onto '", path, "': ", std::strerror(errno));
    tmp.commit();
    // Make the rename itself durable; a failure here cannot undo the complete file, so it is ignored.
    const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
    if (dir >= 0) {
        ::fsync(dir);
        ::close(dir);
    }
}

}  // namespace camfollower::detail

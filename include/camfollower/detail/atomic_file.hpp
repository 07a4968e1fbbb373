// SPDX-License-Identifier: BSD-3-Clause
// Writing an output file atomically (POSIX): readers see either the old file or the complete new
// one, never a partial write, and a failure leaves no stray temporary behind.
//
// The content goes to a uniquely named temporary (mkstemp) in the target's own folder, so the final
// rename stays on one file system and is atomic. The target is refused up front when it is not a
// plain, writable regular file (see write_file_atomically). A new file gets mode 0644; an existing
// one keeps its mode.
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

// A path as messages show it: whole (up to PATH_MAX), control characters as '?'.
inline std::string shown(const std::string& path) { return printable(path, 4096); }

// Owns the temporary until commit(): on any early exit it is closed and unlinked.
class Temporary {
public:
    Temporary(const std::string& folder, const std::string& name, const char* parameter) {
        std::string pattern = folder + "/." + name + ".tmp.XXXXXX";
        std::vector<char> buffer(pattern.begin(), pattern.end());
        buffer.push_back('\0');
        fd_ = ::mkstemp(buffer.data());
        if (fd_ < 0)
            fail(parameter, ": cannot create a temporary file in '", shown(folder), "' for '", shown(name),
                 "': ", std::strerror(errno));
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

// Checks that `path` may be (re)written, before any work is done; returns the mode the new file
// gets (an existing file's own). Throws std::invalid_argument naming `parameter`. Refused targets:
// anything that is not a regular file (directory, FIFO, socket, device) or is a symbolic link
// (replacing the link would leave its file stale; give the real path), a read-only file (renaming
// over it would defeat the protection), and any of `protect` (the run's input files).
inline mode_t require_output_target(const std::string& path, const char* parameter = "path",
                                    const std::vector<std::string>& protect = {}) {
    using atomic_file::shown;
    if (path.empty()) fail(parameter, " must name a file, got an empty string");
    if (path.find('\0') != std::string::npos)
        fail(parameter, ": '", shown(path), "' contains a NUL character; a file name cannot");
    mode_t mode = 0644;
    struct stat target {};
    if (::lstat(path.c_str(), &target) == 0) {
        if (S_ISLNK(target.st_mode))
            fail(parameter, ": '", shown(path), "' is a symbolic link; give the path of the file it points to");
        if (!S_ISREG(target.st_mode))
            fail(parameter, ": '", shown(path), "' exists and is not a regular file (",
                 S_ISDIR(target.st_mode) ? "a directory" : "a FIFO, socket or device", "); give a file name");
        // By the mode bits as well as access(): root may write anything, but a file nobody may write
        // was protected on purpose.
        if ((target.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || ::access(path.c_str(), W_OK) != 0)
            fail(parameter, ": '", shown(path), "' is read-only; make it writable or choose another name");
        for (const std::string& input : protect) {
            struct stat other {};
            if (::stat(input.c_str(), &other) == 0 && other.st_dev == target.st_dev && other.st_ino == target.st_ino)
                fail(parameter, ": '", shown(path), "' is the input file '", shown(input),
                     "' itself; choose another output file");
        }
        mode = target.st_mode & 07777;
    } else if (errno != ENOENT) {
        fail(parameter, ": cannot inspect '", shown(path), "': ", std::strerror(errno));
    }
    return mode;
}

// Replaces (or creates) `path` with exactly `content`. Throws std::invalid_argument naming
// `parameter` on a bad target (require_output_target) or any I/O failure; the target is then untouched.
inline void write_file_atomically(const std::string& path, const std::string& content, const char* parameter = "path",
                                  const std::vector<std::string>& protect = {}) {
    using atomic_file::shown;
    const mode_t mode = require_output_target(path, parameter, protect);
    const auto [folder, name] = atomic_file::split_path(path);
    if (name.empty()) fail(parameter, ": '", shown(path), "' names a folder, not a file");

    atomic_file::Temporary tmp(folder, name, parameter);
    const char* data = content.data();
    std::size_t left = content.size();
    while (left > 0) {
        const ssize_t n = ::write(tmp.fd(), data, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            fail(parameter, ": writing the temporary '", shown(tmp.path()), "' for '", shown(path),
                 "' failed: ", std::strerror(errno));
        }
        data += n;
        left -= static_cast<std::size_t>(n);
    }
    if (::fchmod(tmp.fd(), mode) != 0 || ::fsync(tmp.fd()) != 0 || !tmp.close())
        fail(parameter, ": writing the temporary '", shown(tmp.path()), "' for '", shown(path),
             "' failed: ", std::strerror(errno));
    if (::rename(tmp.path().c_str(), path.c_str()) != 0)
        fail(parameter, ": cannot move the finished temporary '", shown(tmp.path()), "' onto '", shown(path),
             "': ", std::strerror(errno));
    tmp.commit();
    // Make the rename itself durable; a failure here cannot undo the complete file, so it is ignored.
    const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
    if (dir >= 0) {
        ::fsync(dir);
        ::close(dir);
    }
}

}  // namespace camfollower::detail

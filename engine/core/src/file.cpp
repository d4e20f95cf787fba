#include "lantern/core/file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

namespace lantern {
namespace {

Error io_error(const std::string& path, const char* what) {
    return make_error(path + ": " + what + ": " + std::strerror(errno), 1);
}

bool write_all(int fd, const std::byte* data, size_t size) {
    while (size > 0) {
        ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        data += n;
        size -= static_cast<size_t>(n);
    }
    return true;
}

const char* kind_of(mode_t mode) {
    if (S_ISREG(mode)) return "a regular file";
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

Error not_regular(const std::string& path, mode_t mode) {
    return make_error(path + ": is " + std::string(kind_of(mode)) + ", not a regular file", 2);
}

Error too_big(const std::string& path, std::uint64_t size, std::uint64_t max_bytes) {
    return make_error(path + ": " + std::to_string(size) + " bytes, over the limit of " + std::to_string(max_bytes) +
                          " bytes for this kind of file (docs/scenes.md, \"Limits\")",
                      2);
}

struct Fd {
    int fd = -1;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

} // namespace

Result<std::vector<std::uint8_t>> read_binary_file(const std::string& path, std::uint64_t max_bytes) {
    // O_NONBLOCK: opening a FIFO must not wait for a writer; the mode is checked before
    // anything is read.
    Fd f{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
    if (f.fd < 0) return io_error(path, "cannot open");
    struct stat st {};
    if (::fstat(f.fd, &st) != 0) return io_error(path, "cannot stat");
    if (!S_ISREG(st.st_mode)) return not_regular(path, st.st_mode);
    const std::uint64_t size = std::uint64_t(st.st_size);
    if (size > max_bytes) return too_big(path, size, max_bytes);
    std::vector<std::uint8_t> data(static_cast<std::size_t>(size));
    std::size_t used = 0;
    for (;;) {
        if (used == data.size()) {
            // The file grew since fstat: read on, within the limit.
            if (data.size() >= max_bytes) {
                std::uint8_t probe;
                const ssize_t more = ::read(f.fd, &probe, 1);
                if (more > 0) return too_big(path, std::uint64_t(data.size()) + 1, max_bytes);
                if (more == 0) break;
                if (errno == EINTR) continue;
                return io_error(path, "cannot read");
            }
            data.resize(std::min<std::size_t>(std::size_t(max_bytes), std::max<std::size_t>(data.size() * 2, 4096)));
        }
        const ssize_t n = ::read(f.fd, data.data() + used, data.size() - used);
        if (n < 0) {
            if (errno == EINTR) continue;
            return io_error(path, "cannot read");
        }
        if (n == 0) break;
        used += std::size_t(n);
    }
    data.resize(used);
    return data;
}

Result<std::string> read_text_file(const std::string& path, std::uint64_t max_bytes) {
    auto bytes = read_binary_file(path, max_bytes);
    if (!bytes) return bytes.error();
    return std::string(bytes->begin(), bytes->end());
}

Result<void> check_input_file(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return io_error(path, "cannot open");
    if (!S_ISREG(st.st_mode)) return not_regular(path, st.st_mode);
    if (::access(path.c_str(), R_OK) != 0) return io_error(path, "cannot open");
    return {};
}

Result<void> check_output_file(const std::string& path) {
    namespace fs = std::filesystem;
    if (path.empty()) return make_error("an output path is empty", 2);
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) return not_regular(path, st.st_mode);
    fs::path dir = fs::path(path).parent_path();
    if (dir.empty()) dir = ".";
    struct stat dst {};
    if (::stat(dir.c_str(), &dst) != 0 || !S_ISDIR(dst.st_mode))
        return make_error(path + ": its folder " + dir.string() + " does not exist", 2);
    if (::access(dir.c_str(), W_OK) != 0) return make_error(path + ": its folder " + dir.string() + " is not writable", 2);
    return {};
}

Result<void> check_output_folder(const std::string& path) {
    namespace fs = std::filesystem;
    if (path.empty()) return make_error("an output folder path is empty", 2);
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        if (!S_ISDIR(st.st_mode)) return make_error(path + ": is " + std::string(kind_of(st.st_mode)) + ", not a folder", 2);
        if (::access(path.c_str(), W_OK) != 0) return make_error(path + ": the folder is not writable", 2);
        return {};
    }
    // A new folder (and its missing parents) is created in the nearest folder that exists.
    fs::path ancestor = fs::path(path).lexically_normal().parent_path();
    while (!ancestor.empty() && ::stat(ancestor.c_str(), &st) != 0) ancestor = ancestor.parent_path();
    if (ancestor.empty()) ancestor = ".";
    if (::stat(ancestor.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
        return make_error(path + ": " + ancestor.string() + " is not a folder", 2);
    if (::access(ancestor.c_str(), W_OK) != 0) return make_error(path + ": " + ancestor.string() + " is not writable", 2);
    return {};
}

Result<StagedFolder> StagedFolder::create(const std::string& target) {
    namespace fs = std::filesystem;
    if (auto ok = check_output_folder(target); !ok) return ok.error();
    const fs::path t = fs::path(target).lexically_normal();
    fs::path parent = t.parent_path();
    if (parent.empty()) parent = ".";
    if (auto ok = ensure_directory(parent.string()); !ok) return ok.error();
    std::string tmpl = (parent / ("." + t.filename().string() + ".tmp.XXXXXX")).string();
    if (!::mkdtemp(tmpl.data())) return io_error(target, "cannot create a staging folder");
    return StagedFolder(t.string(), tmpl);
}

StagedFolder::StagedFolder(StagedFolder&& other) noexcept
    : target_(std::move(other.target_)), staging_(std::move(other.staging_)), done_(other.done_) {
    other.done_ = true;
}

StagedFolder::~StagedFolder() {
    if (done_) return;
    std::error_code ec;
    std::filesystem::remove_all(staging_, ec);
}

std::string StagedFolder::file(const std::string& name) const { return (std::filesystem::path(staging_) / name).string(); }

Result<void> StagedFolder::commit() {
    namespace fs = std::filesystem;
    struct stat st {};
    if (::stat(target_.c_str(), &st) != 0) {
        if (::rename(staging_.c_str(), target_.c_str()) != 0) return io_error(target_, "cannot move the staged folder into place");
        done_ = true;
        return {};
    }
    if (!S_ISDIR(st.st_mode)) return make_error(target_ + ": is " + std::string(kind_of(st.st_mode)) + ", not a folder", 2);
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(staging_, ec)) {
        const fs::path to = fs::path(target_) / e.path().filename();
        if (::rename(e.path().c_str(), to.c_str()) != 0) return io_error(to.string(), "cannot move into place");
    }
    if (ec) return make_error(staging_ + ": cannot list the staged files: " + ec.message(), 1);
    done_ = true;
    fs::remove_all(staging_, ec);
    return {};
}

Result<void> write_file_atomic(const std::string& path, std::span<const std::byte> bytes) {
    namespace fs = std::filesystem;
    fs::path target(path);
    struct stat existing {};
    if (::stat(path.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode)) return not_regular(path, existing.st_mode);
    fs::path dir = target.parent_path();
    if (dir.empty()) dir = ".";
    std::string tmpl = (dir / ("." + target.filename().string() + ".tmp.XXXXXX")).string();
    int fd = ::mkstemp(tmpl.data());
    if (fd < 0) return io_error(path, "cannot create temporary file");
    bool ok = write_all(fd, bytes.data(), bytes.size()) && ::fsync(fd) == 0;
    int saved_errno = errno;
    ::fchmod(fd, 0644);
    if (::close(fd) != 0 && ok) {
        ok = false;
        saved_errno = errno;
    }
    if (!ok) {
        ::unlink(tmpl.c_str());
        errno = saved_errno;
        return io_error(path, "cannot write");
    }
    if (::rename(tmpl.c_str(), path.c_str()) != 0) {
        saved_errno = errno;
        ::unlink(tmpl.c_str());
        errno = saved_errno;
        return io_error(path, "cannot rename temporary file into place");
    }
    // Make the rename itself durable.
    int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
    if (dfd >= 0) {
        ::fsync(dfd);
        ::close(dfd);
    }
    return {};
}

Result<void> write_file_atomic(const std::string& path, const std::string& text) {
    return write_file_atomic(path, std::as_bytes(std::span<const char>(text.data(), text.size())));
}

Result<void> ensure_directory(const std::string& path) {
    std::error_code ec;
    std::filesystem::create_directories(path, ec);
    if (ec) return make_error(path + ": cannot create folder: " + ec.message(), 1);
    return {};
}

std::optional<FileStamp> file_stamp(const std::string& path) {
    struct stat st{};
    if (::stat(path.c_str(), &st) != 0) return std::nullopt;
    return FileStamp{std::uint64_t(st.st_dev), std::uint64_t(st.st_ino), std::uint64_t(st.st_size),
                     std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec};
}

void FilesWatch::watch(std::vector<std::string> paths) {
    paths_ = std::move(paths);
    stamps_.clear();
    for (const std::string& p : paths_) stamps_.push_back(file_stamp(p));
}

bool FilesWatch::changed() {
    bool any = false;
    for (std::size_t i = 0; i < paths_.size(); ++i) {
        std::optional<FileStamp> now = file_stamp(paths_[i]);
        if (now != stamps_[i]) {
            stamps_[i] = now;
            any = true;
        }
    }
    return any;
}

} // namespace lantern

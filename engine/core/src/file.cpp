#include "lantern/core/file.hpp"

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

} // namespace

Result<std::vector<std::uint8_t>> read_binary_file(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return io_error(path, "cannot open");
    std::vector<std::uint8_t> data;
    std::uint8_t buffer[65536];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof(buffer), f)) > 0) data.insert(data.end(), buffer, buffer + n);
    bool failed = std::ferror(f);
    std::fclose(f);
    if (failed) return io_error(path, "cannot read");
    return data;
}

Result<std::string> read_text_file(const std::string& path) {
    auto bytes = read_binary_file(path);
    if (!bytes) return bytes.error();
    return std::string(bytes->begin(), bytes->end());
}

Result<void> write_file_atomic(const std::string& path, std::span<const std::byte> bytes) {
    namespace fs = std::filesystem;
    fs::path target(path);
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

} // namespace lantern

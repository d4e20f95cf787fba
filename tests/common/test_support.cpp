#include "common/test_support.hpp"

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <unistd.h>

namespace lantern::test {

TempDir::TempDir() {
    static std::atomic<int> counter{0};
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("lantern-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
             std::to_string(rd() % 100000));
    std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
}

std::filesystem::path source_dir() { return LANTERN_SOURCE_DIR; }

std::filesystem::path shared_dir() {
    if (const char* env = std::getenv("LANTERN_SHARED_DIR")) {
        if (std::filesystem::is_directory(env)) return env;
        return {};
    }
    auto candidate = source_dir().parent_path() / "shared";
    if (std::filesystem::is_directory(candidate / "maps")) return candidate;
    return {};
}

bool gpu_required() {
    const char* v = std::getenv("LANTERN_REQUIRE_GPU");
    return v && std::string(v) == "1";
}

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

} // namespace lantern::test

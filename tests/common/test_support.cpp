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

std::string corrupting_edit(const std::string& good, std::uint64_t& random,
                            const std::function<bool(const std::string&)>& malformed) {
    static constexpr char junk[] = "{}[],:\"@#\x01\\-e9.x";
    const auto next = [&random]() { // splitmix64
        std::uint64_t z = (random += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    };
    for (;;) {
        std::string bad = good;
        const std::size_t at = bad.empty() ? 0 : std::size_t(next() % bad.size());
        const char c = junk[next() % (sizeof(junk) - 1)];
        switch (next() % 3) {
        case 0: bad.resize(at); break;
        case 1:
            if (!bad.empty()) bad[at] = c;
            break;
        default: bad.insert(bad.begin() + std::ptrdiff_t(at), c); break;
        }
        if (malformed(bad)) return bad;
    }
}

} // namespace lantern::test

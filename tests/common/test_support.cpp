#include "common/test_support.hpp"

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <thread>
#include <fstream>
#include <random>
#include <sstream>
#include <unistd.h>

extern char** environ;

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

ChildProcess::ChildProcess(const std::string& exe, std::vector<std::string> args, const std::string& log_path)
    : log_path_(log_path) {
    args.insert(args.begin(), exe);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    pid_t pid = -1;
    if (posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), environ) == 0) pid_ = pid;
    posix_spawn_file_actions_destroy(&actions);
}

ChildProcess::~ChildProcess() {
    if (pid_ > 0 && !exited_) {
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
    }
}

std::optional<int> ChildProcess::wait_exit(std::chrono::milliseconds timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (pid_ > 0) {
        if (exited_) return status_;
        int status = 0;
        if (waitpid(pid_, &status, WNOHANG) == pid_) {
            exited_ = true;
            status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
            return status_;
        }
        if (std::chrono::steady_clock::now() >= end) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return std::nullopt;
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

// Helpers shared by the test suites: temporary folders, paths to the source tree and to
// ../shared (skipped cleanly when absent).
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace lantern::test {

// A fresh folder under the system temp dir, removed when the object dies.
class TempDir {
  public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

  private:
    std::filesystem::path path_;
};

std::filesystem::path source_dir();
// ../shared next to the checkout, or empty when it is absent (tests then GTEST_SKIP).
std::filesystem::path shared_dir();

std::string read_file(const std::filesystem::path& path);

// A child process running `exe` with `args`, its stdout and stderr into `log_path`; killed
// (and reaped) if still running when the object dies.
class ChildProcess {
  public:
    ChildProcess(const std::string& exe, std::vector<std::string> args, const std::string& log_path);
    ~ChildProcess();
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;
    bool started() const { return pid_ > 0; }
    // Waits up to `timeout` for the exit; its status (128 + signal when killed; the same again
    // on later calls), or nullopt when it is still running.
    std::optional<int> wait_exit(std::chrono::milliseconds timeout);
    std::string log() const { return read_file(log_path_); }

  private:
    std::string log_path_;
    int pid_ = -1;
    bool exited_ = false;
    int status_ = 0;
};

// A random corrupting edit of `good` (hot-reload tests): a truncation, a byte overwritten or a
// byte inserted, from characters that break JSON and scene files ({}[],:"@#, a control
// byte, ...), drawn again until `malformed` says the edit really is (so a test never counts
// on an edit that happens to stay valid).
std::string corrupting_edit(const std::string& good, std::uint64_t& random,
                            const std::function<bool(const std::string&)>& malformed);

// True when LANTERN_REQUIRE_GPU=1 (the README's test command sets it, since set-up always
// installs lavapipe and Xvfb): a test that finds no Vulkan device or no X server then fails
// instead of skipping. The sanitizer runs, which hide the Vulkan driver on purpose, leave it
// unset and skip.
bool gpu_required();

} // namespace lantern::test

// For a test that needs a Vulkan device or an X server and has none: skips with the reason
// (CTest reports it skipped), or fails with it under LANTERN_REQUIRE_GPU=1. Returns from the
// calling function, like GTEST_SKIP().
#define LANTERN_SKIP_NO_GPU(reason)                                                               \
    do {                                                                                         \
        if (::lantern::test::gpu_required()) {                                                   \
            GTEST_FAIL() << "LANTERN_REQUIRE_GPU=1, but: " << reason;                            \
        } else {                                                                                 \
            GTEST_SKIP() << reason;                                                              \
        }                                                                                        \
    } while (false)

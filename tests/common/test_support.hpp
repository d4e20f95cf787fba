// Helpers shared by the test suites: temporary folders, paths to the source tree and to
// ../shared (skipped cleanly when absent).
#pragma once

#include <filesystem>
#include <string>

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

} // namespace lantern::test

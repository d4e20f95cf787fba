// File helpers with the error contract of lantern::Result.
//
// Reading refuses, with exit code 2 and one line naming the path, anything that is not a
// regular file (a folder, a FIFO, a device: opened without blocking, checked before a byte
// is read) and any file over the caller's size limit (checked before reading, and again
// while reading in case it grows). The limits of each kind of input are documented in
// docs/scenes.md ("Size limits").
//
// write_file_atomic never leaves a half-written file: it writes a temporary file in the
// same folder, flushes it to disk, then renames it over the target, so a crash or kill at
// any moment leaves either the old contents or the new ones. Safe for untrusted paths in
// the sense that failures come back as messages; it does not sanitise the path.
#pragma once

#include "lantern/core/result.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace lantern {

// The documented size limits of Lantern's inputs (docs/scenes.md, "Size limits").
inline constexpr std::uint64_t max_scene_file_bytes = std::uint64_t(16) << 20; // scene files: 16 MiB
inline constexpr std::uint64_t max_map_file_bytes = std::uint64_t(256) << 20;  // Moving AI maps: 256 MiB
inline constexpr std::uint64_t max_save_file_bytes = std::uint64_t(64) << 20;  // saves: 64 MiB
inline constexpr std::uint64_t default_max_file_bytes = std::uint64_t(1) << 30; // anything else: 1 GiB

Result<std::string> read_text_file(const std::string& path, std::uint64_t max_bytes = default_max_file_bytes);
Result<std::vector<std::uint8_t>> read_binary_file(const std::string& path,
                                                   std::uint64_t max_bytes = default_max_file_bytes);

// Why `path` cannot be read as an input file (missing, unreadable, not a regular file),
// or nothing: a cheap check before the read (a save's map, before the world is made).
Result<void> check_input_file(const std::string& path);

// Why `path` cannot be an output file (a folder, a FIFO, a device, a missing or
// unwritable parent folder), or nothing when it can: checked before work starts, so a run
// refuses a bad output before it has written anything. Exit code 2.
Result<void> check_output_file(const std::string& path);

// The same for an output folder: an existing folder, writable, or a new one (created with
// its missing parents) inside the nearest existing folder, which must be writable.
Result<void> check_output_folder(const std::string& path);

// A folder of outputs written all or nothing (--dump): files are written into a hidden
// staging folder beside the target, and commit() moves them into the target (a new target
// is the staging folder renamed: one atomic step; into an existing one each file is
// renamed into place). Until commit() succeeds nothing appears at the target; a
// StagedFolder dropped without commit() removes its staging folder.
class StagedFolder {
  public:
    static Result<StagedFolder> create(const std::string& target);
    StagedFolder(StagedFolder&& other) noexcept;
    StagedFolder& operator=(StagedFolder&&) = delete;
    ~StagedFolder();

    // Where to write `name` (a file name, no folders) before commit().
    std::string file(const std::string& name) const;
    Result<void> commit();

  private:
    StagedFolder(std::string target, std::string staging) : target_(std::move(target)), staging_(std::move(staging)) {}
    std::string target_, staging_;
    bool done_ = false;
};

// Refuses (exit code 2) a target that exists and is not a regular file.
Result<void> write_file_atomic(const std::string& path, std::span<const std::byte> bytes);
Result<void> write_file_atomic(const std::string& path, const std::string& text);

// Creates the folder and its parents if missing.
Result<void> ensure_directory(const std::string& path);

// What a file is right now, to notice that it changed (hot reload): its device, inode, size
// and modification time. An atomic replace (a new inode) or an edit in place (size or
// time) both change it. nullopt when the path cannot be stat()ed.
struct FileStamp {
    std::uint64_t device = 0, inode = 0, size = 0;
    std::int64_t modified_ns = 0;
    friend bool operator==(const FileStamp&, const FileStamp&) = default;
};
std::optional<FileStamp> file_stamp(const std::string& path);

// Whether any of a set of files changed since it was last looked at: a scene file and the
// files it reads (world.map), for --watch. A file that appears, disappears or changes its
// FileStamp counts. Not thread-safe; one owner.
class FilesWatch {
  public:
    // Watches `paths` from now on: their stamps are taken now.
    void watch(std::vector<std::string> paths);
    // Takes the stamps again: true when any differs from the last look.
    bool changed();
    const std::vector<std::string>& paths() const { return paths_; }

  private:
    std::vector<std::string> paths_;
    std::vector<std::optional<FileStamp>> stamps_;
};

} // namespace lantern

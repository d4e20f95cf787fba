#include "lantern/core/file.hpp"

#include "common/test_support.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

using lantern::test::TempDir;

TEST(File, AtomicWriteCreatesAndReplaces) {
    TempDir dir;
    std::string path = dir.file("out.txt");
    ASSERT_TRUE(lantern::write_file_atomic(path, std::string("first")).ok());
    EXPECT_EQ(*lantern::read_text_file(path), "first");
    ASSERT_TRUE(lantern::write_file_atomic(path, std::string("second")).ok());
    EXPECT_EQ(*lantern::read_text_file(path), "second");
    // No temporary files are left behind.
    int entries = 0;
    for (auto& e : std::filesystem::directory_iterator(dir.path())) {
        (void)e;
        ++entries;
    }
    EXPECT_EQ(entries, 1);
}

TEST(File, ErrorsNameThePath) {
    TempDir dir;
    std::string path = dir.file("missing/folder/out.txt");
    auto r = lantern::write_file_atomic(path, std::string("x"));
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find(path), std::string::npos);
    auto read = lantern::read_text_file(dir.file("nope.txt"));
    ASSERT_FALSE(read.ok());
    EXPECT_NE(read.error().message.find("nope.txt"), std::string::npos);
}

TEST(File, KillDuringWriteLeavesOldOrNewContents) {
    TempDir dir;
    std::string path = dir.file("save.bin");
    const std::string old_contents(1000, 'o');
    ASSERT_TRUE(lantern::write_file_atomic(path, old_contents).ok());
    const std::string new_contents(64 * 1024 * 1024, 'n');
    for (int attempt = 0; attempt < 5; ++attempt) {
        pid_t child = fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            for (;;) (void)lantern::write_file_atomic(path, new_contents);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20 + 37 * attempt));
        kill(child, SIGKILL);
        int status = 0;
        waitpid(child, &status, 0);
        auto contents = lantern::read_text_file(path);
        ASSERT_TRUE(contents.ok());
        EXPECT_TRUE(*contents == old_contents || *contents == new_contents)
            << "partial file of " << contents->size() << " bytes";
    }
}

// Hostile paths: a folder, a FIFO with no writer, a device that never ends, a file over
// its limit. Each is refused with exit code 2 and one line naming the path, before a byte
// is read and without blocking.
TEST(File, ReadingRefusesWhatIsNotARegularFile) {
    TempDir dir;
    const std::string fifo = dir.file("pipe");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const std::string& path : {dir.path().string(), fifo, std::string("/dev/zero"), std::string("/dev/null")}) {
        auto r = lantern::read_text_file(path, lantern::max_scene_file_bytes);
        ASSERT_FALSE(r.ok()) << path;
        EXPECT_EQ(r.error().exit_code, 2) << path;
        EXPECT_NE(r.error().message.find(path + ": is "), std::string::npos) << r.error().message;
        EXPECT_NE(r.error().message.find("not a regular file"), std::string::npos) << r.error().message;
        EXPECT_EQ(r.error().message.find('\n'), std::string::npos);
    }
}

TEST(File, ReadingRefusesAFileOverItsLimit) {
    TempDir dir;
    const std::string path = dir.file("big.json");
    ASSERT_TRUE(lantern::write_file_atomic(path, std::string(1001, 'x')).ok());
    auto r = lantern::read_text_file(path, 1000);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().exit_code, 2);
    EXPECT_NE(r.error().message.find("1001 bytes, over the limit of 1000 bytes"), std::string::npos) << r.error().message;
    auto fits = lantern::read_text_file(path, 1001);
    ASSERT_TRUE(fits.ok());
    EXPECT_EQ(fits->size(), 1001u);
}

TEST(File, OutputsMustBeRegularFilesInAWritableFolder) {
    TempDir dir;
    const std::string fifo = dir.file("pipe");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    EXPECT_TRUE(lantern::check_output_file(dir.file("new.png")).ok());
    for (const std::string& bad : {dir.path().string(), fifo, std::string("/dev/null"), dir.file("no/such/out.png")}) {
        auto r = lantern::check_output_file(bad);
        ASSERT_FALSE(r.ok()) << bad;
        EXPECT_EQ(r.error().exit_code, 2);
    }
    // The atomic writer refuses them too, and leaves the FIFO a FIFO.
    EXPECT_FALSE(lantern::write_file_atomic(fifo, std::string("x")).ok());
    EXPECT_TRUE(std::filesystem::is_fifo(fifo));
    EXPECT_FALSE(lantern::write_file_atomic(dir.path().string(), std::string("x")).ok());
}

TEST(File, StagedFolderAppearsWholeOrNotAtAll) {
    TempDir dir;
    const std::string target = dir.file("dump");
    {
        auto staged = lantern::StagedFolder::create(target);
        ASSERT_TRUE(staged.ok()) << staged.error().message;
        ASSERT_TRUE(lantern::write_file_atomic(staged->file("a.pfm"), std::string("a")).ok());
        EXPECT_FALSE(std::filesystem::exists(target)); // nothing before commit
    } // dropped: nothing left, not even the staging folder
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
    auto staged = lantern::StagedFolder::create(target);
    ASSERT_TRUE(staged.ok());
    ASSERT_TRUE(lantern::write_file_atomic(staged->file("a.pfm"), std::string("a")).ok());
    ASSERT_TRUE(lantern::write_file_atomic(staged->file("b.pfm"), std::string("b")).ok());
    ASSERT_TRUE(staged->commit().ok());
    EXPECT_EQ(*lantern::read_text_file(target + "/b.pfm"), "b");
    // Into an existing folder: the files are moved in, other files stay.
    ASSERT_TRUE(lantern::write_file_atomic(target + "/keep.txt", std::string("k")).ok());
    auto again = lantern::StagedFolder::create(target);
    ASSERT_TRUE(again.ok());
    ASSERT_TRUE(lantern::write_file_atomic(again->file("a.pfm"), std::string("new")).ok());
    ASSERT_TRUE(again->commit().ok());
    EXPECT_EQ(*lantern::read_text_file(target + "/a.pfm"), "new");
    EXPECT_EQ(*lantern::read_text_file(target + "/keep.txt"), "k");
    int entries = 0;
    for (auto& e : std::filesystem::directory_iterator(dir.path())) entries += e.path().filename().string()[0] == '.';
    EXPECT_EQ(entries, 0) << "a staging folder was left behind";
    // Missing parents are created; a target under a file, or a file, is refused before
    // anything is created.
    EXPECT_TRUE(lantern::StagedFolder::create(dir.file("new/parents/dump")).ok());
    EXPECT_FALSE(lantern::StagedFolder::create(target + "/keep.txt").ok());
    EXPECT_FALSE(lantern::StagedFolder::create(target + "/keep.txt/dump").ok());
}

// FileStamp (hot reload): the same while a file is untouched; changed by an atomic replace,
// even with the same size and contents, and by an edit in place; absent for a missing path.
TEST(File, StampChangesWithEveryKindOfEdit) {
    lantern::test::TempDir dir;
    const std::string path = dir.file("scene.json");
    EXPECT_FALSE(lantern::file_stamp(path));
    ASSERT_TRUE(lantern::write_file_atomic(path, std::string("{\"a\": 1}")));
    const auto first = lantern::file_stamp(path);
    ASSERT_TRUE(first);
    EXPECT_EQ(lantern::file_stamp(path), first);
    EXPECT_EQ(first->size, 8u);
    ASSERT_TRUE(lantern::write_file_atomic(path, std::string("{\"a\": 1}"))); // same bytes, a new file
    const auto replaced = lantern::file_stamp(path);
    ASSERT_TRUE(replaced);
    EXPECT_NE(replaced, first);
    {
        std::FILE* f = std::fopen(path.c_str(), "ab"); // in place: longer
        ASSERT_NE(f, nullptr);
        std::fputs(" ", f);
        std::fclose(f);
    }
    const auto appended = lantern::file_stamp(path);
    ASSERT_TRUE(appended);
    EXPECT_NE(appended, replaced);
    EXPECT_EQ(appended->inode, replaced->inode);
    std::filesystem::remove(path);
    EXPECT_FALSE(lantern::file_stamp(path));
}

// FilesWatch (--watch of a scene and its map): nothing changed, nothing reported; an edit of
// any watched file, its removal and its return each reported once.
TEST(File, FilesWatchReportsAChangeOfAnyWatchedFileOnce) {
    lantern::test::TempDir dir;
    const std::string scene = dir.file("level.json"), map = dir.file("level.map");
    ASSERT_TRUE(lantern::write_file_atomic(scene, std::string("{}")));
    ASSERT_TRUE(lantern::write_file_atomic(map, std::string("type octile")));
    lantern::FilesWatch watch;
    EXPECT_FALSE(watch.changed()); // watching nothing
    watch.watch({scene, map});
    EXPECT_EQ(watch.paths(), (std::vector<std::string>{scene, map}));
    EXPECT_FALSE(watch.changed());
    ASSERT_TRUE(lantern::write_file_atomic(map, std::string("type octile")));
    EXPECT_TRUE(watch.changed());
    EXPECT_FALSE(watch.changed()) << "one edit, reported twice";
    std::filesystem::remove(scene);
    EXPECT_TRUE(watch.changed());
    EXPECT_FALSE(watch.changed());
    ASSERT_TRUE(lantern::write_file_atomic(scene, std::string("{}")));
    EXPECT_TRUE(watch.changed());
    // watch() takes the stamps afresh: earlier edits are not reported.
    ASSERT_TRUE(lantern::write_file_atomic(map, std::string("type octile\n")));
    watch.watch({scene, map});
    EXPECT_FALSE(watch.changed());
}

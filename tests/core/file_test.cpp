#include "lantern/core/file.hpp"

#include "common/test_support.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <string>
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

// lantern-render as users run it: the real executable, real files, exit statuses.
#include "common/test_support.hpp"
#include "lantern/core/file.hpp"
#include "lantern/scene/loader.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>
#include <sys/stat.h>
#include <sys/wait.h>

namespace fs = std::filesystem;
using lantern::test::TempDir;

namespace {

struct RunResult {
    int status = -1;
    std::string output; // stdout + stderr
};

RunResult run_exe(const std::string& exe, const std::string& args) {
    RunResult r;
    const std::string cmd = exe + " " + args + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    char buf[4096];
    std::size_t n;
    while ((n = fread(buf, 1, sizeof(buf), p)) > 0) r.output.append(buf, n);
    int status = pclose(p);
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

RunResult run(const std::string& args) { return run_exe(LANTERN_RENDER_EXE, args); }

void write(const fs::path& path, const std::string& text) {
    std::ofstream(path) << text;
}

const char* small_scene = R"({
  "lantern_scene": 1,
  "world": { "rows": ["##########", "#........#", "#..#.....#", "#........#", "##########"] },
  "view": { "center": [5.0, 2.5], "size": [10.0, 5.0] },
  "gi": { "resolution": 4, "padding": 1.0, "heat_rounds": 4 },
  "point_lights": [ { "position": [2.5, 2.5], "color": [1.0, 0.6, 0.3], "intensity": 2.0, "radius": 6.0 } ]
})";

std::size_t file_count(const fs::path& dir) {
    std::size_t n = 0;
    for (auto& e : fs::recursive_directory_iterator(dir)) n += e.is_regular_file();
    return n;
}

} // namespace

TEST(RenderCli, HelpAndUsageErrors) {
    auto help = run("--help");
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.output.find("--dump DIR"), std::string::npos);
    EXPECT_EQ(run("").status, 2);
    EXPECT_EQ(run("a.json --backend metal").status, 2);
    EXPECT_EQ(run("a.json --bogus").status, 2);
    EXPECT_EQ(run("a.json --out").status, 2);
}

// Every executable parses its command line with core's cli::Parser: --help and --version
// answer with exit 0, bad options with one line and exit 2.
TEST(EveryExecutable, HelpVersionAndBadOptions) {
    const std::vector<std::pair<std::string, std::string>> programs = {
        {LANTERN_RENDER_EXE, "lantern-render"},
        {LANTERN_BENCH_EXE, "lantern-bench"},
        {std::string(LANTERN_BENCH_EXE) + " accuracy", "lantern-bench accuracy"},
        {std::string(LANTERN_BENCH_EXE) + " seed-table", "lantern-bench seed-table"},
        {std::string(LANTERN_BENCH_EXE) + " baked", "lantern-bench baked"},
        {LANTERN_DEMO_EXE, "lantern-demo"},
        {LANTERN_GAME_EXE, "lantern"},
        {LANTERN_BAKE_EXE, "lantern-bake"},
    };
    for (const auto& [exe, name] : programs) {
        const RunResult help = run_exe(exe, "--help");
        EXPECT_EQ(help.status, 0) << name << ": " << help.output;
        EXPECT_EQ(help.output.rfind("usage: " + name + " ", 0), 0u) << name << ": " << help.output;
        EXPECT_NE(help.output.find("--version"), std::string::npos) << name;
        const RunResult version = run_exe(exe, "--version");
        EXPECT_EQ(version.status, 0) << name << ": " << version.output;
        EXPECT_EQ(version.output.rfind(name + " (Lantern ", 0), 0u) << name << ": " << version.output;
        const RunResult bad = run_exe(exe, "--bogus");
        EXPECT_EQ(bad.status, 2) << name << ": " << bad.output;
        EXPECT_EQ(bad.output, name + ": unknown option '--bogus' (see --help)\n");
    }
    // Values: in range, of the right kind, present; one line each.
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"a.json --frames 0", "lantern-render: --frames: must be an integer in [1, 100000], got '0' (see --help)\n"},
        {"a.json --frames=x", "lantern-render: --frames: must be an integer in [1, 100000], got 'x' (see --help)\n"},
        {"a.json --backend metal", "lantern-render: --backend: must be vulkan or cpu, got 'metal' (see --help)\n"},
        {"a.json --out", "lantern-render: --out needs a value (IMAGE.png) (see --help)\n"},
        {"a.json b.json", "lantern-render: more than one scene file given ('a.json' and 'b.json') (see --help)\n"},
        {"", "lantern-render: no scene file given (see --help)\n"},
        {"--quiet=yes a.json", "lantern-render: --quiet takes no value (see --help)\n"},
    };
    for (const auto& [args, expect] : cases) {
        const RunResult r = run(args);
        EXPECT_EQ(r.status, 2) << args;
        EXPECT_EQ(r.output, expect) << args;
    }
    const RunResult unknown = run_exe(LANTERN_BENCH_EXE, "plot");
    EXPECT_EQ(unknown.status, 2);
    EXPECT_EQ(unknown.output, "lantern-bench: unknown command 'plot' (see --help)\n");
    const RunResult none = run_exe(LANTERN_BENCH_EXE, "");
    EXPECT_EQ(none.status, 2);
    EXPECT_EQ(none.output, "lantern-bench: no command given (see --help)\n");
}

TEST(RenderCli, BadScenesExitTwoAndWriteNothing) {
    TempDir dir;
    struct Case {
        const char* name;
        std::string text;
        const char* expect; // part of the one-line message
    };
    const std::vector<Case> cases = {
        {"malformed.json", "{ \"lantern_scene\": 1, ", "bad.json"},
        {"missing_key.json", R"({"lantern_scene": 1, "view": {"center": [0,0]}})", "world"},
        {"wrong_type.json", std::string(small_scene).replace(std::string(small_scene).find("\"resolution\": 4"), 15, "\"resolution\": \"4\""), "gi.resolution"},
        {"negative_radius.json", std::string(small_scene).replace(std::string(small_scene).find("\"radius\": 6.0"), 13, "\"radius\": -6.0"), "radius"},
        {"missing_map.json", R"({"lantern_scene": 1, "world": {"map": "nowhere.map"}, "view": {"center": [0,0], "size": [4,4]}})", "nowhere.map"},
        {"huge.json", R"({"lantern_scene": 1, "world": {"rows": ["."]}, "view": {"center": [0,0], "size": [1e9, 4]}})", "view"},
    };
    for (const Case& c : cases) {
        const fs::path scene = dir.path() / c.name;
        write(scene, c.text);
        const fs::path out = dir.path() / "out";
        fs::create_directories(out);
        auto r = run(scene.string() + " --backend cpu --out " + (out / "img.png").string() + " --dump " +
                     (out / "dump").string() + " --timings " + (out / "t.json").string());
        EXPECT_EQ(r.status, 2) << c.name << ": " << r.output;
        EXPECT_EQ(file_count(out), 0u) << c.name << " wrote output";
        EXPECT_NE(r.output.find(std::string(c.name) == "malformed.json" ? "malformed.json:" : c.expect), std::string::npos)
            << c.name << ": " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one clear message: " << r.output;
    }
    // A map file with an unknown character: file, line and column of the map.
    write(dir.path() / "bad.map", "type octile\nheight 2\nwidth 3\nmap\n...\n.x.\n");
    write(dir.path() / "map_scene.json",
          R"({"lantern_scene": 1, "world": {"map": "bad.map"}, "view": {"center": [1,1], "size": [4,4]}})");
    auto r = run((dir.path() / "map_scene.json").string() + " --backend cpu");
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("bad.map:6:2"), std::string::npos) << r.output;
    // --set errors name the override.
    write(dir.path() / "ok.json", small_scene);
    auto s = run((dir.path() / "ok.json").string() + " --backend cpu --set gi.resolution=99");
    EXPECT_EQ(s.status, 2);
    EXPECT_NE(s.output.find("--set gi.resolution"), std::string::npos) << s.output;
}

// Every path that is not a regular file (a folder, a FIFO, a device), and every output that
// cannot be written, is refused with exit 2 and one line before any work: no wait on a
// FIFO, no endless read of /dev/zero, nothing written, no staging or .tmp files left.
TEST(RenderCli, HostilePathsAreRefusedBeforeWork) {
    TempDir dir;
    write(dir.path() / "ok.json", small_scene);
    const std::string ok = (dir.path() / "ok.json").string();
    const fs::path fifo = dir.path() / "pipe";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    write(dir.path() / "fifo_map.json",
          R"({"lantern_scene": 1, "world": {"map": "pipe"}, "view": {"center": [1,1], "size": [4,4]}})");
    const fs::path out = dir.path() / "out";
    fs::create_directories(out);
    struct Case {
        std::string args;
        const char* expect;
    };
    const std::vector<Case> cases = {
        {dir.path().string(), "is a folder, not a regular file"},
        {fifo.string(), "is a FIFO, not a regular file"},
        {"/dev/zero", "is a character device, not a regular file"},
        {(dir.path() / "fifo_map.json").string(), "is a FIFO, not a regular file"},
        {ok + " --out " + out.string(), "is a folder, not a regular file"},
        {ok + " --timings " + fifo.string(), "is a FIFO, not a regular file"},
        {ok + " --out /dev/null", "is a character device"},
        {ok + " --dump " + ok, "not a folder"},
        {ok + " --out " + (out / "no" / "such" / "img.png").string(), "does not exist"},
        {ok + " --dump " + (out / "d").string() + " --out " + out.string(), "is a folder"},
    };
    for (const Case& c : cases) {
        auto r = run(c.args + " --backend cpu --quiet");
        EXPECT_EQ(r.status, 2) << c.args << ": " << r.output;
        EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << ": " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one clear message: " << r.output;
        EXPECT_EQ(file_count(out), 0u) << c.args << " wrote output";
    }
    for (const auto& e : fs::directory_iterator(dir.path()))
        EXPECT_NE(e.path().filename().string()[0], '.') << "left behind: " << e.path();
    EXPECT_TRUE(fs::is_fifo(fifo));
}

// A frame over the GI memory budget (docs/gi.md) is refused before anything is allocated,
// on both backends, and the run leaves nothing behind.
TEST(RenderCli, AFrameOverTheMemoryBudgetFailsAndWritesNothing) {
    TempDir dir;
    write(dir.path() / "huge.json", R"({"lantern_scene": 1, "world": {"rows": ["."]},
        "view": {"center": [0, 0], "size": [1800, 1800]}, "gi": {"resolution": 4, "padding": 1.25}})");
    const fs::path out = dir.path() / "out";
    fs::create_directories(out);
    for (const char* backend : {"cpu", "vulkan"}) {
        auto r = run((dir.path() / "huge.json").string() + " --quiet --backend " + backend + " --timings " +
                     (out / "t.json").string() + " --dump " + (out / "dump").string());
        if (std::string(backend) == "vulkan" && r.output.find("try --backend cpu") != std::string::npos) continue;
        EXPECT_EQ(r.status, 2) << backend << ": " << r.output;
        EXPECT_NE(r.output.find("over the budget of 2048 MiB"), std::string::npos) << backend << ": " << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << "one clear message: " << r.output;
        EXPECT_EQ(file_count(out), 0u) << backend;
        EXPECT_FALSE(fs::exists(out / "dump")) << backend;
    }
    for (const auto& e : fs::directory_iterator(out)) ADD_FAILURE() << "left behind: " << e.path();
}

TEST(RenderCli, DumpTimingsAndImageOnTheCpuBackend) {
    TempDir dir;
    write(dir.path() / "scene.json", small_scene);
    auto r = run((dir.path() / "scene.json").string() + " --backend cpu --quiet --out " + dir.file("img.png") +
                 " --dump " + dir.file("dump") + " --timings " + dir.file("t.json") + " --set gi.ao.enabled=false");
    ASSERT_EQ(r.status, 0) << r.output;
    // PNG signature.
    std::string png = lantern::test::read_file(dir.path() / "img.png");
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png.substr(1, 3), "PNG");
    // Every texture of the frame, named by the contract; AO was turned off: no ao.pfm.
    for (const char* name : {"conduction", "direct", "shadow", "wall_direct_px", "wall_direct_nx", "wall_direct_pz",
                             "wall_direct_nz", "emission", "indirect", "wall_indirect_px", "wall_indirect_nz"})
        EXPECT_TRUE(fs::exists(dir.path() / "dump" / (std::string(name) + ".pfm"))) << name;
    EXPECT_FALSE(fs::exists(dir.path() / "dump" / "ao.pfm"));
    // PFM layout: colour "PF", greyscale "Pf", little-endian scale; 64 x 64 (the minimum size).
    std::string pfm = lantern::test::read_file(dir.path() / "dump" / "direct.pfm");
    EXPECT_EQ(pfm.rfind("PF\n64 64\n-1.0\n", 0), 0u);
    EXPECT_EQ(pfm.size(), std::string("PF\n64 64\n-1.0\n").size() + 64 * 64 * 3 * 4);
    std::string cond = lantern::test::read_file(dir.path() / "dump" / "conduction.pfm");
    ASSERT_EQ(cond.rfind("Pf\n64 64\n-1.0\n", 0), 0u);
    // First stored row = texture row 0 = world z in [0, 0.25): the wall row, conduction 0.
    float first;
    std::memcpy(&first, cond.data() + std::string("Pf\n64 64\n-1.0\n").size() + 4 * 20, 4);
    EXPECT_EQ(first, 0.0f);
    auto t = nlohmann::json::parse(lantern::test::read_file(dir.path() / "t.json"));
    EXPECT_EQ(t["texture_size"], nlohmann::json::array({64, 64}));
    EXPECT_EQ(t["camera_view"], nlohmann::json::array({0.0, 0.0, 16.0, 16.0}));
    EXPECT_TRUE(t.contains("device"));
    bool saw_ao = false;
    for (const auto& p : t["passes"]) {
        EXPECT_TRUE(p.contains("name") && p.contains("ran") && p.contains("gpu_ms"));
        if (p["name"] == "ao") {
            saw_ao = true;
            EXPECT_FALSE(p["ran"].get<bool>());
            EXPECT_EQ(p["reason"], "not needed: AO disabled");
        }
    }
    EXPECT_TRUE(saw_ao);
}

TEST(RenderCli, VulkanAndCpuBackendsAgree) {
    TempDir dir;
    write(dir.path() / "scene.json", small_scene);
    auto v = run((dir.path() / "scene.json").string() + " --quiet --out " + dir.file("v.png"));
    if (v.status == 1 && v.output.find("no Vulkan device") != std::string::npos) LANTERN_SKIP_NO_GPU(v.output);
    ASSERT_EQ(v.status, 0) << v.output;
    auto c = run((dir.path() / "scene.json").string() + " --quiet --backend cpu --out " + dir.file("c.png"));
    ASSERT_EQ(c.status, 0) << c.output;
    EXPECT_EQ(lantern::test::read_file(dir.path() / "v.png"), lantern::test::read_file(dir.path() / "c.png"));
}

// lantern-bake end to end: a scene with a baked light bakes its chunks with a summary line,
// a second run reuses them all, a damaged file is named and re-baked; bad input exits 2
// with one line and writes nothing.
// Waits until a watching lantern-render has printed these attempt counts (a generous deadline
// turns a tool that never gets there into a failure, not a hang).
bool watch_counts_reach(lantern::test::ChildProcess& render, const fs::path& log, int rendered, int refused) {
    const std::string line = "watch: " + std::to_string(rendered) + " rendered, " + std::to_string(refused) + " refused";
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(180);
    while (std::chrono::steady_clock::now() < end) {
        if (lantern::test::read_file(log).find(line) != std::string::npos) return true;
        if (render.wait_exit(std::chrono::milliseconds(10))) break;
    }
    ADD_FAILURE() << "never printed '" << line << "':\n" << lantern::test::read_file(log);
    return false;
}

// lantern-render --watch as a designer uses it: a render per change of the scene file; a
// malformed edit (100 random corruptions in a row) is refused with its position, writes
// nothing, and the image keeps the last good render; the next good edit renders again.
// Each step waits on the attempt counts lantern-render prints, never on time.
TEST(RenderCli, WatchRendersEachEditAndKeepsTheLastGoodRender) {
    TempDir dir;
    const fs::path scene = dir.path() / "watched.json", out = dir.path() / "out.png", log = dir.path() / "log.txt";
    ASSERT_TRUE(lantern::write_file_atomic(scene.string(), std::string(small_scene)));
    lantern::test::ChildProcess render(LANTERN_RENDER_EXE,
                                       {scene.string(), "--backend", "cpu", "--watch", "--out", out.string()},
                                       log.string());
    ASSERT_TRUE(render.started());
    const auto until = [&](int rendered, int refused) { return watch_counts_reach(render, log, rendered, refused); };
    ASSERT_TRUE(until(1, 0));
    const std::string first = lantern::test::read_file(out);
    ASSERT_FALSE(first.empty());

    std::uint64_t random = 7;
    for (int k = 1; k <= 100; ++k) {
        const std::string bad = lantern::test::corrupting_edit(small_scene, random, [&](const std::string& text) {
            return !lantern::scene::parse_scene(text, "bad.json", dir.path().string());
        });
        ASSERT_TRUE(lantern::write_file_atomic(scene.string(), bad));
        ASSERT_TRUE(until(1, k)) << "edit " << k;
    }
    EXPECT_EQ(lantern::test::read_file(out), first); // the last good render, untouched
    const std::string text = lantern::test::read_file(log);
    EXPECT_NE(text.find("lantern-render: " + scene.string() + ":"), std::string::npos) << text; // positioned errors

    std::string bluer = small_scene;
    const std::string colour = "\"color\": [1.0, 0.6, 0.3]";
    bluer.replace(bluer.find(colour), colour.size(), "\"color\": [0.3, 0.6, 1.0]");
    ASSERT_TRUE(lantern::write_file_atomic(scene.string(), bluer));
    ASSERT_TRUE(until(2, 100));
    EXPECT_NE(lantern::test::read_file(out), first);
}

// --watch also looks at the map a scene reads (world.map): an edit of the map renders again,
// a broken map is refused and keeps the last good render, the mended map renders. On Vulkan,
// whose device and GI renderer the watch keeps between renders: the mended map's image is
// the first one byte for byte (nothing of the renders between leaks into it).
TEST(RenderCli, WatchRendersEachEditOfTheScenesMap) {
    TempDir dir;
    const fs::path scene = dir.path() / "level.json", map = dir.path() / "level.map", out = dir.path() / "out.png",
                   log = dir.path() / "log.txt";
    const std::string open_map = "type octile\nheight 5\nwidth 10\nmap\n@@@@@@@@@@\n@........@\n@........@\n"
                                 "@........@\n@@@@@@@@@@\n";
    ASSERT_TRUE(lantern::write_file_atomic(map.string(), open_map));
    ASSERT_TRUE(lantern::write_file_atomic(scene.string(), std::string(R"({
  "lantern_scene": 1,
  "world": { "map": "level.map" },
  "view": { "center": [5.0, 2.5], "size": [10.0, 5.0] },
  "gi": { "resolution": 4, "padding": 1.0, "heat_rounds": 4 },
  "point_lights": [ { "position": [2.5, 2.5], "color": [1.0, 0.6, 0.3], "intensity": 2.0, "radius": 6.0 } ]
})")));
    lantern::test::ChildProcess render(LANTERN_RENDER_EXE,
                                       {scene.string(), "--backend", "vulkan", "--watch", "--out", out.string()},
                                       log.string());
    ASSERT_TRUE(render.started());
    const auto until = [&](int rendered, int refused) { return watch_counts_reach(render, log, rendered, refused); };
    {
        // No device: lantern-render exits 1 before its first render.
        const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(180);
        while (std::chrono::steady_clock::now() < end &&
               lantern::test::read_file(log).find("watch: 1 rendered") == std::string::npos)
            if (const auto code = render.wait_exit(std::chrono::milliseconds(10))) {
                const std::string text = lantern::test::read_file(log);
                if (*code == 1 && text.find("no Vulkan device") != std::string::npos) LANTERN_SKIP_NO_GPU(text);
                break;
            }
    }
    ASSERT_TRUE(until(1, 0));
    const std::string first = lantern::test::read_file(out);
    ASSERT_FALSE(first.empty());
    std::string walled = open_map;
    walled.replace(walled.find("@........@\n@@@@"), 10, "@...@@...@"); // two wall tiles by the light
    ASSERT_TRUE(lantern::write_file_atomic(map.string(), walled));
    ASSERT_TRUE(until(2, 0));
    const std::string second = lantern::test::read_file(out);
    EXPECT_NE(second, first);
    ASSERT_TRUE(lantern::write_file_atomic(map.string(), walled.substr(0, walled.size() - 6) + "?\n")); // a bad char
    ASSERT_TRUE(until(2, 1));
    EXPECT_EQ(lantern::test::read_file(out), second);
    EXPECT_NE(lantern::test::read_file(log).find("level.map"), std::string::npos);
    ASSERT_TRUE(lantern::write_file_atomic(map.string(), open_map));
    ASSERT_TRUE(until(3, 1));
    EXPECT_EQ(lantern::test::read_file(out), first);
}

TEST(BakeCli, BakesReusesAndRefusesBadInput) {
    TempDir dir;
    write(dir.path() / "s.json", R"({
  "lantern_scene": 1,
  "materials": [ { "name": "lava", "albedo": [0.3, 0.1, 0.05], "emission": [1.5, 0.5, 0.1], "symbol": "L" } ],
  "world": { "rows": ["##########", "#........#", "#..#.....L", "#........#", "##########"], "origin": [30, 30] },
  "view": { "center": [35.0, 32.5] },
  "point_lights": [ { "position": [32.5, 32.5], "radius": 6.0, "mode": "baked" } ]
})");
    const std::string out = (dir.path() / "cache").string();
    const RunResult first = run_exe(LANTERN_BAKE_EXE, (dir.path() / "s.json").string() + " --out " + out + " --resolution 2 --margin 2");
    ASSERT_EQ(first.status, 0) << first.output;
    // Tiles 30..39 x 30..34 touch chunks (0, 0) and (1, 0), (0, 1) and (1, 1).
    EXPECT_NE(first.output.find("4 chunks: 4 baked, 0 reused"), std::string::npos) << first.output;
    EXPECT_EQ(file_count(out), 4u);
    const RunResult second = run_exe(LANTERN_BAKE_EXE, (dir.path() / "s.json").string() + " --out " + out + " --resolution 2 --margin 2");
    ASSERT_EQ(second.status, 0) << second.output;
    EXPECT_NE(second.output.find("4 chunks: 0 baked, 4 reused"), std::string::npos) << second.output;
    write(fs::path(out) / "chunk_0_0.lbk", "not a bake");
    const RunResult third = run_exe(LANTERN_BAKE_EXE, (dir.path() / "s.json").string() + " --out " + out + " --resolution 2 --margin 2");
    ASSERT_EQ(third.status, 0) << third.output;
    EXPECT_NE(third.output.find("chunk_0_0.lbk: truncated (10 bytes); baking it again"), std::string::npos) << third.output;
    EXPECT_NE(third.output.find("1 baked, 3 reused"), std::string::npos) << third.output;
    const std::vector<std::pair<std::string, std::string>> bad = {
        {"--out x", "lantern-bake: WORLD is required (see --help)\n"},
        {(dir.path() / "s.json").string(), "lantern-bake: --out DIR is required (see --help)\n"},
        {"a.json --out x --shard 4/4", "lantern-bake: --shard: expected I/N with 0 <= I < N (e.g. 0/4), got '4/4' (see --help)\n"},
        {(dir.path() / "none.json").string() + " --out x", (dir.path() / "none.json").string() + ": cannot open: No such file or directory\n"},
    };
    for (const auto& [args, expect] : bad) {
        const RunResult r = run_exe(LANTERN_BAKE_EXE, args);
        EXPECT_EQ(r.status, 2) << args;
        EXPECT_EQ(r.output, expect) << args;
    }
    EXPECT_FALSE(fs::exists("x")) << "bad input writes nothing";
}

namespace {

// A colour PFM as lantern-render --dump writes it (docs/scenes.md): RGB floats, rows in order.
std::vector<float> read_pfm_rgb(const fs::path& path, int& width, int& height) {
    const std::string bytes = lantern::test::read_file(path);
    std::size_t at = 0;
    auto token = [&] {
        while (at < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
        const std::size_t start = at;
        while (at < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
        return bytes.substr(start, at - start);
    };
    if (token() != "PF") return {};
    width = std::stoi(token());
    height = std::stoi(token());
    token(); // scale
    ++at;    // the one whitespace byte before the data
    std::vector<float> out(std::size_t(width) * std::size_t(height) * 3);
    if (bytes.size() < at + out.size() * 4) return {};
    std::memcpy(out.data(), bytes.data() + at, out.size() * 4);
    return out;
}

// Ground light the frame dumped: direct + indirect, per texel and channel.
std::vector<float> ground_light(const fs::path& dump) {
    int w = 0, h = 0, w2 = 0, h2 = 0;
    std::vector<float> direct = read_pfm_rgb(dump / "direct.pfm", w, h), indirect = read_pfm_rgb(dump / "indirect.pfm", w2, h2);
    if (direct.empty() || indirect.size() != direct.size()) return {};
    for (std::size_t i = 0; i < direct.size(); ++i) direct[i] += indirect[i];
    return direct;
}

} // namespace

// lantern-render --bake: the scene's baked light and glowing lava come from its bake (baked
// first where missing), the frame adds them in its `baked` pass and the live passes leave
// them out; with the live method the bake's solver at the bake's settings the picture is
// the live one, on both backends.
TEST(RenderCli, ABakeLightsTheSceneAsTheLivePassesDo) {
    TempDir dir;
    const std::string scene = R"({
  "lantern_scene": 1,
  "materials": [ { "name": "lava", "albedo": [0.3, 0.1, 0.05], "emission": [1.5, 0.5, 0.1], "symbol": "L" } ],
  "world": { "rows": ["##########", "#........#", "#..#.....L", "#........#", "##########"], "origin": [30, 30] },
  "view": { "center": [35.0, 32.5], "size": [10.0, 5.0] },
  "gi": { "method": "gather", "resolution": 2, "padding": 1.0, "blur": false, "ao": { "enabled": false },
          "gather": { "scale": "full", "margin": 2, "rays": 32, "face_rays": 32, "frames": 1, "bounces": 4 } },
  "point_lights": [ { "position": [32.5, 32.5], "radius": 6.0, "mode": "MODE" } ]
})";
    auto with_mode = [&](const char* mode) {
        std::string s = scene;
        s.replace(s.find("MODE"), 4, mode);
        return s;
    };
    write(dir.path() / "baked.json", with_mode("baked"));
    write(dir.path() / "live.json", with_mode("realtime"));
    // A margin of 8 tiles: every chunk's solve sees the whole room (the lava too).
    const std::string bake = " --bake " + dir.file("cache") + " --bake-resolution 2 --bake-margin 8 --bake-rays 32 --bake-face-rays 32";
    for (const char* backend : {"cpu", "vulkan"}) {
        const std::string b = std::string(" --backend ") + backend;
        const RunResult live = run(dir.file("live.json") + b + " --quiet --dump " + dir.file(std::string("live_") + backend));
        if (live.status == 1 && live.output.find("no Vulkan device") != std::string::npos) LANTERN_SKIP_NO_GPU(live.output);
        ASSERT_EQ(live.status, 0) << live.output;
        const RunResult baked = run(dir.file("baked.json") + b + bake + " --timings " + dir.file("t.json") + " --dump " +
                                    dir.file(std::string("baked_") + backend));
        ASSERT_EQ(baked.status, 0) << baked.output;
        // The first run bakes (with progress), the second reuses the cache.
        EXPECT_NE(baked.output.find(std::string(backend) == "cpu" ? "(0 reused)" : "(4 reused)"), std::string::npos) << baked.output;
        auto t = nlohmann::json::parse(lantern::test::read_file(dir.path() / "t.json"));
        EXPECT_EQ(t["lights"]["point"], 0) << "the baked light left the live passes";
        bool ran = false;
        for (const auto& p : t["passes"])
            if (p["name"] == "baked") ran = p["ran"].get<bool>();
        EXPECT_TRUE(ran);
        const std::vector<float> a = ground_light(dir.path() / (std::string("live_") + backend)),
                                 c = ground_light(dir.path() / (std::string("baked_") + backend));
        ASSERT_FALSE(a.empty());
        ASSERT_EQ(a.size(), c.size());
        double err2 = 0.0, ref2 = 0.0;
        for (std::size_t i = 0; i < a.size(); ++i) {
            err2 += double(c[i] - a[i]) * double(c[i] - a[i]);
            ref2 += double(a[i]) * double(a[i]);
        }
        std::printf("%s: baked against live, relative RMS %.3f %%\n", backend, 100.0 * std::sqrt(err2 / ref2));
        EXPECT_LT(std::sqrt(err2 / ref2), 0.02) << backend;
        EXPECT_GT(ref2, 1.0);
    }
}

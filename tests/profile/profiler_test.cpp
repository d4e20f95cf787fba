#include "lantern/profile/profiler.hpp"

#include "common/test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <set>
#include <thread>

namespace profile = lantern::profile;

namespace {

class Profiler : public ::testing::Test {
  protected:
    void SetUp() override {
        profile::reset();
        profile::set_history_size(300);
        profile::set_enabled(true);
    }
    void TearDown() override {
        profile::set_enabled(false);
        profile::reset();
    }
};

const profile::ScopeStats* find(const std::vector<profile::ScopeStats>& stats, const char* name,
                                 profile::LaneKind kind = profile::LaneKind::cpu) {
    for (const auto& s : stats)
        if (std::strcmp(s.name, name) == 0 && s.kind == kind) return &s;
    return nullptr;
}

} // namespace

TEST(Percentiles, NearestRank) {
    std::vector<double> v;
    for (int i = 1; i <= 100; ++i) v.push_back(double(101 - i)); // 100..1, last = 1
    auto p = profile::percentiles(v);
    EXPECT_EQ(p.count, 100u);
    EXPECT_DOUBLE_EQ(p.last, 1.0);
    EXPECT_DOUBLE_EQ(p.mean, 50.5);
    EXPECT_DOUBLE_EQ(p.p50, 50.0);
    EXPECT_DOUBLE_EQ(p.p95, 95.0);
    EXPECT_DOUBLE_EQ(p.p99, 99.0);
    EXPECT_DOUBLE_EQ(p.max, 100.0);
    EXPECT_EQ(profile::percentiles({}).count, 0u);
}

TEST_F(Profiler, StatsSumSpansPerFrame) {
    // Frame k holds two spans of "update" lasting k ms each and one "render" of 1 ms.
    for (int k = 1; k <= 10; ++k) {
        profile::begin_frame();
        std::int64_t t = 1'000'000'000;
        profile::record("update", t, t + k * 1'000'000);
        profile::record("update", t, t + k * 1'000'000);
        profile::record("render", t, t + 1'000'000);
        profile::end_frame();
    }
    auto stats = profile::stats();
    const auto* update = find(stats, "update");
    ASSERT_NE(update, nullptr);
    EXPECT_EQ(update->frames_seen, 10u);
    EXPECT_DOUBLE_EQ(update->calls_per_frame, 2.0);
    EXPECT_DOUBLE_EQ(update->last_ms, 20.0);
    EXPECT_DOUBLE_EQ(update->max_ms, 20.0);
    EXPECT_DOUBLE_EQ(update->mean_ms, 11.0);
    EXPECT_DOUBLE_EQ(update->p50_ms, 10.0);
    const auto* render = find(stats, "render");
    ASSERT_NE(render, nullptr);
    EXPECT_DOUBLE_EQ(render->p99_ms, 1.0);
}

TEST_F(Profiler, HistoryKeepsLastFrames) {
    profile::set_history_size(4);
    for (int k = 0; k < 10; ++k) {
        profile::begin_frame();
        profile::record("x", 0, 1000 * (k + 1));
        profile::end_frame();
    }
    auto frames = profile::history();
    ASSERT_EQ(frames.size(), 4u);
    EXPECT_LT(frames[0]->index, frames[3]->index);
    EXPECT_EQ(frames[3]->events.size(), 1u);
    EXPECT_EQ(frames[3]->events[0].end_ns, 10000);
    EXPECT_EQ(profile::frame_time_ms().count, 4u);
}

TEST_F(Profiler, ScopesFromManyThreadsLandOnTheirLanes) {
    profile::begin_frame();
    std::vector<std::thread> threads;
    for (int t = 0; t < 3; ++t)
        threads.emplace_back([t] {
            std::string name = "thread-under-test " + std::to_string(t);
            profile::set_thread_name(profile::intern(name));
            for (int i = 0; i < 100; ++i) LANTERN_PROFILE_SCOPE("work");
        });
    for (auto& th : threads) th.join();
    profile::end_frame();
    std::set<std::uint32_t> lanes;
    int count = 0;
    for (const auto& e : profile::history().back()->events)
        if (std::strcmp(e.name, "work") == 0) {
            lanes.insert(e.lane);
            ++count;
        }
    EXPECT_EQ(count, 300);
    EXPECT_EQ(lanes.size(), 3u);
    auto all = profile::lanes();
    for (std::uint32_t lane : lanes) EXPECT_NE(all[lane].name.find("thread-under-test"), std::string::npos);
}

TEST_F(Profiler, DisabledRecordsNothing) {
    profile::set_enabled(false);
    profile::begin_frame();
    { LANTERN_PROFILE_SCOPE("invisible"); }
    profile::end_frame();
    EXPECT_TRUE(profile::history().back()->events.empty());
}

TEST_F(Profiler, FullRingDropsAndCounts) {
    profile::begin_frame();
    for (int i = 0; i < 40000; ++i) profile::record("spam", 0, 1);
    profile::end_frame();
    EXPECT_EQ(profile::history().back()->events.size(), 32768u);
    EXPECT_EQ(profile::dropped_events(), 40000u - 32768u);
    EXPECT_NE(profile::text_report().find("dropped"), std::string::npos);
}

TEST_F(Profiler, GpuSpansJoinTheirFrameLate) {
    std::uint32_t gpu = profile::add_gpu_lane("GPU queue");
    profile::begin_frame();
    std::uint64_t first = profile::frame_index();
    profile::end_frame();
    profile::begin_frame();
    profile::record_gpu(gpu, first, "heat_transfer", 5'000'000, 7'500'000); // arrives a frame later
    profile::end_frame();
    auto stats = profile::stats();
    const auto* heat = find(stats, "heat_transfer", profile::LaneKind::gpu);
    ASSERT_NE(heat, nullptr);
    EXPECT_DOUBLE_EQ(heat->last_ms, 2.5);
    EXPECT_EQ(profile::history().front()->events.size(), 1u);
}

TEST_F(Profiler, ChromeTraceParsesWithLanesAndFrames) {
    std::uint32_t gpu = profile::add_gpu_lane("GPU");
    for (int k = 0; k < 3; ++k) {
        profile::begin_frame();
        std::thread([] {
            profile::set_thread_name("helper \"quoted\"");
            LANTERN_PROFILE_SCOPE("helper_work");
        }).join();
        { LANTERN_PROFILE_SCOPE("main_work"); }
        profile::record_gpu(gpu, profile::frame_index(), "direct_light", 100, 200);
        profile::end_frame();
    }
    lantern::test::TempDir dir;
    ASSERT_TRUE(profile::write_chrome_trace(dir.file("trace.json"), 2).ok());
    auto json = nlohmann::json::parse(lantern::test::read_file(dir.path() / "trace.json"));
    std::set<std::pair<int, int>> lanes;
    int frames = 0, gpu_events = 0;
    bool named_helper = false;
    for (const auto& e : json["traceEvents"]) {
        if (e["ph"] == "M" && e["name"] == "thread_name" && e["args"]["name"] == "helper \"quoted\"")
            named_helper = true;
        if (e["ph"] != "X") continue;
        EXPECT_GE(e["dur"].get<double>(), 0.0);
        if (e["cat"] == "frame") ++frames;
        if (e["cat"] == "gpu") ++gpu_events;
        if (e["cat"] == "scope") lanes.insert({e["pid"].get<int>(), e["tid"].get<int>()});
    }
    EXPECT_EQ(frames, 2); // only the last two frames were asked for
    EXPECT_EQ(gpu_events, 2);
    EXPECT_GE(lanes.size(), 2u);
    EXPECT_TRUE(named_helper);
}

TEST_F(Profiler, TextReportListsScopes) {
    profile::begin_frame();
    { LANTERN_PROFILE_SCOPE("streaming"); }
    profile::end_frame();
    std::string report = profile::text_report();
    EXPECT_NE(report.find("streaming"), std::string::npos);
    EXPECT_NE(report.find("p95"), std::string::npos);
}

TEST(ProfilerDeathTest, EndFrameWithoutBeginAsserts) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(profile::end_frame(), "end_frame\\(\\) without begin_frame\\(\\)");
}

// Streaming: bounded residency over a large world, background loads, edits that survive
// unloading, and a GPU wall buffer that always equals the CPU mirror.
#include "gpu_test_support.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/systems/streaming.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace lantern;
using systems::Streaming;

namespace {

jobs::JobSystem::Config workers(int n) {
    jobs::JobSystem::Config c;
    c.worker_threads = n;
    return c;
}

gi::CameraView window_at(glm::vec2 center) { return {center.x - 21.0f, center.y - 12.0f, 42.0f, 24.0f}; }

// One streaming frame as the frame system runs it: update, apply the commands.
void frame(Streaming& s, ecs::World& w, jobs::JobSystem& jobs, glm::vec2 center) {
    ecs::CommandBuffer commands(w);
    s.update(w, commands, jobs, window_at(center));
    commands.apply();
}

std::shared_ptr<systems::CaveSource> caves() { return std::make_shared<systems::CaveSource>(scene::CaveParams{3, 0.52f}); }

} // namespace

TEST(Streaming, WalkAcross4096WorldKeepsResidencyBounded) {
    jobs::JobSystem jobs(workers(1));
    ecs::World w;
    Streaming s(caves());
    s.load_all(w, jobs, window_at({64.0f, 64.0f}));
    const auto size = s.resident_size();
    const std::size_t max_chunks = std::size_t(size.x / systems::chunk_size) * std::size_t(size.y / systems::chunk_size);
    std::size_t peak = 0;
    // Walk diagonally across the whole 4096 x 4096 world, a tile and a half per frame. This
    // loop runs frames far faster than real ones, so every 8 frames the loads catch up (as
    // they do during a real frame's 16 ms).
    int n = 0;
    for (float t = 64.0f; t < 4096.0f - 64.0f; t += 1.5f) {
        if (++n % 8 == 0)
            s.load_all(w, jobs, window_at({t, t * 0.9f}));
        else
            frame(s, w, jobs, {t, t * 0.9f});
        const auto stats = s.stats();
        peak = std::max<std::size_t>(peak, stats.resident_chunks + stats.loading_chunks);
        ASSERT_LE(stats.resident_chunks + stats.loading_chunks, max_chunks);
        ASSERT_EQ(stats.mirror_bytes, std::size_t(size.x) * std::size_t(size.y)); // never grows
        ASSERT_EQ(w.count<WallChunk>(), stats.resident_chunks + stats.loading_chunks);
    }
    const auto stats = s.stats();
    // It really streamed: about 7 chunks enter per 32 tiles of diagonal travel.
    EXPECT_GT(stats.loads_completed, 500u);
    EXPECT_EQ(stats.loads_started, stats.loads_completed + stats.loads_cancelled + stats.loading_chunks);
    EXPECT_EQ(stats.edited_chunks_stored, 0u);
    EXPECT_LE(peak, max_chunks);
    RecordProperty("peak_chunks", int(peak));
}

TEST(Streaming, MirrorMatchesTheSourceOnceLoaded) {
    jobs::JobSystem jobs(workers(2));
    ecs::World w;
    auto source = caves();
    Streaming s(source);
    s.load_all(w, jobs, window_at({300.0f, -200.0f}));
    const gi::WallView v = s.view();
    for (int z = v.origin.y; z < v.origin.y + v.height; z += 3)
        for (int x = v.origin.x; x < v.origin.x + v.width; x += 5)
            ASSERT_EQ(v.is_wall(x, z), scene::cave_wall(x, z, {3, 0.52f})) << x << "," << z;
    EXPECT_FALSE(v.is_wall(v.origin.x - 1, v.origin.y)); // outside the resident area: air
}

TEST(Streaming, EditsSurviveUnloadAndReload) {
    jobs::JobSystem jobs(workers(1));
    ecs::World w;
    Streaming s(caves());
    s.load_all(w, jobs, window_at({0.0f, 0.0f}));
    const glm::ivec2 a(3, 4), b(-10, 7);
    const bool was_a = s.is_wall(a), was_b = s.is_wall(b);
    s.set_wall(w, a, !was_a);
    s.set_wall(w, b, !was_b);
    EXPECT_EQ(s.is_wall(a), !was_a);
    // Walk far away: the chunks unload, their edits are stored.
    s.load_all(w, jobs, window_at({2000.0f, 2000.0f}));
    EXPECT_GE(s.stats().edited_chunks_stored, 1u);
    EXPECT_EQ(s.is_wall(a), !was_a); // answered from the stored edits
    // Edit a chunk that is not resident, then come back: everything is there.
    const glm::ivec2 c(20, -20);
    const bool was_c = s.is_wall(c);
    s.set_wall(w, c, !was_c);
    s.load_all(w, jobs, window_at({0.0f, 0.0f}));
    EXPECT_EQ(s.view().is_wall(a.x, a.y), !was_a);
    EXPECT_EQ(s.view().is_wall(b.x, b.y), !was_b);
    EXPECT_EQ(s.view().is_wall(c.x, c.y), !was_c);
    EXPECT_EQ(s.stats().edited_chunks_stored, 0u); // all back in resident chunks
    // A second round trip keeps them too (a chunk reloaded from edits stays edited).
    s.load_all(w, jobs, window_at({2000.0f, 2000.0f}));
    s.load_all(w, jobs, window_at({0.0f, 0.0f}));
    EXPECT_EQ(s.view().is_wall(a.x, a.y), !was_a);
    EXPECT_EQ(s.view().is_wall(c.x, c.y), !was_c);
    EXPECT_EQ(s.edited_chunks(w).size(), 3u);
}

TEST(Streaming, EditWhileLoadingLandsWhenTheChunkArrives) {
    jobs::JobSystem jobs(workers(0)); // zero workers: loads run only inside waits
    ecs::World w;
    Streaming s(caves());
    {
        ecs::CommandBuffer commands(w);
        s.update(w, commands, jobs, window_at({0.0f, 0.0f}));
        commands.apply();
    }
    ASSERT_GT(s.stats().loading_chunks, 0u);
    const glm::ivec2 tile(1, 1);
    const bool was = scene::cave_wall(1, 1, {3, 0.52f});
    s.set_wall(w, tile, !was);
    s.load_all(w, jobs, window_at({0.0f, 0.0f}));
    EXPECT_EQ(s.view().is_wall(1, 1), !was);
}

class StreamingGpu : public lantern::test::GpuTest {};

TEST_F(StreamingGpu, RandomEditsKeepTheGpuBufferEqualToTheMirror) {
    jobs::JobSystem jobs(workers(1));
    ecs::World w;
    Streaming s(caves());
    auto renderer = gi::vk::Renderer::create(device());
    ASSERT_TRUE(renderer.ok());
    gi::vk::Renderer& r = **renderer;
    std::mt19937 rng(5);
    glm::vec2 center(0.0f, 0.0f);
    std::uint64_t partial_bytes = 0;
    bool uploaded = false;
    for (int step = 0; step < 60; ++step) {
        if (step % 10 == 9) center += glm::vec2(40.0f, -25.0f); // cross chunk boundaries
        ecs::CommandBuffer commands(w);
        s.update(w, commands, jobs, window_at(center));
        commands.apply();
        for (int e = 0; e < 20; ++e) {
            const glm::ivec2 tile(int(center.x) + int(rng() % 60) - 30, int(center.y) + int(rng() % 40) - 20);
            s.set_wall(w, tile, rng() % 2);
        }
        gpu::CommandList cmd = device().begin("walls");
        const std::uint64_t before = r.wall_bytes_uploaded();
        if (!uploaded || s.resized()) {
            r.upload_walls(cmd, s.view());
            uploaded = true;
        } else {
            r.update_walls(cmd, s.view(), s.dirty());
            partial_bytes += r.wall_bytes_uploaded() - before;
        }
        device().submit(std::move(cmd));
        s.clear_dirty();
        const gi::WallView v = s.view();
        const auto gpu = r.read_back_walls();
        ASSERT_GE(gpu.size(), std::size_t(v.width) * std::size_t(v.height));
        ASSERT_EQ(0, std::memcmp(gpu.data(), v.cells, std::size_t(v.width) * std::size_t(v.height))) << "step " << step;
    }
    // Only dirty ranges went up after the first upload: far less than whole buffers.
    const std::uint64_t whole = std::uint64_t(s.view().width) * std::uint64_t(s.view().height);
    EXPECT_LT(partial_bytes, 59 * whole / 4);
    r.device().wait_idle();
}

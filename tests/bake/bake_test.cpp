// The bake (lantern/bake/bake.hpp, docs/baked.md): light modes decide what is baked; the
// baked direct light equals the live direct pass; a second run reuses every cache file;
// an edit re-bakes only the chunks it reaches; shards together write the same bytes as one
// run; truncated, damaged, foreign, stale and future-version files are detected and
// re-baked; a bake killed midway leaves only whole files.
#include "common/test_support.hpp"

#include "lantern/bake/bake.hpp"
#include "lantern/core/cli.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/reference.hpp"
#include "lantern/gi/window.hpp"
#include "lantern/jobs/job_system.hpp"
#include "lantern/scene/day.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

using namespace lantern;
using bake::BakeSettings;
using bake::ChunkId;
using lantern::test::TempDir;
using scene::LightMode;

namespace {

// 96 x 64 tiles (3 x 2 chunks): rooms with doorways, a lava wall in chunk (0, 0), a mixed
// light in chunk (1, 0), a baked light in chunk (1, 1), a realtime light in chunk (2, 1).
// Baked light reaches chunks (0, 0), (1, 0) and (1, 1) only.
scene::Scene world() {
    scene::Scene s;
    const int w = 96, h = 64;
    s.walls.width = w;
    s.walls.height = h;
    s.walls.cells.assign(std::size_t(w * h), 0);
    auto wall = [&](int x, int z, std::uint8_t cell = scene::default_wall_cell) {
        s.walls.cells[std::size_t(z * w + x)] = cell;
    };
    for (int x = 0; x < w; ++x) wall(x, 0), wall(x, h - 1), wall(x, 30);
    for (int z = 0; z < h; ++z) wall(0, z), wall(w - 1, z), wall(40, z), wall(70, z);
    for (int z : {10, 11, 50}) s.walls.cells[std::size_t(z * w + 40)] = 0;
    for (int x : {20, 21, 60}) s.walls.cells[std::size_t(30 * w + x)] = 0;
    s.materials = {{"lava", {0.3f, 0.1f, 0.05f}, {1.5f, 0.5f, 0.1f}}};
    for (int x = 8; x < 14; ++x) wall(x, 8, scene::material_cell(0));
    s.point_lights = {{{44.5f, 15.5f}, 1.0f, {1.0f, 0.6f, 0.3f}, 2.0f, 8.0f, LightMode::mixed},
                      {{44.5f, 45.5f}, 1.0f, {0.4f, 0.6f, 1.0f}, 2.0f, 8.0f, LightMode::baked},
                      {{80.5f, 45.5f}, 1.0f, {1.0f, 1.0f, 1.0f}, 2.0f, 8.0f, LightMode::realtime}};
    s.view = scene::OrthoView{{48, 32}, {30, 20}};
    return s;
}

BakeSettings quick() {
    BakeSettings b;
    b.resolution = 2;
    b.margin = 2;
    return b;
}

std::vector<std::uint8_t> bytes_of(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// The scene with its lights realtime and the live gather at the bake's settings, viewing
// chunk (1, 0) with the bake's margin: what the bake of that chunk solves.
scene::Scene as_live_gather(scene::Scene s, const BakeSettings& b) {
    for (auto& l : s.point_lights) l.mode = LightMode::realtime;
    for (auto& l : s.directional_lights) l.mode = LightMode::realtime;
    s.gi.method = scene::GiMethod::gather;
    s.gi.resolution = b.resolution;
    s.gi.padding = 1.0f;
    s.gi.blur = false;
    s.gi.gather.scale = scene::HeatScale::full;
    s.gi.gather.margin = b.margin;
    s.gi.gather.rays = b.rays;
    s.gi.gather.face_rays = b.face_rays;
    s.view = scene::OrthoView{{48.0f, 16.0f}, {32.0f, 32.0f}}; // chunk (1, 0)
    return s;
}

// `frames` frames of a still scene on the reference, with the history the frame systems keep.
gi::ReferenceStore run_frames(const gi::FrameInputs& in, int frames) {
    gi::Convergence convergence;
    gi::ReferenceStore store;
    for (int f = 0; f < frames; ++f) {
        gi::PassPlan plan = gi::plan_passes(in, false);
        gi::derive_keys(in, plan, gi::input_keys_of(in), &convergence);
        gi::execute_reference(in, plan, plan.run, {}, store);
        convergence.advance(plan.run);
    }
    return store;
}

glm::vec3 texel(const std::vector<float>& v, int side, int x, int y) {
    const std::size_t i = (std::size_t(y) * std::size_t(side) + std::size_t(x)) * 3;
    return {v[i], v[i + 1], v[i + 2]};
}

} // namespace

TEST(Bake, ChunksCoverTheGridAndShardsPartitionThem) {
    scene::Scene s = world();
    s.walls.origin = {-40, 5};
    const std::vector<ChunkId> chunks = bake::scene_chunks(s);
    // Tiles x -40..55, z 5..68: chunks x -2..1, z 0..2.
    ASSERT_EQ(chunks.size(), 12u);
    EXPECT_EQ(chunks.front(), (ChunkId{-2, 0}));
    EXPECT_EQ(chunks.back(), (ChunkId{1, 2}));
    std::vector<ChunkId> all;
    for (int i = 0; i < 5; ++i)
        for (ChunkId c : bake::shard_of(chunks, i, 5)) all.push_back(c);
    EXPECT_EQ(all.size(), chunks.size());
    for (ChunkId c : chunks) EXPECT_EQ(std::count(all.begin(), all.end(), c), 1);
}

// Realtime lights are not baked; a mixed light's direct light is not either (only its
// bounce); a baked light's direct light is Lantern's direct pass, texel for texel.
TEST(Bake, LightModesDecideWhatIsBaked) {
    const scene::Scene s = world();
    const BakeSettings b = quick();
    const int side = bake::chunk_tiles * b.resolution;
    // Chunk (2, 1) holds only the realtime light, out of every baked light's reach: empty.
    EXPECT_TRUE(bake::bake_chunk(s, {2, 1}, b).empty);
    // The mixed light at (44.5, 15.5), 4 tiles from a wall: its bounce light only, far below
    // its direct light.
    const bake::ChunkBake mixed = bake::bake_chunk(s, {1, 0}, b);
    ASSERT_FALSE(mixed.empty);
    EXPECT_TRUE(bake::bake_chunk(s, {0, 1}, b).empty) << "the lava's glow is in chunk (0, 0), beyond its margin";
    const glm::vec3 near_mixed = texel(mixed.ground, side, (44 - 32) * 2 + 1, 15 * 2 + 1);
    EXPECT_GT(near_mixed.r, 0.0f);
    EXPECT_LT(near_mixed.r, 0.5f) << "bounce light only: the light's own is ~1.9 there";
    // The baked light at (55.5, 45.5): direct + bounce; the direct part equals the live pass.
    scene::Scene direct_only = s;
    direct_only.point_lights = {s.point_lights[1]};
    direct_only.materials.clear();
    for (auto& c : direct_only.walls.cells) c = c != 0 ? 1 : 0;
    direct_only.gi.wall_albedo = 0.0f; // no bounce: the bake is the direct light alone
    const bake::ChunkBake baked = bake::bake_chunk(direct_only, {1, 1}, b);
    ASSERT_FALSE(baked.empty);
    scene::GiSettings gi = s.gi;
    gi.resolution = b.resolution;
    gi.padding = 1.0f;
    const scene::OrthoView chunk{{48.0f, 48.0f}, {32.0f, 32.0f}};
    const gi::GiWindow w = *gi::compute_window(chunk, gi);
    scene::Scene live = direct_only;
    live.gi = gi;
    gi::FrameInputs in = gi::gather_frame_inputs(live, w);
    const gi::DirectTextures d = gi::reference_direct(in);
    int lit = 0;
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const float* v = d.direct.at(x, y);
            const glm::vec3 got = texel(baked.ground, side, x, y);
            for (int c = 0; c < 3; ++c) ASSERT_EQ(got[c], v[c]) << x << ", " << y;
            lit += v[0] > 0.0f ? 1 : 0;
        }
    EXPECT_GT(lit, 500);
}

// A mixed light's baked bounce light is what the live gather method computes for it, texel
// for texel, when the live method runs with the bake's settings (its frames x bounces
// spread over 8 frames instead of one). A mixed point light, and a mixed sun.
TEST(Bake, BakedBounceEqualsTheLiveGather) {
    for (bool sun : {false, true}) {
        SCOPED_TRACE(sun ? "a mixed sun" : "a mixed point light");
        scene::Scene s = world();
        s.point_lights = {s.point_lights[0]}; // the mixed light at (44.5, 15.5)
        if (sun) {
            s.point_lights.clear();
            scene::DirectionalLight d;
            d.direction = glm::normalize(glm::vec3(0.5f, -0.7f, -0.4f));
            d.intensity = 0.8f;
            d.mode = LightMode::mixed;
            s.directional_lights = {d};
        }
        s.materials.clear();
        for (auto& c : s.walls.cells) c = c != 0 ? 1 : 0;
        const BakeSettings b = quick();
        const bake::ChunkBake baked = bake::bake_chunk(s, {1, 0}, b);
        ASSERT_FALSE(baked.empty);
        const scene::Scene live = as_live_gather(s, b);
        const gi::GiWindow w = *gi::compute_window(live.view, live.gi);
        const gi::FrameInputs in = gi::gather_frame_inputs(live, w);
        const gi::ReferenceStore store = run_frames(in, live.gi.gather.frames);
        const gi::Texture& indirect = store.at(gi::Tex::indirect);
        const int side = baked.side(), offset = b.margin * b.resolution;
        int lit = 0;
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x) {
                const float* v = indirect.at(x + offset, y + offset);
                const glm::vec3 got = texel(baked.ground, side, x, y);
                for (int c = 0; c < 3; ++c) ASSERT_EQ(got[c], v[c]) << x << ", " << y;
                lit += v[0] > 0.0f ? 1 : 0;
            }
        EXPECT_GT(lit, 1000);
    }
}

TEST(Bake, SecondRunReusesEveryCacheAndAnEditRebakesOnlyTheChunksItReaches) {
    TempDir dir;
    scene::Scene s = world();
    jobs::JobSystem jobs;
    bake::BakeOptions o;
    o.jobs = &jobs;
    int progress_calls = 0;
    o.progress = [&](const bake::BakeProgress& p) {
        ++progress_calls;
        EXPECT_LE(p.done, p.total);
    };
    auto first = bake::bake_world(s, dir.path().string(), quick(), o);
    ASSERT_TRUE(first.ok()) << first.error().message;
    EXPECT_EQ(first->chunks, 6);
    EXPECT_EQ(first->baked, 6);
    EXPECT_EQ(first->empty, 3); // (0, 1), (2, 0) and (2, 1) (a realtime light only)
    EXPECT_GE(progress_calls, 2);
    auto second = bake::bake_world(s, dir.path().string(), quick(), o);
    ASSERT_TRUE(second.ok());
    EXPECT_EQ(second->reused, 6);
    EXPECT_EQ(second->baked, 0);
    // A wall placed in the far corner of chunk (2, 1) (tile 94, 62): out of every other
    // chunk's reach (its margin and its lights' radii).
    s.walls.cells[std::size_t(62 * 96 + 94)] = 1;
    auto third = bake::bake_world(s, dir.path().string(), quick(), o);
    ASSERT_TRUE(third.ok());
    EXPECT_EQ(third->baked, 1);
    EXPECT_EQ(third->reused, 5);
    // A baked light moved: the chunks it reaches re-bake, the others do not.
    s.point_lights[1].position.x += 0.25f;
    auto fourth = bake::bake_world(s, dir.path().string(), quick(), o);
    ASSERT_TRUE(fourth.ok());
    EXPECT_GE(fourth->baked, 1);
    EXPECT_LE(fourth->baked, 4);
    EXPECT_EQ(fourth->baked + fourth->reused, 6);
}

TEST(Bake, ShardsTogetherWriteTheSameBytesAsOneRun) {
    const scene::Scene s = world();
    TempDir one, sharded;
    jobs::JobSystem jobs;
    bake::BakeOptions o;
    o.jobs = &jobs;
    ASSERT_TRUE(bake::bake_world(s, one.path().string(), quick(), o).ok());
    for (int i = 0; i < 4; ++i) { // one thread each, as separate machines would
        bake::BakeOptions shard;
        shard.shard = i;
        shard.shards = 4;
        auto r = bake::bake_world(s, sharded.path().string(), quick(), shard);
        ASSERT_TRUE(r.ok()) << r.error().message;
        EXPECT_EQ(r->chunks, i < 2 ? 2 : 1);
    }
    int files = 0;
    for (ChunkId c : bake::scene_chunks(s)) {
        const std::string name = bake::chunk_file_name(c);
        const auto a = bytes_of(one.file(name)), b = bytes_of(sharded.file(name));
        ASSERT_FALSE(a.empty()) << name;
        EXPECT_TRUE(a == b) << name << " differs between one run and the shards";
        ++files;
    }
    EXPECT_EQ(files, 6);
}

TEST(Bake, UnusableCacheFilesAreNamedAndRebaked) {
    TempDir dir;
    const scene::Scene s = world();
    ASSERT_TRUE(bake::bake_world(s, dir.path().string(), quick()).ok());
    const std::string f00 = dir.file(bake::chunk_file_name({0, 0})), f10 = dir.file(bake::chunk_file_name({1, 0}));
    const std::vector<std::uint8_t> good = bytes_of(f00);
    struct Fault {
        const char* name;
        std::function<void()> apply;
        const char* reason;
    };
    const std::vector<Fault> faults{
        {"truncated", [&] { write_bytes(f00, std::vector<std::uint8_t>(good.begin(), good.begin() + 100)); },
         "sizes do not match"},
        {"short header", [&] { write_bytes(f00, std::vector<std::uint8_t>(good.begin(), good.begin() + 10)); },
         "truncated"},
        {"foreign", [&] { write_bytes(f00, std::vector<std::uint8_t>(200, '{')); }, "not a Lantern bake file"},
        {"another chunk's file", [&] { std::filesystem::copy_file(f10, f00, std::filesystem::copy_options::overwrite_existing); },
         "holds chunk 1, 0"},
        {"a damaged texel", [&] {
             auto b = good;
             b[b.size() - 7] ^= 0x40;
             write_bytes(f00, b);
         }, "damaged"},
        {"a future version", [&] {
             auto b = good;
             b[8] = 99;
             write_bytes(f00, b);
         }, "format version 99"},
    };
    for (const Fault& fault : faults) {
        fault.apply();
        std::string why;
        EXPECT_FALSE(bake::load_chunk(dir.path().string(), {0, 0}, bake::chunk_key(s, {0, 0}, quick()), &why)) << fault.name;
        EXPECT_NE(why.find(fault.reason), std::string::npos) << fault.name << ": " << why;
        std::vector<std::string> warnings;
        bake::BakeOptions o;
        o.warn = [&](const std::string& m) { warnings.push_back(m); };
        auto r = bake::bake_world(s, dir.path().string(), quick(), o);
        ASSERT_TRUE(r.ok());
        EXPECT_EQ(r->baked, 1) << fault.name;
        ASSERT_EQ(warnings.size(), 1u) << fault.name;
        EXPECT_NE(warnings[0].find(bake::chunk_file_name({0, 0})), std::string::npos) << warnings[0];
        EXPECT_TRUE(bytes_of(f00) == good) << fault.name << ": the re-bake gives the same file";
    }
    // A stored size that promises more than the file holds, and a payload that does not inflate.
    {
        auto b = good;
        b[56] ^= 1;
        write_bytes(f00, b);
        std::string why;
        EXPECT_FALSE(bake::load_chunk(dir.path().string(), {0, 0}, bake::chunk_key(s, {0, 0}, quick()), &why));
        EXPECT_NE(why.find("sizes do not match"), std::string::npos) << why;
        b = good;
        for (std::size_t i = 64; i < 80; ++i) b[i] = 0xff;
        write_bytes(f00, b);
        EXPECT_FALSE(bake::load_chunk(dir.path().string(), {0, 0}, bake::chunk_key(s, {0, 0}, quick()), &why));
        EXPECT_NE(why.find("damaged"), std::string::npos) << why;
        write_bytes(f00, good);
    }
    // Deflated on disk: the payload (five half-float textures and the probes) is far larger.
    const std::size_t side = std::size_t(bake::chunk_tiles * quick().resolution);
    const std::size_t payload = side * side * 3 * 2 * 5 + std::size_t(bake::chunk_probes * bake::chunk_probes) * (15 * 4 + 1);
    std::printf("[ cache ] chunk (0, 0): %zu bytes on disk for a %zu-byte payload (%.1fx)\n", good.size(), payload,
                double(payload) / double(good.size()));
    EXPECT_LT(good.size() * 2, payload);
    // Stale: the lava glows brighter; the file is for other inputs.
    scene::Scene brighter = s;
    brighter.materials[0].emission *= 2.0f;
    std::string why;
    EXPECT_FALSE(bake::load_chunk(dir.path().string(), {0, 0}, bake::chunk_key(brighter, {0, 0}, quick()), &why));
    EXPECT_NE(why.find("stale"), std::string::npos) << why;
}

// A bake process killed at an arbitrary point (here: as soon as its first file exists)
// leaves only whole cache files: each decodes, and the next run reuses them.
TEST(Bake, AKilledBakeLeavesOnlyWholeFiles) {
    TempDir dir;
    const scene::Scene s = world();
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        for (;;) { // bake over and over until killed
            bake::BakeOptions o;
            o.force = true;
            (void)bake::bake_world(s, dir.path().string(), quick(), o);
        }
    }
    // Wait for a condition (a second pass has begun rewriting files), never for a time;
    // the deadline only turns a hang into a failure.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
    auto files = [&] {
        int n = 0;
        for (const auto& e : std::filesystem::directory_iterator(dir.path())) n += e.path().extension() == ".lbk";
        return n;
    };
    while (files() < 6 && std::chrono::steady_clock::now() < deadline) usleep(1000);
    usleep(20000); // somewhere inside the second pass's writes
    kill(child, SIGKILL);
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_EQ(files(), 6);
    for (ChunkId c : bake::scene_chunks(s)) {
        std::string why;
        EXPECT_TRUE(bake::load_chunk(dir.path().string(), c, bake::chunk_key(s, c, quick()), &why)) << why;
    }
    auto r = bake::bake_world(s, dir.path().string(), quick());
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->reused, 6);
}

TEST(Bake, BadSettingsAndShardsAreRefused) {
    TempDir dir;
    const scene::Scene s = world();
    BakeSettings b;
    b.resolution = 0;
    auto r = bake::bake_world(s, dir.path().string(), b);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "bake.resolution: must be an integer in [1, 16], got 0");
    b = quick();
    b.falloff = 0.0f;
    r = bake::bake_world(s, dir.path().string(), b);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message.substr(0, 41), "bake.falloff: must be a number in [0.0156");
    b = quick();
    b.ambient = std::nanf("");
    r = bake::bake_world(s, dir.path().string(), b);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message.substr(0, 34), "bake.ambient: must be a number in ");
    bake::BakeOptions o;
    o.shard = 3;
    o.shards = 3;
    r = bake::bake_world(s, dir.path().string(), quick(), o);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "bake: shard 3 of 3: needs 0 <= shard < shards");
}

// No seams: across the border of two chunks the baked light steps no more than the light's
// own gradient beside the border (twice the larger step on either side) plus 5 % of its
// value: each chunk's solve sees every light in reach and the walls of its neighbours within
// the margin (32 tiles: a glowing wall 20 tiles away still lights the border). With margin 8
// the lava's light is missing on one side (a step of ~85 %), so the test can fail.
TEST(Bake, NoSeamsAtChunkBorders) {
    scene::Scene s = world();
    s.point_lights[0].position = {33.5f, 20.5f}; // 1.5 tiles right of the border x = 32
    s.point_lights[0].mode = LightMode::baked;
    auto worst_seam = [&](int margin) {
        BakeSettings b; // the default margin, 32
        b.resolution = 1;
        b.rays = 1024; // one ray of the lava's glow is then ~2 % of the light at the border
        b.face_rays = 64;
        b.margin = margin;
        const bake::ChunkBake left = bake::bake_chunk(s, {0, 0}, b), right = bake::bake_chunk(s, {1, 0}, b);
        const int side = left.side();
        double worst = 0.0;
        int rows = 0;
        for (int y = 0; y < side; ++y)
            for (int c = 0; c < 3; ++c) {
                const float a1 = texel(left.ground, side, side - 2, y)[c], a0 = texel(left.ground, side, side - 1, y)[c];
                const float b0 = texel(right.ground, side, 0, y)[c], b1 = texel(right.ground, side, 1, y)[c];
                if (a0 <= 0.0f || b0 <= 0.0f) continue; // walls
                const double beside = std::max(std::abs(double(a0) - a1), std::abs(double(b1) - b0));
                const double excess = std::abs(double(b0) - a0) - 2.0 * beside;
                worst = std::max(worst, excess / std::max(a0, b0));
                rows += c == 0;
            }
        std::printf("margin %d: %d rows across the border, the worst step beyond the gradient is %.1f %% of the light\n",
                    margin, rows, 100.0 * worst);
        EXPECT_GT(rows, 20);
        return worst;
    };
    EXPECT_LT(worst_seam(BakeSettings{}.margin), 0.05);
    EXPECT_GT(worst_seam(8), 0.2) << "the test sees a seam where there is one";
}

// Light probes (seed 004's, in 2D): a probe beside a glowing lava wall is lit orange from
// that side; a probe's fluence is the baked ground light at its place; a lone baked light
// arrives from its direction; the cache file keeps the probes exactly.
TEST(Bake, ProbesBesideLavaAreLitOrangeFromThatSide) {
    scene::Scene s;
    std::vector<std::string> rows(32, std::string(32, '#'));
    for (int z = 4; z < 28; ++z) rows[std::size_t(z)].replace(4, 24, std::string(24, '.'));
    s.walls.width = s.walls.height = 32;
    for (const std::string& r : rows)
        for (char c : r) s.walls.cells.push_back(c == '#' ? 1 : 0);
    s.materials = {{"lava", {0.3f, 0.1f, 0.05f}, {1.5f, 0.5f, 0.1f}}};
    for (int z = 10; z < 22; ++z) s.walls.cells[std::size_t(z * 32 + 3)] = scene::material_cell(0); // the west wall, x = 3
    BakeSettings b = quick();
    b.rays = 512;
    const bake::ChunkBake chunk = bake::bake_chunk(s, {0, 0}, b);
    ASSERT_FALSE(chunk.empty);
    // The probe at (4.5, 16.5), a tile and a half east of the lava's face on x = 4.
    const std::size_t k = std::size_t(8 * bake::chunk_probes + 2);
    ASSERT_EQ(chunk.probe_valid[k], 1);
    const bake::CircularHarmonics& h = chunk.probes[k];
    const glm::vec3 west = h.irradiance(3.14159265f), east = h.irradiance(0.0f);
    std::printf("facing the lava (%.3f %.3f %.3f), facing away (%.3f %.3f %.3f)\n", west.r, west.g, west.b, east.r, east.g,
                east.b);
    EXPECT_GT(west.r, 4.0f * east.r) << "lit from the lava's side";
    EXPECT_GT(west.r, 2.0f * west.g);
    EXPECT_GT(west.g, 2.0f * west.b) << "orange";
    // Its fluence is the ground light baked at the same place (texel (9, 33) at 2 a tile).
    const glm::vec3 ground = texel(chunk.ground, chunk.side(), 9, 33);
    EXPECT_NEAR(h.fluence().r, ground.r, 0.05f * ground.r);
    EXPECT_EQ(chunk.probe_valid[0], 0) << "a probe in rock";
    // Through a cache file, the probes are kept bit for bit.
    TempDir dir;
    ASSERT_TRUE(bake::save_chunk(dir.path().string(), chunk).ok());
    auto again = bake::load_chunk(dir.path().string(), {0, 0}, chunk.key);
    ASSERT_TRUE(again);
    EXPECT_EQ(again->probes, chunk.probes);
    EXPECT_EQ(again->probe_valid, chunk.probe_valid);
}

TEST(Bake, ALoneBakedLightArrivesFromItsDirection) {
    scene::Scene s = world();
    s.point_lights = {{{50.5f, 16.5f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 10.0f, LightMode::baked}};
    s.materials.clear();
    for (auto& c : s.walls.cells) c = c != 0 ? 1 : 0;
    s.gi.wall_albedo = 0.0f; // no bounce: the probe holds the light alone
    const bake::ChunkBake chunk = bake::bake_chunk(s, {1, 0}, quick());
    // The probe at (54.5, 16.5): 4 tiles east of the light, which arrives from the west.
    const bake::CircularHarmonics& h = chunk.probes[std::size_t(8 * bake::chunk_probes + 11)];
    const float fluence = h.fluence().r;
    EXPECT_NEAR(fluence, 0.6f, 1e-5f) << "(1 - 4 / 10)";
    EXPECT_NEAR(h.irradiance(3.14159265f).r, fluence, 0.05f * fluence) << "facing the light: its whole fluence";
    EXPECT_LT(h.irradiance(0.0f).r, 0.1f * fluence) << "facing away: order 2 leaves a little ringing";
    EXPECT_LT(h.irradiance(3.14159265f / 2.0f).r, 0.15f * fluence) << "side on: grazing light, 0 (order 2 gives 0.11)";
}

// Order 1 against order 2 (issue 18: "order 2, or order 1 if measured good enough"): a chunk's
// probes against the exact irradiance of what each was captured from (its rays and baked
// lights). The harmonics hold exactly the samples' moments (a0 is their summed flux); order 2
// follows the irradiance far better than order 1, which is not good enough here.
TEST(Bake, OrderTwoProbesFollowTheirSamplesAndOrderOneDoesNot) {
    std::vector<bake::ProbeSamples> samples;
    const bake::ChunkBake chunk = bake::bake_chunk(world(), {1, 0}, quick(), &samples);
    ASSERT_FALSE(chunk.empty);
    ASSERT_EQ(samples.size(), chunk.probes.size());
    bake::ProbeOrderError e;
    for (std::size_t k = 0; k < chunk.probes.size(); ++k) {
        if (!chunk.probe_valid[k]) {
            EXPECT_TRUE(samples[k].theta.empty());
            continue;
        }
        glm::vec3 flux(0.0f);
        for (const glm::vec3& f : samples[k].flux) flux += f;
        EXPECT_NEAR(chunk.probes[k].fluence().r, flux.r, 1e-4f * (1.0f + flux.r)) << k;
        e.add(chunk.probes[k], samples[k]);
    }
    ASSERT_GT(e.probes, 100);
    std::printf("order 1: rel. RMS %.2f %%, order 2: %.2f %% (worst probe %.1f %%, %.1f %%)\n", 100.0 * e.relative_rms(1),
                100.0 * e.relative_rms(2), 100.0 * e.worst_probe[0], 100.0 * e.worst_probe[1]);
    EXPECT_LT(e.relative_rms(2), 0.5 * e.relative_rms(1));
    EXPECT_LT(e.relative_rms(2), 0.12);
    EXPECT_GT(e.relative_rms(1), 0.15) << "order 1 would do: measure again (docs/baked.md, Probes)";
    // A lone delta: order 2's irradiance facing it is 3 % over the exact, order 1's 18 % short.
    bake::ProbeSamples one;
    bake::CircularHarmonics h;
    one.add(0.5f, glm::vec3(1.0f));
    h.add_delta(0.5f, glm::vec3(1.0f));
    EXPECT_NEAR(h.irradiance(0.5f, 2).r, 1.0f, 0.035f); // 1 / pi + 1 / 2 + 2 / (3 pi) = 1.0305
    EXPECT_NEAR(h.irradiance(0.5f, 1).r, 1.0f / 3.14159265f + 0.5f, 1e-5f);
    EXPECT_FLOAT_EQ(one.irradiance(0.5f).r, 1.0f);
}

TEST(Bake, ProbesInterpolateBilinearlyOverThoseThatExist) {
    auto probe = [](float f) {
        bake::CircularHarmonics h;
        h.c[0] = glm::vec3(f);
        return h;
    };
    const bake::CircularHarmonics a = probe(1.0f), b = probe(2.0f), c = probe(3.0f), d = probe(4.0f);
    auto at = [&](int ix, int iz) -> const bake::CircularHarmonics* {
        if (ix == 0 && iz == 0) return &a;
        if (ix == 1 && iz == 0) return &b;
        if (ix == 0 && iz == 1) return &c;
        if (ix == 1 && iz == 1) return &d;
        return nullptr;
    };
    // Probes at (0.5, 0.5), (2.5, 0.5), (0.5, 2.5), (2.5, 2.5).
    EXPECT_FLOAT_EQ(bake::interpolate_probes(at, {0.5f, 0.5f}).fluence().r, 1.0f);
    EXPECT_FLOAT_EQ(bake::interpolate_probes(at, {1.5f, 1.5f}).fluence().r, 2.5f);
    EXPECT_FLOAT_EQ(bake::interpolate_probes(at, {2.0f, 0.5f}).fluence().r, 1.75f);
    // Beyond (2.5, 2.5) only d exists among the four around: d's light.
    EXPECT_FLOAT_EQ(bake::interpolate_probes(at, {3.0f, 3.0f}).fluence().r, 4.0f);
    EXPECT_FLOAT_EQ(bake::interpolate_probes(at, {-3.0f, -3.0f}).fluence().r, 0.0f) << "no probe around";
}

// At run time (bake::load_world_light, the frame's `baked` row): a baked light looks as the
// same light does live when the live method is the bake's solver with the bake's settings:
// direct + indirect light live equal the baked light the frame adds, on the ground and on
// every exposed wall face, within the bricks' colour range and RGBM's rounding.
TEST(BakeAtRunTime, ABakedLightLooksAsItDoesLive) {
    scene::Scene s = world();
    s.point_lights = {s.point_lights[0]};
    s.point_lights[0].mode = LightMode::baked;
    s.materials.clear();
    for (auto& c : s.walls.cells) c = c != 0 ? 1 : 0;
    const BakeSettings b = quick();
    TempDir dir;
    auto light = bake::load_world_light(s, dir.path().string(), b);
    ASSERT_TRUE(light.ok()) << light.error().message;
    ASSERT_TRUE(*light);
    const scene::Scene live = as_live_gather(s, b);
    const gi::GiWindow w = *gi::compute_window(live.view, live.gi);
    const gi::ReferenceStore a = run_frames(gi::gather_frame_inputs(live, w), live.gi.gather.frames);
    scene::Scene baked_scene = bake::live_scene(s);
    baked_scene.gi = live.gi;
    EXPECT_TRUE(baked_scene.point_lights.empty()) << "the baked light leaves the live passes";
    gi::FrameInputs in = gi::gather_frame_inputs(baked_scene, w);
    in.baked = *light;
    const gi::ReferenceStore bs = run_frames(in, 1);
    auto rgb = [](const gi::Texture* t, int x, int y) {
        if (!t) return glm::vec3(0.0f);
        const float* v = t->at(x, y);
        return glm::vec3(v[0], v[1], v[2]);
    };
    int ground = 0, faces = 0;
    double err2 = 0.0, ref2 = 0.0;
    for (int y = 0; y < w.height; ++y)
        for (int x = 0; x < w.width; ++x) {
            const glm::vec2 p = w.texel_center(x, y);
            if (p.x < 32.0f || p.x >= 64.0f || p.y < 0.0f || p.y >= 32.0f) continue; // the chunk
            const glm::ivec2 cell(int(std::floor(p.x)), int(std::floor(p.y)));
            const bool wall = s.walls.is_wall_tile(cell.x, cell.y);
            auto check = [&](glm::vec3 want, glm::vec3 got) {
                for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], want[c], 0.012f + 0.01f * want[c]) << x << ", " << y;
                const glm::vec3 d = got - want;
                err2 += double(glm::dot(d, d));
                ref2 += double(glm::dot(want, want));
            };
            if (!wall) {
                check(rgb(a.find(gi::Tex::direct), x, y) + rgb(a.find(gi::Tex::indirect), x, y),
                      rgb(bs.find(gi::Tex::direct), x, y) + rgb(bs.find(gi::Tex::indirect), x, y));
                ++ground;
                continue;
            }
            const glm::vec4 mask = gi::wall_face_mask(in.walls, cell);
            for (int f = 0; f < 4; ++f)
                if (mask[f] > 0.0f) {
                    const gi::Tex direct = gi::Tex(int(gi::Tex::wall_direct_px) + f);
                    const gi::Tex indirect = gi::Tex(int(gi::Tex::wall_indirect_px) + f);
                    check(rgb(a.find(direct), x, y) + rgb(a.find(indirect), x, y),
                          rgb(bs.find(direct), x, y) + rgb(bs.find(indirect), x, y));
                    ++faces;
                }
        }
    std::printf("ground texels %d, face texels %d, relative RMS difference %.3f %%\n", ground, faces,
                100.0 * std::sqrt(err2 / std::max(ref2, 1e-30)));
    EXPECT_GT(ground, 2000);
    EXPECT_GT(faces, 100);
    EXPECT_LT(std::sqrt(err2 / ref2), 0.01);
}

// Seed 002's own bake (BakeSolver::seed002) in a closed square room with no light but the
// ambient fill: every ray hits a wall of radiosity albedo x ambient, weighted by
// 1 / (1 + (d / falloff)^2). The ground's fluence is then the integral over the circle of
// (B w(d) / 2), a face's irradiance the integral over its half circle of (B w(d) / 2) cos,
// with d the distance to the room's wall along each direction: computed here from the
// geometry alone, independently of the bake's ray marching.
namespace {

// Distance from p (inside or on the box [lo, hi]^2) to the box's boundary along angle t.
double to_box(glm::dvec2 p, double lo, double hi, double t) {
    const double c = std::cos(t), s = std::sin(t);
    double d = 1e30;
    if (c > 1e-12) d = std::min(d, (hi - p.x) / c);
    if (c < -1e-12) d = std::min(d, (lo - p.x) / c);
    if (s > 1e-12) d = std::min(d, (hi - p.y) / s);
    if (s < -1e-12) d = std::min(d, (lo - p.y) / s);
    return d;
}

double weight(double d, double falloff) { return 1.0 / (1.0 + (d / falloff) * (d / falloff)); }

scene::Scene ambient_room() { // open tiles 1..10 in x and z: the room spans [1, 11]^2
    scene::Scene s;
    s.walls.width = s.walls.height = 12;
    s.walls.cells.assign(144, 0);
    for (int i = 0; i < 12; ++i)
        for (int k : {0, 11}) s.walls.cells[std::size_t(i * 12 + k)] = s.walls.cells[std::size_t(k * 12 + i)] = 1;
    s.gi.wall_albedo = 0.6f;
    return s;
}

} // namespace

TEST(Bake, Seed002WeighsEachHitByItsDistanceAndFillsWithAmbient) {
    const scene::Scene s = ambient_room();
    BakeSettings b = quick();
    b.solver = bake::BakeSolver::seed002;
    b.ambient = 0.5f;
    b.rays = 1024;
    b.face_rays = 1024;
    const double radiosity = 0.6 * 0.5;
    const double pi = 3.14159265358979;
    for (float falloff : {1.0f, 3.0f, 4096.0f}) {
        b.falloff = falloff;
        const bake::ChunkBake baked = bake::bake_chunk(s, {0, 0}, b);
        ASSERT_FALSE(baked.empty) << "the ambient fill lights the room";
        const int side = baked.side();
        // Ground texel (12, 9): centre (6.25, 4.75).
        const glm::dvec2 p(6.25, 4.75);
        double ground = 0.0, face = 0.0, at_probe = 0.0;
        const int steps = 200000;
        for (int k = 0; k < steps; ++k) {
            const double t = 2.0 * pi * (k + 0.5) / steps;
            ground += radiosity * weight(to_box(p, 1.0, 11.0, t), double(falloff)) / 2.0 * (2.0 * pi / steps);
            at_probe += radiosity * weight(to_box({6.5, 4.5}, 1.0, 11.0, t), double(falloff)) / 2.0 * (2.0 * pi / steps);
            // The +Z face of wall tile (6, 0) at its texel (12, 1): the point (6.25, 1), facing +z.
            const double u = pi * (k + 0.5) / steps; // 0..pi: the half circle above the face
            face += radiosity * weight(to_box({6.25, 1.0}, 1.0, 11.0, u), double(falloff)) / 2.0 * std::sin(u) *
                    (pi / steps);
        }
        const glm::vec3 got_ground = texel(baked.ground, side, 12, 9);
        const glm::vec3 got_face = texel(baked.faces[2], side, 12, 1);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(got_ground[c], ground, 0.01 * ground) << "falloff " << falloff;
            EXPECT_NEAR(got_face[c], face, 0.01 * face) << "falloff " << falloff;
        }
        // Walls far from the ambient room's walls count less: the nearer the wall, the more
        // a shorter falloff keeps of the light.
        if (falloff == 1.0f) {
            EXPECT_LT(ground, 0.45 * radiosity * pi);
        }
        if (falloff == 4096.0f) {
            EXPECT_NEAR(ground, radiosity * pi, 1e-3 * radiosity * pi);
        }
        // The light probe at (6.5, 4.5) holds the fluence there (its zeroth harmonic).
        const std::size_t k = std::size_t(2 * bake::chunk_probes + 3);
        ASSERT_EQ(baked.probe_valid[k], 1);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(baked.probes[k].fluence()[c], at_probe, 0.01 * at_probe);
    }
}

// Seed 002's settings are part of the cache key; the gather's key does not depend on them.
TEST(Bake, Seed002SettingsAreInTheKey) {
    const scene::Scene s = world();
    BakeSettings b = quick();
    const std::uint64_t gather = bake::chunk_key(s, {0, 0}, b);
    b.falloff = 9.0f;
    b.ambient = 0.25f;
    EXPECT_EQ(bake::chunk_key(s, {0, 0}, b), gather);
    b.solver = bake::BakeSolver::seed002;
    const std::uint64_t seed = bake::chunk_key(s, {0, 0}, b);
    EXPECT_NE(seed, gather);
    b.falloff = 8.0f;
    EXPECT_NE(bake::chunk_key(s, {0, 0}, b), seed);
    b.falloff = 9.0f;
    b.ambient = 0.5f;
    EXPECT_NE(bake::chunk_key(s, {0, 0}, b), seed);
}

// Seed 004's emission GI modes: a `baked` glowing material is in the bake and leaves the live
// scene; a `realtime` one is not baked and stays live; `none` lights nothing, baked or live,
// though the tile keeps its emission (the game still draws it glowing).
TEST(Bake, EmissionGiModesDecideWhereAGlowLights) {
    scene::Scene s = world();
    s.point_lights.clear(); // only the lava wall in chunk (0, 0) gives light
    const glm::vec3 glow = s.materials[0].emission;
    for (scene::EmissionGi mode : {scene::EmissionGi::baked, scene::EmissionGi::realtime, scene::EmissionGi::none}) {
        s.materials[0].emission_gi = mode;
        const bake::ChunkBake b = bake::bake_chunk(s, {0, 0}, quick());
        const scene::Scene live = bake::live_scene(s);
        const gi::GpuMaterial gpu = gi::pack_material(s.materials[0]);
        EXPECT_EQ(live.materials[0].emission, mode == scene::EmissionGi::baked ? glm::vec3(0.0f) : glow) << int(mode);
        EXPECT_EQ(b.empty, mode != scene::EmissionGi::baked) << int(mode);
        EXPECT_EQ(glm::vec3(gpu.emission), mode == scene::EmissionGi::none ? glm::vec3(0.0f) : glow) << int(mode);
    }
}

// Seed 004's opacity multiplies what a tile reflects and emits (the GI's material table and,
// through it, the bake): half-opaque lava bakes about half the light (less its own bounce).
TEST(Bake, OpacityScalesWhatATileReflectsAndEmits) {
    scene::Scene s = world();
    s.point_lights.clear();
    scene::Material m = s.materials[0];
    m.opacity = 0.5f;
    const gi::GpuMaterial gpu = gi::pack_material(m);
    EXPECT_EQ(glm::vec3(gpu.albedo), s.materials[0].albedo * 0.5f);
    EXPECT_EQ(glm::vec3(gpu.emission), s.materials[0].emission * 0.5f);
    const bake::ChunkBake full = bake::bake_chunk(s, {0, 0}, quick());
    s.materials[0].opacity = 0.5f;
    const bake::ChunkBake half = bake::bake_chunk(s, {0, 0}, quick());
    EXPECT_NE(full.key, half.key);
    double a = 0.0, b = 0.0;
    for (std::size_t i = 0; i < full.ground.size(); ++i) a += full.ground[i], b += half.ground[i];
    ASSERT_GT(a, 0.0);
    std::printf("[ opacity ] ground light at opacity 0.5: %.4f of opacity 1\n", b / a);
    EXPECT_GT(b / a, 0.45);
    EXPECT_LE(b / a, 0.5 + 1e-3);
}

// Seed 004's indirect multiplier scales what the bake holds of a light's bounce and nothing
// else: x2 doubles a mixed light's baked bounce (ground, faces and probes), 0 leaves none; a
// baked light at 0 keeps its baked direct light.
TEST(Bake, TheIndirectMultiplierScalesOnlyTheBakedBounce) {
    scene::Scene s = world();
    s.materials.clear();
    for (auto& c : s.walls.cells) c = c != 0 ? 1 : 0;
    s.point_lights = {s.point_lights[0]}; // the mixed light in chunk (1, 0)
    const bake::ChunkBake one = bake::bake_chunk(s, {1, 0}, quick());
    s.point_lights[0].indirect = 2.0f;
    const bake::ChunkBake two = bake::bake_chunk(s, {1, 0}, quick());
    s.point_lights[0].indirect = 0.0f;
    const bake::ChunkBake none = bake::bake_chunk(s, {1, 0}, quick());
    ASSERT_FALSE(one.empty);
    EXPECT_NE(one.key, two.key);
    double sum = 0.0;
    for (std::size_t i = 0; i < one.ground.size(); ++i) {
        sum += one.ground[i];
        ASSERT_NEAR(two.ground[i], 2.0f * one.ground[i], 1e-5f * (1.0f + one.ground[i])) << i;
        ASSERT_EQ(none.ground[i], 0.0f) << i;
    }
    EXPECT_GT(sum, 1.0);
    for (std::size_t i = 0; i < one.faces[0].size(); ++i) ASSERT_NEAR(two.faces[0][i], 2.0f * one.faces[0][i], 1e-5f * (1.0f + one.faces[0][i]));
    for (std::size_t k = 0; k < one.probes.size(); ++k)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(two.probes[k].c[0][c], 2.0f * one.probes[k].c[0][c], 1e-4f);

    // A baked light with indirect 0: its direct light alone.
    s.point_lights[0].mode = LightMode::baked;
    const bake::ChunkBake direct_only = bake::bake_chunk(s, {1, 0}, quick());
    s.point_lights[0].indirect = 1.0f;
    const bake::ChunkBake both = bake::bake_chunk(s, {1, 0}, quick());
    int less = 0;
    for (std::size_t i = 0; i < both.ground.size(); ++i) {
        ASSERT_NEAR(direct_only.ground[i], both.ground[i] - one.ground[i], 1e-4f * (1.0f + both.ground[i])) << i;
        less += direct_only.ground[i] < both.ground[i];
    }
    EXPECT_GT(less, 1000);
}

// Seed 004's static flag: a moving shadow proxy does not shadow the baked light (nor change
// the key); a static one does.
TEST(Bake, OnlyStaticProxiesShadowTheBake) {
    scene::Scene s = world();
    s.point_lights = {s.point_lights[1]}; // the baked light at (44.5, 45.5), chunk (1, 1)
    const bake::ChunkBake bare = bake::bake_chunk(s, {1, 1}, quick());
    scene::ShadowProxy p;
    p.position = {46.5f, 45.5f};
    p.size = glm::vec2(0.6f);
    p.is_static = false;
    s.shadow_proxies = {p};
    const bake::ChunkBake moving = bake::bake_chunk(s, {1, 1}, quick());
    s.shadow_proxies[0].is_static = true;
    const bake::ChunkBake placed = bake::bake_chunk(s, {1, 1}, quick());
    EXPECT_EQ(moving, bare);
    EXPECT_NE(placed.key, bare.key);
    EXPECT_NE(placed.ground, bare.ground);
}

// Seed 004's directional and non-directional bakes: the same fluence, and the
// non-directional probes hold nothing of the direction.
TEST(Bake, NonDirectionalProbesKeepTheFluenceAlone) {
    const scene::Scene s = world();
    BakeSettings b = quick();
    const bake::ChunkBake directional = bake::bake_chunk(s, {0, 0}, b);
    b.directional = false;
    const bake::ChunkBake flat = bake::bake_chunk(s, {0, 0}, b);
    EXPECT_NE(flat.key, directional.key);
    EXPECT_EQ(flat.ground, directional.ground);
    int directed = 0;
    for (std::size_t k = 0; k < flat.probes.size(); ++k) {
        EXPECT_EQ(flat.probes[k].c[0], directional.probes[k].c[0]);
        for (std::size_t h = 1; h < 5; ++h) EXPECT_EQ(flat.probes[k].c[h], glm::vec3(0.0f));
        directed += glm::length(directional.probes[k].c[1]) > 1e-3f;
    }
    EXPECT_GT(directed, 10) << "the directional bake's probes beside the lava hold a direction";
}

// A world's own bake settings (its scene's "bake") under the options a command line gave:
// given ones win, the rest stay the world's.
TEST(Bake, GivenOptionsWinOverTheWorldsSettings) {
    BakeSettings cli_values;
    cli::Parser p("lantern-bake", "", "");
    bake::add_settings_options(p, cli_values, "--");
    const char* argv[] = {"lantern-bake", "--rays", "9", "--solver", "seed002", "--max-level", "1"};
    ASSERT_FALSE(p.parse(7, argv));
    BakeSettings world;
    world.rays = 100;
    world.margin = 7;
    world.falloff = 2.5f;
    world.eps = 0.2f;
    const BakeSettings s = bake::given_settings(p, cli_values, "--").over(world);
    EXPECT_EQ(s.rays, 9);
    EXPECT_EQ(s.solver, bake::BakeSolver::seed002);
    EXPECT_EQ(s.max_level, 1);
    EXPECT_EQ(s.margin, 7);
    EXPECT_EQ(s.falloff, 2.5f);
    EXPECT_EQ(s.eps, 0.2f);
    EXPECT_EQ(s.resolution, world.resolution);
    // Nothing given: the world's settings as they are.
    cli::Parser q("lantern-bake", "", "");
    BakeSettings unused;
    bake::add_settings_options(q, unused, "--");
    const char* none[] = {"lantern-bake"};
    ASSERT_FALSE(q.parse(1, none));
    EXPECT_EQ(bake::given_settings(q, unused, "--").over(world), world);
    // --density (repeatable) replaces the world's regions.
    world.density = {{{5, 5}, {6, 6}, 8}};
    BakeSettings d_values;
    cli::Parser d("lantern-bake", "", "");
    bake::add_settings_options(d, d_values, "--");
    const char* dargv[] = {"lantern-bake", "--density", "0,-1,3,2,1", "--density", "2,2,2,2,16"};
    ASSERT_FALSE(d.parse(5, dargv));
    const BakeSettings ds = bake::given_settings(d, d_values, "--").over(world);
    ASSERT_EQ(ds.density.size(), 2u);
    EXPECT_EQ(ds.density[0], (scene::BakeDensity{{0, -1}, {3, 2}, 1}));
    EXPECT_EQ(ds.resolution_at(2, 2), 16);
    EXPECT_EQ(ds.resolution_at(5, 5), world.resolution);
    for (const char* bad : {"1,2,3", "0,0,1,1,17", "2,0,1,1,4", "0,0,1,1,x", "0,0,1,1,4,"}) {
        BakeSettings v;
        cli::Parser e("lantern-bake", "", "");
        bake::add_settings_options(e, v, "--");
        const char* eargv[] = {"lantern-bake", "--density", bad};
        EXPECT_EQ(e.parse(3, eargv), std::optional<int>(2)) << bad;
    }
}

// Seed 004's texel density per chunk: each chunk bakes at its region's resolution, with the
// key and the bytes a bake of the whole world at that resolution gives it, so a chunk in no
// region keeps its cache; the run time lays them out at the finest.
TEST(Bake, TexelDensityPerChunkBakesEachChunkAtItsOwnResolution) {
    const scene::Scene s = world();
    BakeSettings b = quick();
    b.rays = 32;
    b.face_rays = 16;
    BakeSettings dense = b;
    dense.density = {{{0, 0}, {0, 1}, 1}, {{1, 1}, {2, 1}, 3}, {{2, 1}, {2, 1}, 4}};
    EXPECT_EQ(dense.resolution_at(0, 1), 1);
    EXPECT_EQ(dense.resolution_at(1, 1), 3);
    EXPECT_EQ(dense.resolution_at(2, 1), 4); // the last region holding a chunk wins
    EXPECT_EQ(dense.resolution_at(1, 0), 2); // in none: the world's
    auto uniform = [&](int r) {
        BakeSettings u = b;
        u.resolution = r;
        return u;
    };
    for (ChunkId c : bake::scene_chunks(s)) {
        const int r = dense.resolution_at(c.x, c.z);
        EXPECT_EQ(bake::chunk_key(s, c, dense), bake::chunk_key(s, c, uniform(r))) << c.x << ", " << c.z;
        if (r != b.resolution) {
            EXPECT_NE(bake::chunk_key(s, c, dense), bake::chunk_key(s, c, b));
        }
    }
    TempDir dir;
    auto report = bake::bake_world(s, dir.path().string(), dense);
    ASSERT_TRUE(report.ok()) << report.error().message;
    std::vector<bake::ChunkBake> loaded;
    for (ChunkId c : bake::scene_chunks(s)) {
        auto chunk = bake::load_chunk(dir.path().string(), c, bake::chunk_key(s, c, dense));
        ASSERT_TRUE(chunk) << c.x << ", " << c.z;
        EXPECT_EQ(chunk->resolution, dense.resolution_at(c.x, c.z));
        loaded.push_back(std::move(*chunk));
    }
    // The bytes of a uniform bake at the chunk's resolution (chunk (1, 1) holds the baked light).
    auto file_bytes = [](const bake::ChunkBake& c) {
        const std::vector<std::byte> e = bake::encode_chunk(c);
        std::vector<std::uint8_t> u(e.size());
        std::memcpy(u.data(), e.data(), e.size());
        return u;
    };
    EXPECT_EQ(file_bytes(bake::bake_chunk(s, {1, 1}, uniform(3))), bytes_of((dir.path() / bake::chunk_file_name({1, 1})).string()));
    EXPECT_EQ(file_bytes(bake::bake_chunk(s, {0, 0}, uniform(1))), bytes_of((dir.path() / bake::chunk_file_name({0, 0})).string()));
    EXPECT_FALSE(loaded[4].empty);
    // A second run reuses every file; a chunk outside the regions reads the uniform bake's file.
    report = bake::bake_world(s, dir.path().string(), dense);
    ASSERT_TRUE(report.ok());
    EXPECT_EQ(report->reused, report->chunks);
    EXPECT_TRUE(bake::load_chunk(dir.path().string(), {1, 0}, bake::chunk_key(s, {1, 0}, b)));
    // The run time lays them out at the finest resolution.
    std::vector<const bake::ChunkBake*> pointers;
    for (const auto& c : loaded) pointers.push_back(&c);
    auto light = bake::runtime_light(pointers, gi::WallView::of(s.walls), 0.0f);
    ASSERT_TRUE(light);
    EXPECT_EQ(light->resolution, 4);
    // Chunk (1, 1) at 3 texels a tile, read at its own texel centres, is its own light (within
    // RGBM8's rounding and the bilinear blend with its neighbouring texels: 5 % relative RMS).
    const bake::ChunkBake& c11 = loaded[4];
    int checked = 0;
    double err2 = 0.0, ref2 = 0.0;
    for (int y = 4; y < c11.side() - 4; y += 5)
        for (int x = 4; x < c11.side() - 4; x += 5) {
            const glm::vec2 p = glm::vec2(32.0f, 32.0f) + (glm::vec2(float(x), float(y)) + 0.5f) / 3.0f;
            const glm::ivec2 tile(int(std::floor(p.x)), int(std::floor(p.y)));
            bool near_wall = false;
            for (int dz = -1; dz <= 1; ++dz)
                for (int dx = -1; dx <= 1; ++dx) near_wall |= s.walls.is_wall_tile(tile.x + dx, tile.y + dz);
            if (near_wall) continue;
            const glm::vec3 want = texel(c11.ground, c11.side(), x, y), d = light->sample(0, p) - want;
            err2 += double(glm::dot(d, d));
            ref2 += double(glm::dot(want, want));
            ++checked;
        }
    EXPECT_GT(checked, 100);
    EXPECT_GT(ref2, 0.0) << "the baked light reaches chunk (1, 1)";
    EXPECT_LT(std::sqrt(err2 / std::max(ref2, 1e-30)), 0.05);
}

// How a coarser chunk is laid out at a finer resolution (runtime_light): bilinear between its
// texels, so a linear ramp comes back exactly; over the texels that hold light only, so
// light beside a wall is not pulled to the wall's zero; and no step at the border with a
// finer chunk beyond the ramp's own change over a tile.
TEST(BakeAtRunTime, ACoarserChunkIsResampledBilinearlyOverItsLitTexels) {
    scene::WallGrid walls;
    walls.width = 64;
    walls.height = 32;
    walls.cells.assign(std::size_t(64 * 32), 0);
    walls.cells[std::size_t(10 * 64 + 10)] = scene::default_wall_cell; // one wall tile, (10, 10)
    auto ramp = [](glm::vec2 p) { return glm::vec3(0.2f + 0.01f * p.x, 0.1f + 0.005f * p.y, 0.3f); };
    auto chunk = [&](int x, int r) {
        bake::ChunkBake c;
        c.id = {x, 0};
        c.key = std::uint64_t(x + 1);
        c.resolution = r;
        c.empty = false;
        const int side = c.side();
        c.ground.assign(std::size_t(side * side * 3), 0.0f);
        for (auto& f : c.faces) f.assign(c.ground.size(), 0.0f);
        for (int y = 0; y < side; ++y)
            for (int i = 0; i < side; ++i) {
                const glm::vec2 p = glm::vec2(float(x * 32), 0.0f) + (glm::vec2(float(i), float(y)) + 0.5f) / float(r);
                if (walls.is_wall_tile(int(std::floor(p.x)), int(std::floor(p.y)))) continue; // walls hold 0
                const glm::vec3 v = ramp(p);
                for (int k = 0; k < 3; ++k) c.ground[(std::size_t(y) * std::size_t(side) + std::size_t(i)) * 3 + std::size_t(k)] = v[k];
            }
        c.probes.resize(std::size_t(bake::chunk_probes * bake::chunk_probes));
        c.probe_valid.assign(c.probes.size(), 1);
        return c;
    };
    const bake::ChunkBake coarse = chunk(0, 1), fine = chunk(1, 4);
    const bake::ChunkBake* pointers[] = {&coarse, &fine};
    auto light = bake::runtime_light(pointers, gi::WallView::of(walls), 0.0f);
    ASSERT_TRUE(light);
    ASSERT_EQ(light->resolution, 4);
    // The coarse chunk (1 texel a tile, laid out at 4) holds no detail below brick level 2, so
    // its cells stop there although the ramp's range exceeds eps 0; the fine chunk's do not.
    EXPECT_EQ(light->level(0, {5.5f, 20.5f}), 2);
    EXPECT_EQ(light->level(0, {40.5f, 20.5f}), 0);
    EXPECT_EQ(light->bricks.bricks_per_level[0] + light->bricks.bricks_per_level[1], 32 * 32);
    auto close = [](glm::vec3 got, glm::vec3 want, float tolerance) {
        return glm::all(glm::lessThanEqual(glm::abs(got - want), glm::vec3(tolerance)));
    };
    // Inside the coarse chunk, away from its border and the wall: the ramp, at every fine texel.
    int inside = 0;
    for (int y = 4; y < 124; ++y)
        for (int x = 4; x < 124; ++x) {
            const glm::vec2 p = (glm::vec2(float(x), float(y)) + 0.5f) / 4.0f;
            if (glm::all(glm::greaterThan(p, glm::vec2(8.5f))) && glm::all(glm::lessThan(p, glm::vec2(12.5f)))) continue;
            EXPECT_TRUE(close(light->sample(0, p), ramp(p), 0.004f)) << p.x << ", " << p.y;
            ++inside;
        }
    EXPECT_GT(inside, 14000);
    // Beside the wall tile: its zero does not pull the light down (a blend with it would give
    // 0.625 of the light at x = 11.125).
    for (float z : {9.125f, 10.5f, 11.875f}) {
        const glm::vec2 p(11.125f, z);
        const glm::vec3 got = light->sample(0, p), want = ramp(glm::vec2(11.5f, z));
        EXPECT_TRUE(close(got, want, 0.01f)) << z << ": " << got.x << " " << got.y << " " << got.z << " against " << want.x << " " << want.y << " " << want.z;
    }
    // Across the border x = 32: the step is within the ramp's change over one tile.
    for (float z = 2.5f; z < 30.0f; z += 3.0f) {
        const glm::vec3 a = light->sample(0, {31.875f, z}), b = light->sample(0, {32.125f, z});
        EXPECT_LE(std::abs(b.x - a.x), 0.01f + 0.004f) << z;
    }
}

// Seed 004's pulsing emission: a pulsing material's glow is baked apart from the steady
// light (the gather is linear in its sources: steady + pulsing equals the bake of the steady
// world, light by light and probe by probe), keyed apart, kept in the cache file, and the
// run time's light at pulse p is the steady part plus p times the pulsing part.
TEST(Bake, APulsingGlowIsBakedApartAndAddsUpToTheSteadyBake) {
    scene::Scene steady = world(); // the lava wall in chunk (0, 0) glows
    steady.point_lights.push_back({{20.5f, 20.5f}, 1.0f, {0.8f, 0.9f, 1.0f}, 2.0f, 8.0f, LightMode::baked});
    scene::Scene pulsing = steady;
    pulsing.materials[0].pulse = 0.5f;
    scene::Scene dark = steady;
    dark.materials[0].emission = glm::vec3(0.0f);
    BakeSettings b = quick();
    b.rays = 64;
    b.face_rays = 32;
    EXPECT_NE(bake::chunk_key(pulsing, {0, 0}, b), bake::chunk_key(steady, {0, 0}, b));
    const bake::ChunkBake a = bake::bake_chunk(steady, {0, 0}, b), p = bake::bake_chunk(pulsing, {0, 0}, b),
                          d = bake::bake_chunk(dark, {0, 0}, b);
    ASSERT_TRUE(p.pulses());
    EXPECT_FALSE(a.pulses());
    // The steady part is the world without the glow, exactly.
    EXPECT_EQ(p.ground, d.ground);
    EXPECT_EQ(p.faces, d.faces);
    EXPECT_EQ(p.probes, d.probes);
    // Steady + pulsing = the steady world's bake.
    double err2 = 0.0, ref2 = 0.0, pulse2 = 0.0;
    auto sum_check = [&](const std::vector<float>& whole, const std::vector<float>& part, const std::vector<float>& pulse) {
        ASSERT_EQ(whole.size(), pulse.size());
        for (std::size_t i = 0; i < whole.size(); ++i) {
            const double e = double(part[i]) + pulse[i] - whole[i];
            err2 += e * e;
            ref2 += double(whole[i]) * whole[i];
            pulse2 += double(pulse[i]) * pulse[i];
        }
    };
    sum_check(a.ground, p.ground, p.pulse.ground);
    for (int f = 0; f < 4; ++f) sum_check(a.faces[std::size_t(f)], p.faces[std::size_t(f)], p.pulse.faces[std::size_t(f)]);
    std::printf("steady + pulsing against the steady bake: relative RMS %.2e; the pulsing part holds %.1f %% of the light\n",
                std::sqrt(err2 / ref2), 100.0 * std::sqrt(pulse2 / ref2));
    EXPECT_LT(std::sqrt(err2 / ref2), 1e-5);
    EXPECT_GT(pulse2, 0.01 * ref2) << "the lava's glow is a good part of this chunk's light";
    EXPECT_LT(pulse2, 0.99 * ref2) << "and the steady light the rest";
    for (std::size_t k = 0; k < a.probes.size(); ++k)
        for (std::size_t h = 0; h < a.probes[k].c.size(); ++h)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(p.probes[k].c[h][c] + p.pulse.probes[k].c[h][c], a.probes[k].c[h][c],
                            1e-5f + 1e-5f * std::abs(a.probes[k].c[h][c]));
    // A chunk the glow does not reach has no pulsing part.
    EXPECT_FALSE(bake::bake_chunk(pulsing, {2, 1}, b).pulses());
    // The cache file keeps both parts (as halves), and a file without one reads as before.
    TempDir dir;
    ASSERT_TRUE(bake::save_chunk(dir.path().string(), p).ok());
    auto back = bake::load_chunk(dir.path().string(), {0, 0}, p.key);
    ASSERT_TRUE(back);
    ASSERT_TRUE(back->pulses());
    for (std::size_t i = 0; i < p.pulse.ground.size(); ++i)
        ASSERT_NEAR(back->pulse.ground[i], p.pulse.ground[i], 1e-3f * p.pulse.ground[i] + 1e-6f);
    EXPECT_EQ(back->pulse.probes, p.pulse.probes);
    EXPECT_EQ(back->probes, p.probes);
    auto bytes = bytes_of((dir.path() / bake::chunk_file_name({0, 0})).string());
    bytes.resize(bytes.size() - 1);
    EXPECT_FALSE(bake::decode_chunk(bytes).ok()) << "a truncated pulsing file is refused";
    // At run time: the light at pulse 1 is the steady world's, at pulse 0 the dark world's.
    const bake::ChunkBake* pp[] = {&p};
    const bake::ChunkBake* ap[] = {&a};
    const bake::ChunkBake* dp[] = {&d};
    const gi::WallView walls = gi::WallView::of(steady.walls);
    auto lp = bake::runtime_light(pp, walls, 0.0f), la = bake::runtime_light(ap, walls, 0.0f), ld = bake::runtime_light(dp, walls, 0.0f);
    ASSERT_TRUE(lp->pulsing);
    EXPECT_FALSE(la->pulsing);
    int checked = 0;
    for (float z = 1.3f; z < 30.0f; z += 1.7f)
        for (float x = 1.3f; x < 30.0f; x += 1.7f) {
            if (steady.walls.is_wall_tile(int(x), int(z))) continue;
            const glm::vec2 q(x, z);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(lp->light(0, q, 1.0f)[c], la->sample(0, q)[c], 0.01f + 0.01f * la->sample(0, q)[c]) << x << ", " << z;
                EXPECT_NEAR(lp->light(0, q, 0.0f)[c], ld->sample(0, q)[c], 0.01f + 0.01f * ld->sample(0, q)[c]) << x << ", " << z;
            }
            ++checked;
        }
    EXPECT_GT(checked, 200);
}

namespace {

// The world's walls lit by one mixed sun alone (default walls, no glow).
scene::Scene sunlit_world(glm::vec3 direction, glm::vec3 color = glm::vec3(1.0f), float intensity = 1.0f) {
    scene::Scene s = world();
    s.point_lights.clear();
    s.materials.clear();
    for (auto& c : s.walls.cells) c = c != 0 ? scene::default_wall_cell : 0;
    scene::DirectionalLight sun;
    sun.direction = direction;
    sun.color = color;
    sun.intensity = intensity;
    sun.mode = LightMode::mixed;
    s.directional_lights = {sun};
    return s;
}

double relative_rms(const std::vector<float>& got, const std::vector<float>& want) {
    double e2 = 0.0, r2 = 0.0;
    for (std::size_t i = 0; i < want.size(); ++i) {
        e2 += (double(got[i]) - want[i]) * (double(got[i]) - want[i]);
        r2 += double(want[i]) * want[i];
    }
    return r2 > 0.0 ? std::sqrt(e2 / r2) : 0.0;
}

} // namespace

// Seed 004's precomputed GI for the moving sun: with bake.sun_keys the mixed sun's bounce is
// baked at each key's time of the day's path, at unit colour, apart from the steady light;
// key k is exactly the bake of the sun fixed there; the cache file keeps the keys; at run time
// the two keys around the sun's time blend, scaled by its colour. Between keys the blend is an
// approximation: its error against the exact bake at the midpoint is printed.
TEST(Bake, SunKeysHoldTheMovingSunsBounceAtEachKeyOfTheDay) {
    BakeSettings b = quick();
    b.rays = 64;
    b.face_rays = 32;
    BakeSettings keyed_settings = b;
    keyed_settings.sun_keys = 5; // sunrise, 0.375, noon, 0.625, sunset
    const scene::Scene s = sunlit_world(glm::normalize(glm::vec3(0.3f, -0.8f, 0.2f)), {1.0f, 0.5f, 0.2f}, 0.7f);
    const ChunkId c{1, 0};
    EXPECT_NE(bake::chunk_key(s, c, keyed_settings), bake::chunk_key(s, c, b));
    const bake::ChunkBake keyed = bake::bake_chunk(s, c, keyed_settings);
    ASSERT_FALSE(keyed.empty);
    ASSERT_EQ(keyed.sun_keys.size(), 5u);
    // The steady part leaves the keyed sun out: nothing else lights this world.
    for (float v : keyed.ground) ASSERT_EQ(v, 0.0f);
    // Key 2 (noon) is the bake of a white sun fixed at noon, exactly; the authored direction
    // and colour play no part.
    const bake::ChunkBake noon = bake::bake_chunk(sunlit_world(scene::day_sun_direction(0.5f)), c, b);
    EXPECT_EQ(keyed.sun_keys[2].ground, noon.ground);
    EXPECT_EQ(keyed.sun_keys[2].faces, noon.faces);
    EXPECT_EQ(keyed.sun_keys[2].probes, noon.probes);
    double noon2 = 0.0;
    for (float v : noon.ground) noon2 += double(v) * v;
    EXPECT_GT(noon2, 1.0) << "the noon sun's bounce lights the chunk";
    // Sunrise: the sun on the horizon adds nothing.
    for (float v : keyed.sun_keys[0].ground) ASSERT_EQ(v, 0.0f);
    // Halfway between noon and the next key: the blend against the exact bake there, for 5,
    // 9 and 17 keys. The light between keys is an interpolation: more keys, less error.
    double last = 1.0;
    for (int keys : {5, 9, 17}) {
        BakeSettings k_settings = b;
        k_settings.sun_keys = keys;
        const bake::ChunkBake k = keys == 5 ? keyed : bake::bake_chunk(s, c, k_settings);
        const int noon_key = (keys - 1) / 2;
        const float t = 0.5f * (scene::sun_key_time(noon_key, keys) + scene::sun_key_time(noon_key + 1, keys));
        const bake::ChunkBake mid = bake::bake_chunk(sunlit_world(scene::day_sun_direction(t)), c, b);
        std::vector<float> blend(mid.ground.size());
        for (std::size_t i = 0; i < blend.size(); ++i)
            blend[i] = 0.5f * (k.sun_keys[std::size_t(noon_key)].ground[i] + k.sun_keys[std::size_t(noon_key + 1)].ground[i]);
        const double error = relative_rms(blend, mid.ground);
        std::printf("moving sun, %d keys (%.1f degrees apart): the blend at t = %.4f against the exact bake: relative RMS %.1f %%\n",
                    keys, 180.0 / double(keys - 1), double(t), 100.0 * error);
        EXPECT_LT(error, last) << keys << " keys";
        last = error;
    }
    EXPECT_LT(last, 0.1) << "17 keys";
    // The cache file keeps the keys (as halves); a truncated one is refused.
    TempDir dir;
    ASSERT_TRUE(bake::save_chunk(dir.path().string(), keyed).ok());
    auto back = bake::load_chunk(dir.path().string(), c, keyed.key);
    ASSERT_TRUE(back);
    ASSERT_EQ(back->sun_keys.size(), 5u);
    for (std::size_t i = 0; i < keyed.sun_keys[2].ground.size(); ++i)
        ASSERT_NEAR(back->sun_keys[2].ground[i], keyed.sun_keys[2].ground[i], 1e-3f * keyed.sun_keys[2].ground[i] + 1e-6f);
    EXPECT_EQ(back->sun_keys[3].probes, keyed.sun_keys[3].probes);
    auto bytes = bytes_of((dir.path() / bake::chunk_file_name(c)).string());
    bytes.resize(bytes.size() - 1);
    EXPECT_FALSE(bake::decode_chunk(bytes).ok()) << "a truncated keyed file is refused";
    // At run time: the sun at noon with colour C reads C x key 2.
    const bake::ChunkBake* kp[] = {&keyed};
    const bake::ChunkBake* np[] = {&noon};
    const gi::WallView walls = gi::WallView::of(s.walls);
    auto lk = bake::runtime_light(kp, walls, 0.0f), ln = bake::runtime_light(np, walls, 0.0f);
    ASSERT_EQ(lk->sun_keys, 5);
    const glm::vec3 color(1.0f, 0.5f, 0.2f);
    const gi::BakedSun at_noon{2, 0.0f, color};
    int checked = 0;
    for (float z = 1.3f; z < 30.0f; z += 1.7f)
        for (float x = 33.3f; x < 62.0f; x += 1.7f) {
            if (s.walls.is_wall_tile(int(x), int(z))) continue;
            const glm::vec2 q(x, z);
            const glm::vec3 want = color * ln->sample(0, q), got = lk->light(0, q, 1.0f, at_noon);
            for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[ch], want[ch], 0.01f + 0.01f * want[ch]) << x << ", " << z;
            ++checked;
        }
    EXPECT_GT(checked, 200);
    // Settings: 1 key, or more than 32, is refused.
    BakeSettings bad = b;
    bad.sun_keys = 1;
    EXPECT_FALSE(bake::validate_settings(bad).ok());
    bad.sun_keys = 33;
    EXPECT_FALSE(bake::validate_settings(bad).ok());
}

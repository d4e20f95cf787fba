// The transport reference's disk cache: round trip, keys, and damaged files.
#include "transport_test_util.hpp"

#include "common/test_support.hpp"
#include "lantern/core/file.hpp"
#include "lantern/transport/cache.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>

namespace {

using namespace lantern;
using transport::TransportResult;

scene::Scene lit_room() {
    scene::Scene s = transport_test::scene(transport_test::closed_room(), {8, 8}, {16, 16});
    s.point_lights.push_back({{7.3f, 8.4f}, 1.0f, {1.0f, 0.8f, 0.6f}, 1.0f, 6.0f});
    return s;
}

TransportResult solve_cached(const scene::Scene& s, const transport::TransportSettings& t,
                             const std::string& dir) {
    transport::SolveOptions o;
    o.cache_dir = dir;
    auto r = transport::solve_transport(s, t, o);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    return std::move(r.value());
}

int files_in(const std::string& dir) {
    int n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
    return n;
}

void expect_same_fields(const TransportResult& a, const TransportResult& b) {
    EXPECT_EQ(a.window, b.window);
    EXPECT_EQ(a.direct, b.direct);
    EXPECT_EQ(a.indirect, b.indirect);
    EXPECT_EQ(a.indirect_error, b.indirect_error);
    EXPECT_EQ(a.face_direct, b.face_direct);
    EXPECT_EQ(a.face_indirect, b.face_indirect);
    EXPECT_EQ(a.face_indirect_error, b.face_indirect_error);
}

TEST(Cache, RoundTrip) {
    test::TempDir tmp;
    const std::string dir = tmp.file("cache"); // created by the first solve
    const scene::Scene s = lit_room();
    const auto t = transport_test::quick(0.5f);
    const TransportResult first = solve_cached(s, t, dir);
    EXPECT_FALSE(first.stats.from_cache);
    ASSERT_EQ(files_in(dir), 1);
    EXPECT_TRUE(std::filesystem::exists(transport::cache_path(dir, *transport::cache_key(s, t))));

    const TransportResult second = solve_cached(s, t, dir);
    EXPECT_TRUE(second.stats.from_cache);
    expect_same_fields(first, second);
    EXPECT_EQ(second.stats.photons, first.stats.photons);
    EXPECT_EQ(second.stats.batches, first.stats.batches);
    EXPECT_EQ(second.stats.relative_error, first.stats.relative_error);
    EXPECT_EQ(second.stats.seconds, first.stats.seconds);
}

TEST(Cache, KeyCoversSceneSettingsAndWindow) {
    const scene::Scene s = lit_room();
    const auto t = transport_test::quick(0.5f);
    const std::uint64_t key = *transport::cache_key(s, t);
    EXPECT_EQ(*transport::cache_key(s, t), key);

    auto other_settings = t;
    other_settings.albedo = 0.6f;
    EXPECT_NE(*transport::cache_key(s, other_settings), key);
    other_settings = t;
    other_settings.seed = 2;
    EXPECT_NE(*transport::cache_key(s, other_settings), key);

    scene::Scene other = s;
    other.walls.cells[0] = 1;
    EXPECT_NE(*transport::cache_key(other, t), key);
    other = s;
    other.point_lights[0].radius += 0.5f;
    EXPECT_NE(*transport::cache_key(other, t), key);
    other = s;
    other.shadow_proxies.push_back({});
    EXPECT_NE(*transport::cache_key(other, t), key);
    other = s;
    other.view = scene::OrthoView{{9, 8}, {16, 16}};
    EXPECT_NE(*transport::cache_key(other, t), key);
    other = s;
    other.gi.light_softness = 2.0f;
    EXPECT_NE(*transport::cache_key(other, t), key);
    other = s;
    other.gi.heat_rounds = 7; // Lantern-only settings do not change the reference
    EXPECT_EQ(*transport::cache_key(other, t), key);
}

TEST(Cache, DamagedFilesAreIgnoredAndReplaced) {
    test::TempDir tmp;
    const std::string dir = tmp.path().string();
    const scene::Scene s = lit_room();
    const auto t = transport_test::quick(0.5f);
    const TransportResult fresh = solve_cached(s, t, dir);
    const std::string path = transport::cache_path(dir, *transport::cache_key(s, t));
    auto bytes = read_binary_file(path);
    ASSERT_TRUE(bytes.ok());
    const std::vector<std::uint8_t> good = *bytes;

    auto damage = [&](std::vector<std::uint8_t> b) {
        ASSERT_TRUE(write_file_atomic(
                        path, std::span(reinterpret_cast<const std::byte*>(b.data()), b.size()))
                        .ok());
        EXPECT_FALSE(transport::read_cached(path, *transport::cache_key(s, t)).ok());
        const TransportResult again = solve_cached(s, t, dir);
        EXPECT_FALSE(again.stats.from_cache);
        expect_same_fields(fresh, again);
        EXPECT_TRUE(transport::read_cached(path, *transport::cache_key(s, t)).ok()); // replaced
    };
    damage(std::vector<std::uint8_t>(good.begin(),
                                     good.begin() + std::ptrdiff_t(good.size() / 2))); // truncated
    damage({});                                                                        // empty
    auto extended = good;
    extended.push_back(0);
    damage(extended); // trailing bytes
    auto nan = good;
    const float bad = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(nan.data() + nan.size() - sizeof(float), &bad, sizeof(float));
    damage(nan); // a non-finite value
    auto version = good;
    version[8] ^= 0xFF; // the code version
    damage(version);

    // A valid file of another problem under this name is rejected by its key.
    auto other_settings = t;
    other_settings.albedo = 0.25f;
    solve_cached(s, other_settings, dir); // writes the other problem's file
    std::filesystem::copy_file(transport::cache_path(dir, *transport::cache_key(s, other_settings)),
                               path, std::filesystem::copy_options::overwrite_existing);
    EXPECT_FALSE(transport::read_cached(path, *transport::cache_key(s, t)).ok());
    expect_same_fields(fresh, solve_cached(s, t, dir));
}

// A cached result whose direct light differs from the model's (as after a change to
// Lantern's direct-light code, which the key cannot see) is stale.
TEST(Cache, StaleDirectTermsAreRecomputed) {
    test::TempDir tmp;
    const std::string dir = tmp.path().string();
    const scene::Scene s = lit_room();
    const auto t = transport_test::quick(0.5f);
    const TransportResult fresh = solve_cached(s, t, dir);
    const std::string path = transport::cache_path(dir, *transport::cache_key(s, t));
    auto bytes = *read_binary_file(path);
    constexpr std::size_t header = 80; // the direct field follows (cache.hpp)
    float first = 0.0f;
    std::memcpy(&first, bytes.data() + header, sizeof(float));
    first += 0.5f;
    std::memcpy(bytes.data() + header, &first, sizeof(float));
    ASSERT_TRUE(write_file_atomic(
                    path, std::span(reinterpret_cast<const std::byte*>(bytes.data()), bytes.size()))
                    .ok());
    ASSERT_TRUE(transport::read_cached(path, *transport::cache_key(s, t)).ok()); // well formed
    const TransportResult again = solve_cached(s, t, dir);
    EXPECT_FALSE(again.stats.from_cache);
    expect_same_fields(fresh, again);
    EXPECT_TRUE(solve_cached(s, t, dir).stats.from_cache); // replaced by the fresh result
}

TEST(Cache, DefaultFolderFollowsTheEnvironment) {
    const char* saved = std::getenv("LANTERN_TRANSPORT_CACHE");
    const std::string keep = saved ? saved : "";
    setenv("LANTERN_TRANSPORT_CACHE", "/tmp/lantern-transport-test", 1);
    EXPECT_EQ(transport::default_cache_dir(), "/tmp/lantern-transport-test");
    if (saved)
        setenv("LANTERN_TRANSPORT_CACHE", keep.c_str(), 1);
    else
        unsetenv("LANTERN_TRANSPORT_CACHE");
    EXPECT_EQ(transport::cache_path("/c", 0x1234), "/c/0000000000001234.ltr");
}

} // namespace

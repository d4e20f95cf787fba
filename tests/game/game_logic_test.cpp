// The game's rules without a window or GPU: collision, the following camera and picking,
// flicker and the sun, worlds, and save files (exact round trip, clear errors, and a kill
// during a save that leaves the previous save loadable).
#include "lantern/game/baking.hpp"
#include "lantern/game/gameplay.hpp"
#include "lantern/game/options.hpp"
#include "lantern/gi/backend.hpp"
#include "lantern/scene/procedural.hpp"
#include "lantern/systems/gi_frame.hpp"
#include "lantern/game/save.hpp"
#include "lantern/game/world_setup.hpp"
#include "lantern/gi/window.hpp"
#include "lantern/core/file.hpp"
#include "common/test_support.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <array>
#include <csignal>
#include <fstream>
#include <random>
#include <set>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

using namespace lantern;
using namespace lantern::game;

namespace {

// A 10 x 10 room (walls on its border) with a pillar at (5, 5).
IsWall room() {
    return [](int x, int z) { return x <= 0 || z <= 0 || x >= 9 || z >= 9 || (x == 5 && z == 5); };
}

jobs::JobSystem::Config no_workers() {
    jobs::JobSystem::Config c;
    c.worker_threads = 0;
    return c;
}

} // namespace

TEST(Gameplay, MovementStopsAtWallsAndSlidesAlongThem) {
    const float r = 0.3f;
    // Walking east into the pillar stops the circle touching it.
    glm::vec2 p = move_with_collision({3.5f, 5.5f}, {3.0f, 0.0f}, r, room());
    EXPECT_NEAR(p.x, 5.0f - r, 0.01f);
    EXPECT_FLOAT_EQ(p.y, 5.5f);
    // Diagonal into the north wall: x keeps moving, z stops.
    p = move_with_collision({2.5f, 7.5f}, {1.0f, 2.0f}, r, room());
    EXPECT_FLOAT_EQ(p.x, 3.5f);
    EXPECT_NEAR(p.y, 9.0f - r, 0.01f);
    // A large step never tunnels through a one-tile wall.
    p = move_with_collision({3.5f, 2.5f}, {0.0f, 50.0f}, r, room());
    EXPECT_LT(p.y, 9.0f - r + 1e-4f);
    // Free movement is exact.
    p = move_with_collision({2.5f, 2.5f}, {1.25f, 0.5f}, r, room());
    EXPECT_FLOAT_EQ(p.x, 3.75f);
    EXPECT_FLOAT_EQ(p.y, 3.0f);
}

TEST(Gameplay, CameraRayThroughTheCentreHitsThePlayersFocus) {
    const CameraRig rig;
    const scene::PerspectiveCamera cam = follow_camera({12.5f, 0.0f, 7.5f}, rig);
    const Ray centre = camera_ray(cam, {0.5f, 0.5f});
    const auto tile = pick_ground(centre);
    ASSERT_TRUE(tile);
    EXPECT_EQ(*tile, glm::ivec2(12, 7));
    // Up the screen is -z (a map's rows run down the screen), right is +x.
    EXPECT_LT(pick_ground(camera_ray(cam, {0.5f, 0.1f}))->y, 7);
    EXPECT_GT(pick_ground(camera_ray(cam, {0.9f, 0.5f}))->x, 12);
    // The visible footprint of the ray corners lies in the GI window's view.
    const auto area = gi::visible_area(scene::ViewSpec{cam});
    ASSERT_TRUE(area);
    const gi::CameraView view{area->min.x, area->min.y, area->size.x, area->size.y};
    for (glm::vec2 ndc : {glm::vec2(0.0f, 0.0f), glm::vec2(1.0f, 1.0f), glm::vec2(0.0f, 1.0f), glm::vec2(1.0f, 0.0f)}) {
        const Ray ray = camera_ray(cam, ndc);
        const float t = -ray.origin.y / ray.direction.y;
        const glm::vec3 g = ray.origin + ray.direction * t;
        EXPECT_GE(g.x, view.min_x - 1e-3f);
        EXPECT_LE(g.x, view.min_x + view.width + 1e-3f);
        EXPECT_GE(g.z, view.min_z - 1e-3f);
        EXPECT_LE(g.z, view.min_z + view.height + 1e-3f);
    }
}

TEST(Gameplay, PickWallFindsTheFirstWallAlongTheRay) {
    const CameraRig rig;
    const scene::PerspectiveCamera cam = follow_camera({4.5f, 0.0f, 2.5f}, rig);
    // A column of walls at x = 4..5, z = 4: looking at (4.5, 4.5) from the south-above.
    const IsWall wall = [](int x, int z) { return x == 4 && z == 4; };
    // Find the NDC of the wall top centre by searching the screen.
    bool hit_any = false;
    for (float y = 0.0f; y <= 1.0f; y += 0.02f) {
        const auto t = pick_wall(camera_ray(cam, {0.5f, y}), 2.0f, wall);
        if (t) {
            EXPECT_EQ(*t, glm::ivec2(4, 4));
            hit_any = true;
        }
    }
    EXPECT_TRUE(hit_any);
    EXPECT_FALSE(pick_wall(camera_ray(cam, {0.05f, 0.95f}), 2.0f, wall));
}

TEST(Gameplay, FlickerIsSmoothBoundedAndDecorrelated) {
    float lo = 10.0f, hi = -10.0f, max_step = 0.0f, prev = flicker(0.0, 0.3f);
    double differs = 0.0;
    for (int i = 1; i < 6000; ++i) {
        const double t = i / 60.0;
        const float f = flicker(t, 0.3f);
        lo = std::min(lo, f), hi = std::max(hi, f);
        max_step = std::max(max_step, std::abs(f - prev));
        prev = f;
        differs += std::abs(f - flicker(t, 2.7f));
    }
    EXPECT_GE(lo, 0.8f);
    EXPECT_LE(hi, 1.05f);
    EXPECT_GT(hi - lo, 0.1f);    // it does flicker
    EXPECT_LT(max_step, 0.06f); // gently: no jumps between 60 Hz frames
    EXPECT_GT(differs / 6000.0, 0.02); // two torches do not flicker in step
}

TEST(Gameplay, SunRisesEastSetsWestAndIsDarkAtNight) {
    EXPECT_LT(sun_direction(0.5f).y, -0.9f); // noon: from above
    EXPECT_LT(sun_direction(0.3f).x, 0.0f);  // morning: travels west (rises in the east)
    EXPECT_GT(sun_direction(0.7f).x, 0.0f);
    EXPECT_EQ(sun_light(0.0f), glm::vec3(0.0f));
    EXPECT_EQ(sun_light(0.9f), glm::vec3(0.0f));
    EXPECT_GT(sun_light(0.5f).g, 0.5f);
    EXPECT_GT(sun_light(0.28f).r, sun_light(0.28f).b); // dawn is warm
}

TEST(Worlds, CavesSpawnInTheOpenWithTorchesCrystalsAndASun) {
    ecs::World world;
    auto w = create_world({WorldKind::caves, "", 7}, world, {});
    ASSERT_TRUE(w) << w.error().message;
    for (int dz = -2; dz <= 2; ++dz)
        for (int dx = -2; dx <= 2; ++dx)
            EXPECT_FALSE(w->source->is_wall(glm::ivec2(glm::floor(w->spawn)) + glm::ivec2(dx, dz)));
    int torches = 0, crystals = 0, suns = 0;
    world.view<Torch, PointLight>().each([&](const Torch&, const PointLight& l) {
        ++torches;
        EXPECT_FALSE(w->source->is_wall(glm::ivec2(glm::floor(l.position))));
    });
    world.view<Prop, EmissiveLight>().each([&](const Prop& p, const EmissiveLight&) { crystals += p.kind == PropKind::crystal; });
    world.view<Sun, DirectionalLight>().each([&](const Sun&, const DirectionalLight&) { ++suns; });
    EXPECT_GE(torches, 3);
    EXPECT_GE(crystals, 20);
    EXPECT_EQ(suns, 1);
    EXPECT_TRUE(world.try_get<Player>(w->player));
    EXPECT_TRUE(world.try_get<GICache>(w->camera));
    // Deterministic: the same seed gives the same world.
    ecs::World again;
    auto w2 = create_world({WorldKind::caves, "", 7}, again, {});
    EXPECT_EQ(w2->spawn, w->spawn);
    EXPECT_EQ(again.alive_count(), world.alive_count());
}

TEST(Worlds, MapTreesBecomeTreePropsWithProxyShadows) {
    test::TempDir dir;
    const std::string path = dir.file("tiny.map");
    ASSERT_TRUE(write_file_atomic(path, std::string("type octile\nheight 4\nwidth 6\nmap\n@@@@@@\n@..T.@\n@.T..@\n@@@@@@\n")));
    ecs::World world;
    WorldOptions options;
    options.decorate = false;
    auto w = create_world({WorldKind::map, path, 1}, world, options);
    ASSERT_TRUE(w) << w.error().message;
    std::set<std::pair<float, float>> trees;
    world.view<Prop, ShadowProxy>().each([&](const Prop& p, const ShadowProxy& s) {
        EXPECT_EQ(p.kind, PropKind::tree);
        EXPECT_EQ(s.shape.shape, scene::ProxyShape::circle);
        trees.insert({s.shape.position.x, s.shape.position.y});
    });
    EXPECT_EQ(trees, (std::set<std::pair<float, float>>{{3.5f, 1.5f}, {2.5f, 2.5f}}));
    EXPECT_FALSE(w->source->is_wall({3, 1})); // a tree cell is floor
    EXPECT_TRUE(w->source->is_wall({0, 0}));
    EXPECT_FALSE(w->source->is_wall(glm::ivec2(glm::floor(w->spawn))));
}

// docs/game.md's save example shows the game's defaults (it showed a day of 240 s, the
// game's is 60).
TEST(Saves, TheDocsExampleShowsTheDefaults) {
    const std::string docs = test::read_file(test::source_dir() / "docs/game.md");
    const std::size_t at = docs.find("\"day_length\": ");
    ASSERT_NE(at, std::string::npos);
    EXPECT_EQ(std::stof(docs.substr(at + 14, 8)), DayCycle{}.day_length);
}

// Beyond a map's edge is rock, as docs/game.md says (it was open floor: the player walked off
// the map): the source's tiles and chunks, and the player's movement at the edge.
TEST(Worlds, BeyondTheMapIsRock) {
    test::TempDir dir;
    const std::string path = dir.file("open.map");
    // No border of its own: row 0 and column 0 are open.
    ASSERT_TRUE(write_file_atomic(path, std::string("type octile\nheight 3\nwidth 4\nmap\n....\n....\n....\n")));
    ecs::World world;
    WorldOptions options;
    options.decorate = false;
    auto w = create_world({WorldKind::map, path, 1}, world, options);
    ASSERT_TRUE(w) << w.error().message;
    EXPECT_FALSE(w->source->is_wall({0, 0}));
    EXPECT_FALSE(w->source->is_wall({3, 2}));
    for (glm::ivec2 outside : {glm::ivec2(-1, 0), glm::ivec2(0, -1), glm::ivec2(4, 1), glm::ivec2(2, 3),
                               glm::ivec2(-500, 900)}) {
        EXPECT_TRUE(w->source->is_wall(outside)) << outside.x << "," << outside.y;
        EXPECT_EQ(w->source->cell(outside), scene::default_wall_cell);
    }
    std::vector<std::uint8_t> cells(std::size_t(systems::chunk_size * systems::chunk_size));
    w->source->generate({0, 0}, cells);
    EXPECT_EQ(cells[0], 0);                                       // tile (0, 0): the map's floor
    EXPECT_EQ(cells[4], scene::default_wall_cell);                // tile (4, 0): beyond
    EXPECT_EQ(cells[std::size_t(3 * systems::chunk_size)], 1);    // tile (0, 3): beyond
    w->source->generate({-1, 0}, cells);
    EXPECT_TRUE(std::all_of(cells.begin(), cells.end(), [](std::uint8_t c) { return c != 0; }));
    // The player, pushing west from the map's first column, stays on the map.
    const IsWall is_wall = [&](int x, int z) { return w->source->is_wall({x, z}); };
    glm::vec2 p(0.5f, 1.5f);
    for (int i = 0; i < 120; ++i) p = move_with_collision(p, glm::vec2(-0.1f, 0.0f), 0.3f, is_wall);
    EXPECT_GE(p.x, 0.3f - 1e-4f);
    // Scene files keep the GI's convention: air beyond their rows.
    systems::GridSource scene_grid(scene::WallGrid{2, 2, {0, 0}, {1, 1, 1, 1}});
    EXPECT_FALSE(scene_grid.is_wall({5, 5}));
}

TEST(Worlds, BadWorldFilesGiveOneClearMessage) {
    test::TempDir dir;
    const std::string path = dir.file("bad.map");
    ASSERT_TRUE(write_file_atomic(path, std::string("type octile\nheight 2\nwidth 3\nmap\n...\n.x.\n")));
    ecs::World world;
    auto w = create_world({WorldKind::map, path, 1}, world, {});
    ASSERT_FALSE(w);
    EXPECT_NE(w.error().message.find("bad.map:6:2:"), std::string::npos) << w.error().message;
    auto s = create_world({WorldKind::scene, dir.file("missing.json"), 1}, world, {});
    ASSERT_FALSE(s);
    EXPECT_NE(s.error().message.find("missing.json"), std::string::npos) << s.error().message;
}

namespace {

// A game state with every kind of entity and some edits.
SaveState sample_state(ecs::World& world, systems::Streaming& streaming, jobs::JobSystem& jobs) {
    auto w = create_world({WorldKind::caves, "", 11}, world, {});
    EXPECT_TRUE(w);
    streaming.load_all(world, jobs, {w->spawn.x - 20.0f, w->spawn.y - 12.0f, 40.0f, 24.0f});
    const glm::ivec2 s = glm::ivec2(glm::floor(w->spawn));
    streaming.set_wall(world, s + glm::ivec2(1, 0), true);
    streaming.set_wall(world, s + glm::ivec2(40, 3), true); // not resident
    spawn_prop(world, PropKind::lamp_post, w->spawn + glm::vec2(2.0f, 1.0f));
    spawn_prop(world, PropKind::tree, w->spawn + glm::vec2(-2.0f, 1.0f));
    const ecs::Entity block = world.create(); // mined, not yet collected
    world.emplace<DroppedItem>(block, DroppedItem{Item::wall, 3, w->spawn + glm::vec2(3.5f, -1.25f), 0.1f});
    Inventory carried;
    carried.counts = {17, 3, 0, 999, 1};
    world.set_resource<Inventory>(carried);
    world.resource<DayCycle>() = DayCycle{true, 0.625f, 30.0f};
    return capture_save(world, streaming, w->spec);
}

void expect_same(const SaveState& a, const SaveState& b) {
    EXPECT_EQ(format_save(a), format_save(b));
    EXPECT_EQ(a.world, b.world);
    EXPECT_EQ(a.player, b.player);
    ASSERT_EQ(a.entities.size(), b.entities.size());
    ASSERT_EQ(a.edits.size(), b.edits.size());
    for (std::size_t i = 0; i < a.edits.size(); ++i) {
        EXPECT_EQ(a.edits[i].coord, b.edits[i].coord);
        EXPECT_EQ(a.edits[i].cells, b.edits[i].cells);
    }
}

} // namespace

TEST(Saves, RoundTripIsExactAndRestoresTheWorld) {
    jobs::JobSystem jobs(no_workers());
    ecs::World world;
    world.set_resource<DayCycle>();
    auto w = create_world({WorldKind::caves, "", 11}, world, {});
    ASSERT_TRUE(w);
    // Build the state through a streaming object of the same world.
    ecs::World world2;
    world2.set_resource<DayCycle>();
    systems::Streaming streaming(w->source);
    const SaveState saved = sample_state(world2, streaming, jobs);
    ASSERT_GE(saved.edits.size(), 2u);
    test::TempDir dir;
    const std::string path = dir.file("world.save.json");
    ASSERT_TRUE(write_save(path, saved));
    auto loaded = read_save(path);
    ASSERT_TRUE(loaded) << loaded.error().message;
    expect_same(saved, *loaded);

    // Apply it to a fresh world: same entities, same walls, same player and day.
    ecs::World fresh;
    fresh.set_resource<DayCycle>();
    auto fw = create_world(loaded->world, fresh, {});
    ASSERT_TRUE(fw);
    apply_save(*loaded, fresh, fw->player);
    systems::Streaming restored(fw->source);
    restored.restore_edits(loaded->edits);
    restored.load_all(fresh, jobs, {fw->spawn.x - 20.0f, fw->spawn.y - 12.0f, 40.0f, 24.0f});
    const SaveState again = capture_save(fresh, restored, fw->spec);
    expect_same(saved, again);
    EXPECT_TRUE(fresh.resource<DayCycle>().running);
    EXPECT_FLOAT_EQ(fresh.resource<DayCycle>().time_of_day, 0.625f);
    EXPECT_EQ(fresh.resource<Inventory>().counts, (std::array<int, item_count>{17, 3, 0, 999, 1}));
    // The dropped block lies where it lay, resting (its hop is not saved).
    int items = 0;
    fresh.view<DroppedItem>().each([&](const DroppedItem& d) {
        ++items;
        EXPECT_EQ(d.item, Item::wall);
        EXPECT_EQ(d.count, 3);
        EXPECT_EQ(d.position, fw->spawn + glm::vec2(3.5f, -1.25f));
        EXPECT_GE(d.age, item_pickup_delay);
    });
    EXPECT_EQ(items, 1);
}

// Dropped items in saves: kinds by the inventory's names, counts in [1, 999], a position;
// anything else is refused with its position.
TEST(Saves, DroppedItemsAreCheckedLikeEverythingElse) {
    const std::string head = "{\"lantern_save\": 1, \"world\": {\"kind\": \"caves\"}, \"player\": [1, 2], \"entities\": [";
    auto good = parse_save(head + "{\"item\": {\"kind\": \"lamp_post\", \"position\": [4.5, 6]}}]}", "t.json");
    ASSERT_TRUE(good) << good.error().message;
    ASSERT_EQ(good->entities.size(), 1u);
    ASSERT_TRUE(good->entities[0].item);
    EXPECT_EQ(good->entities[0].item->item, Item::lamp_post);
    EXPECT_EQ(good->entities[0].item->count, 1);
    const std::pair<const char*, const char*> bad[] = {
        {"{\"item\": {\"kind\": \"sword\", \"position\": [0, 0]}}", "entities[0].item.kind"},
        {"{\"item\": {\"kind\": \"wall\", \"count\": 0, \"position\": [0, 0]}}", "entities[0].item.count: must be an integer in [1, 999], got 0"},
        {"{\"item\": {\"kind\": \"wall\", \"count\": 1000, \"position\": [0, 0]}}", "entities[0].item.count"},
        {"{\"item\": {\"kind\": \"wall\"}}", "entities[0].item.position"},
        {"{\"item\": {\"kind\": \"wall\", \"position\": [0, 0], \"age\": 1}}", "age"},
        {"{\"item\": [1]}", "entities[0].item"},
    };
    for (const auto& [entity, expect] : bad) {
        auto r = parse_save(head + entity + "]}", "t.json");
        ASSERT_FALSE(r) << entity;
        EXPECT_NE(r.error().message.find("t.json:1:"), std::string::npos) << r.error().message;
        EXPECT_NE(r.error().message.find(expect), std::string::npos) << r.error().message;
    }
}

// Seed 004's anchor override in the game: a tree samples the baked light's probes at its base
// (its crown sways and overhangs), wherever it comes from: the world's setup, the player's
// placing it, a save. Saves carry the anchor, checked like everything else.
TEST(Saves, ATreesProbeAnchorIsItsBaseAndSavesKeepIt) {
    const glm::vec2 at{12.5f, 7.5f};
    ASSERT_TRUE(prop_parts(PropKind::tree, at).anchor);
    EXPECT_EQ(prop_parts(PropKind::tree, at).anchor->position, at);
    EXPECT_FALSE(prop_parts(PropKind::lamp_post, at).anchor);
    EXPECT_FALSE(prop_parts(PropKind::crystal, at).anchor);
    ecs::World world;
    const ecs::Entity tree = spawn_prop(world, PropKind::tree, at, default_tables());
    ASSERT_NE(world.try_get<ProbeAnchor>(tree), nullptr);
    EXPECT_EQ(world.get<ProbeAnchor>(tree).position, at);

    const std::string head = "{\"lantern_save\": 1, \"world\": {\"kind\": \"caves\"}, \"player\": [1, 2], \"entities\": [";
    auto good = parse_save(head + "{\"prop\": {\"kind\": \"tree\", \"position\": [4.5, 6]}, \"probe_anchor\": [4.5, 6.25]}]}", "t.json");
    ASSERT_TRUE(good) << good.error().message;
    ASSERT_TRUE(good->entities[0].probe_anchor);
    EXPECT_EQ(good->entities[0].probe_anchor->position, glm::vec2(4.5f, 6.25f));
    auto again = parse_save(format_save(*good), "t.json");
    ASSERT_TRUE(again) << again.error().message;
    ASSERT_TRUE(again->entities[0].probe_anchor);
    EXPECT_EQ(again->entities[0].probe_anchor->position, glm::vec2(4.5f, 6.25f));
    // Applied to a world, the entity gets its anchor back.
    ecs::World fresh;
    fresh.set_resource<DayCycle>();
    apply_save(*again, fresh, ecs::Entity{});
    int anchored = 0;
    fresh.view<Prop, ProbeAnchor>().each([&](const Prop& p, const ProbeAnchor& a) {
        ++anchored;
        EXPECT_EQ(p.kind, PropKind::tree);
        EXPECT_EQ(a.position, glm::vec2(4.5f, 6.25f));
    });
    EXPECT_EQ(anchored, 1);
    for (const char* bad : {"\"probe_anchor\": [1]", "\"probe_anchor\": \"base\"", "\"probe_anchor\": [1e30, 0]"}) {
        auto r = parse_save(head + "{\"prop\": {\"kind\": \"tree\", \"position\": [4.5, 6]}, " + bad + "}]}", "t.json");
        ASSERT_FALSE(r) << bad;
        EXPECT_NE(r.error().message.find("t.json:1:"), std::string::npos) << r.error().message;
        EXPECT_NE(r.error().message.find("entities[0].probe_anchor"), std::string::npos) << r.error().message;
    }
}

// The inventory in saves: a save without one (written before it existed) gives a new game's;
// counts outside [0, 999] and unknown items are refused with their position.
TEST(Saves, InventoryDefaultsAndBadCountsAreRefused) {
    const std::string head = "{\"lantern_save\": 1, \"world\": {\"kind\": \"caves\"}, \"player\": [1, 2]";
    auto old = parse_save(head + "}", "t.json");
    ASSERT_TRUE(old) << old.error().message;
    EXPECT_EQ(old->inventory, Inventory{});
    auto some = parse_save(head + ", \"inventory\": {\"wall\": 5, \"tree\": 0}}", "t.json");
    ASSERT_TRUE(some) << some.error().message;
    EXPECT_EQ(some->inventory.counts, (std::array<int, item_count>{5, 8, 4, 2, 0})); // the rest a new game's
    auto negative = parse_save(head + ", \"inventory\": {\"torch\": -1}}", "t.json");
    ASSERT_FALSE(negative);
    EXPECT_NE(negative.error().message.find("t.json:1:90: inventory.torch: must be an integer in [0, 999], got -1"), std::string::npos) << negative.error().message;
    auto huge = parse_save(head + ", \"inventory\": {\"wall\": 1000}}", "t.json");
    ASSERT_FALSE(huge);
    EXPECT_NE(huge.error().message.find("inventory.wall"), std::string::npos) << huge.error().message;
    auto unknown = parse_save(head + ", \"inventory\": {\"sword\": 1}}", "t.json");
    ASSERT_FALSE(unknown);
    EXPECT_NE(unknown.error().message.find("sword"), std::string::npos) << unknown.error().message;
}

TEST(Saves, MalformedSavesAreRejectedWithPositions) {
    struct Case {
        const char* text;
        const char* expect;
    };
    const Case cases[] = {
        {"{\"lantern_save\": 1, \"world\": {\"kind\": \"caves\"}, \"player\": [1]}", "t.json:1:59: player: expected an array of 2 numbers"},
        {"{\"lantern_save\": 2, \"world\": {\"kind\": \"caves\"}, \"player\": [1, 2]}", "t.json:1:18: lantern_save: save format 2 is not supported"},
        {"{\"lantern_save\": 1, \"world\": {\"kind\": \"moon\"}, \"player\": [1, 2]}", "world.kind: expected one of \"caves\", \"map\", \"scene\""},
        {"{\"lantern_save\": 1, \"world\": {\"kind\": \"map\"}, \"player\": [1, 2]}", "world.path: a map world needs its file"},
        {"{\"lantern_save\": 1, \"world\": {\"kind\": \"caves\"}, \"player\": [1, 2], \"bogus\": 1}", "t.json:1:67: bogus: unknown key 'bogus' in the save"},
        {"{\"lantern_save\": 1, \"world\": {\"kind\": \"caves\"}, \"player\": [1, 2],\n \"entities\": [{\"torch\": {}}]}",
         "t.json:2:25: entities[0].torch: a torch needs a point_light"},
        {"{\"lantern_save\": 1, \"world\": {\"kind\": \"caves\"}, \"player\": [1, 2],\n \"entities\": [{\"point_light\": {\"position\": [0, 0], \"radius\": -1}}]}",
         "entities[0].point_light.radius: must be > 0"},
        {"{\"lantern_save\": 1, \"world\": {\"kind\": \"caves\"}, \"player\": [1, 2], \"edits\": [{\"chunk\": [0, 0], \"rows\": [\"#\"]}]}",
         "edits[0].rows: expected an array of 32 strings"},
        {"{\"lantern_save\": 1, \"world\": {\"kind\": \"caves\"}, \"player\": [1, 2],", "t.json:1:"},
        {"{\"lantern_save\": 1, \"world\": {\"kind\": \"caves\"}, \"player\": [1, 2], \"baked\": [{\"chunk\": [0, 0], \"key\": \"12G4\"}]}",
         "baked[0].key: expected 16 lowercase hexadecimal digits"},
    };
    for (const Case& c : cases) {
        auto r = parse_save(c.text, "t.json");
        ASSERT_FALSE(r) << c.text;
        EXPECT_NE(r.error().message.find(c.expect), std::string::npos) << r.error().message;
    }
    // A bad character in a row is reported at its column.
    std::string rows = "[";
    for (int i = 0; i < 32; ++i) rows += std::string(i ? "," : "") + "\"" + std::string(i == 3 ? "..!" : "...") + std::string(29, '.') + "\"";
    rows += "]";
    auto r = parse_save("{\"lantern_save\": 1, \"world\": {\"kind\": \"caves\"}, \"player\": [1, 2], \"edits\": [{\"chunk\": [0, 0], \"rows\": " + rows + "}]}", "t.json");
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("edits[0].rows[3]: expected '#' (wall), '.' (floor) or a..z"), std::string::npos)
        << r.error().message;
}

// Game extensions' data (extension.hpp): written by their save hooks under "extensions",
// read back exactly, handed to their load hooks with positions for their messages; entities
// they own stay out of the game's own list; data for an unknown extension is set aside.
TEST(Saves, ExtensionDataRoundTripsAndItsProblemsHavePositions) {
    struct Glow {
        float level = 0.0f;
    };
    struct Counter {
        int value = 0;
    };
    GameExtension ext;
    ext.name = "glow";
    ext.setup = [](ecs::World& w) { w.set_resource<Counter>(); };
    ext.save = [](ecs::World& w, json::Writer& out) {
        out.begin_object().field("counter", w.resource<Counter>().value).key("levels").begin_array();
        w.view<Glow>().each([&](const Glow& g) { out.value(g.level); });
        out.end().end();
    };
    ext.load = [](ecs::World& w, const json::Value& v, scene::reading::Reader& r, const std::string& path) {
        int counter = 0;
        std::vector<float> levels;
        scene::reading::Fields f(r, v, path, {"counter", "levels"});
        f.required("counter", counter, scene::reading::IntRange{0, 100});
        if (const json::Value* l = f.find_required("levels"); l && r.expect(*l, path + ".levels", json::Type::array))
            for (std::size_t i = 0; i < l->as_array().size(); ++i) {
                float level = 0.0f;
                r.read(l->as_array()[i], scene::reading::index_path(path + ".levels", i), level,
                       scene::reading::between(0.0, 1.0));
                levels.push_back(level);
            }
        if (!r.ok()) return;
        w.resource<Counter>().value = counter;
        for (float level : levels) {
            const ecs::Entity e = w.create();
            w.emplace<Glow>(e, Glow{level});
            w.emplace<EmissiveLight>(e);
            w.emplace<ExtensionOwned>(e);
        }
    };
    const std::vector<GameExtension> exts{ext};
    ASSERT_TRUE(check_extensions(exts));

    jobs::JobSystem jobs(no_workers());
    ecs::World world;
    world.set_resource<DayCycle>();
    auto w = create_world({WorldKind::caves, "", 11}, world, {});
    ASSERT_TRUE(w);
    ext.setup(world);
    world.resource<Counter>().value = 7;
    systems::Streaming streaming(w->source);
    const std::size_t game_entities = capture_save(world, streaming, w->spec).entities.size();
    for (float level : {0.25f, 0.5f}) {
        const ecs::Entity e = world.create();
        world.emplace<Glow>(e, Glow{level});
        world.emplace<EmissiveLight>(e);
        world.emplace<ExtensionOwned>(e);
    }
    SaveState saved = capture_save(world, streaming, w->spec);
    EXPECT_EQ(saved.entities.size(), game_entities) << "an extension's entity in the game's list";
    saved.extensions = capture_extensions(exts, world);
    ASSERT_EQ(saved.extensions.size(), 1u);
    const std::string text = format_save(saved);
    EXPECT_NE(text.find("\"extensions\": {\n    \"glow\": {\"counter\": 7, \"levels\": [0.25, 0.5]}"), std::string::npos) << text;
    auto loaded = parse_save(text, "s.json");
    ASSERT_TRUE(loaded) << loaded.error().message;
    EXPECT_EQ(format_save(*loaded), text);
    ecs::World fresh;
    ext.setup(fresh);
    ASSERT_TRUE(load_extensions(exts, loaded->extensions, fresh, "s.json"));
    EXPECT_EQ(fresh.resource<Counter>().value, 7);
    std::vector<float> levels;
    fresh.view<Glow>().each([&](const Glow& g) { levels.push_back(g.level); });
    std::sort(levels.begin(), levels.end());
    EXPECT_EQ(levels, (std::vector<float>{0.25f, 0.5f}));

    // A problem inside the extension's data: the save's file, line, column and path.
    const std::string head = "{\"lantern_save\": 1, \"world\": {\"kind\": \"caves\"}, \"player\": [1, 2],\n";
    auto bad = parse_save(head + " \"extensions\": {\"glow\": {\"counter\": 3, \"levels\": [0.5, 2]}}}", "t.json");
    ASSERT_TRUE(bad) << bad.error().message; // the game reads only its own part
    ecs::World scratch;
    ext.setup(scratch);
    auto refused = load_extensions(exts, bad->extensions, scratch, "t.json");
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().message.rfind("t.json:2:56: extensions.glow.levels[1]: must be in [0, 1], got 2", 0), 0u)
        << refused.error().message;
    EXPECT_EQ(refused.error().exit_code, 2);
    EXPECT_EQ(scratch.resource<Counter>().value, 0); // nothing applied
    // Not an object: the game's own reader refuses it.
    auto not_object = parse_save(head + " \"extensions\": [1]}", "t.json");
    ASSERT_FALSE(not_object);
    EXPECT_NE(not_object.error().message.find("t.json:2:16: extensions: expected an object"), std::string::npos)
        << not_object.error().message;
    // Data for an extension this game lacks: set aside and named.
    auto other = parse_save(head + " \"extensions\": {\"fireflies\": {\"flies\": []}}}", "t.json");
    ASSERT_TRUE(other);
    std::vector<std::string> ignored;
    ASSERT_TRUE(load_extensions(exts, other->extensions, scratch, "t.json", &ignored));
    EXPECT_EQ(ignored, (std::vector<std::string>{"fireflies"}));

    // Malformed extension lists are a programmer's error, refused before the game starts.
    GameExtension unnamed = ext;
    unnamed.name = "Glow!";
    EXPECT_FALSE(check_extensions({unnamed}));
    EXPECT_FALSE(check_extensions({ext, ext}));
    GameExtension half = ext;
    half.load = nullptr;
    EXPECT_FALSE(check_extensions({half}));
}

// A save whose world file is gone (or is not a file) names the save and the key, on one
// line, before the game makes the world.
TEST(Saves, AMissingWorldFileNamesTheSaveAndTheKey) {
    test::TempDir dir;
    const std::string save = dir.file("s.json");
    ASSERT_TRUE(write_file_atomic(save, std::string("{\"lantern_save\": 1, \"world\": {\"kind\": \"map\", \"path\": \"") +
                                            dir.file("gone.map") + "\"}, \"player\": [1, 2]}"));
    auto r = read_save(save);
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().exit_code, 2);
    EXPECT_EQ(r.error().message.rfind(save + ": world.path: " + dir.file("gone.map") + ": cannot open", 0), 0u)
        << r.error().message;
    ASSERT_TRUE(write_file_atomic(save, std::string("{\"lantern_save\": 1, \"world\": {\"kind\": \"scene\", \"path\": \"") +
                                            dir.path().string() + "\\u0001\"}, \"player\": [1, 2]}"));
    auto control = read_save(save);
    ASSERT_FALSE(control);
    EXPECT_NE(control.error().message.find("world.path: "), std::string::npos) << control.error().message;
    EXPECT_NE(control.error().message.find("\\x01"), std::string::npos) << control.error().message;
}

TEST(Saves, KillDuringSaveLeavesThePreviousSaveLoadable) {
    // A large save (many edited chunks) written over and over by a child process that is
    // killed at random moments: the file must always read back as one whole save.
    SaveState a;
    a.world = {WorldKind::caves, "", 5};
    a.player = {1.5f, 2.5f};
    std::mt19937 rng(42);
    for (int i = 0; i < 400; ++i) {
        systems::Streaming::EditedChunk c{{i % 20, i / 20}, std::vector<std::uint8_t>(32 * 32)};
        for (auto& cell : c.cells) cell = std::uint8_t(rng() & 1);
        a.edits.push_back(std::move(c));
    }
    SaveState b = a;
    b.player = {9.5f, 9.5f};
    for (auto& c : b.edits) c.cells[0] ^= 1;
    const std::string text_a = format_save(a), text_b = format_save(b);
    ASSERT_GT(text_a.size(), 400000u);
    test::TempDir dir;
    const std::string path = dir.file("world.save.json");
    ASSERT_TRUE(write_save(path, a));
    // Kills are aimed inside a save, by conditions only (no sleeps, so a busy machine changes
    // nothing): the child reports each finished save through a pipe; on odd rounds the parent
    // first waits for two more finished saves (both texts on disk in turn). Then it waits
    // until the child has opened a new temporary file (a save is under way), stops the child
    // (SIGSTOP freezes it where it is), checks that the temporary file is still there (else the
    // save finished in between: continue the child and wait for the next one) and kills it.
    const auto temporaries = [&] {
        int n = 0;
        for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
            n += entry.path().filename().string().rfind(".world.save.json.tmp", 0) == 0;
        return n;
    };
    int torn = 0;
    for (int round = 0; round < 12; ++round) {
        int saves[2];
        ASSERT_EQ(pipe(saves), 0);
        const pid_t child = fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            close(saves[0]);
            for (int i = 0;; ++i) {
                if (!write_save(path, i % 2 ? a : b)) _exit(3);
                const char done = 1;
                if (write(saves[1], &done, 1) != 1) _exit(4);
            }
        }
        close(saves[1]);
        for (int finished = 0; round % 2 && finished < 2; ++finished) {
            char done = 0;
            ASSERT_EQ(read(saves[0], &done, 1), 1) << "the saving child stopped by itself";
        }
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
        bool inside = false;
        while (!inside && std::chrono::steady_clock::now() < deadline) {
            const int before = temporaries();
            while (temporaries() == before && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
            ASSERT_EQ(kill(child, SIGSTOP), 0);
            int stopped = 0;
            ASSERT_EQ(waitpid(child, &stopped, WUNTRACED), child);
            ASSERT_TRUE(WIFSTOPPED(stopped)) << "the saving child stopped by itself";
            inside = temporaries() > before;
            if (!inside) {
                ASSERT_EQ(kill(child, SIGCONT), 0);
            }
        }
        kill(child, SIGKILL);
        int status = 0;
        waitpid(child, &status, 0);
        close(saves[0]);
        ASSERT_TRUE(WIFSIGNALED(status)) << "the saving child stopped by itself";
        EXPECT_TRUE(inside) << "round " << round << ": no kill landed inside a save within 5 minutes";
        const std::string on_disk = test::read_file(path);
        if (on_disk != text_a && on_disk != text_b) ++torn;
        auto loaded = read_save(path);
        ASSERT_TRUE(loaded) << loaded.error().message;
        EXPECT_EQ(loaded->edits.size(), a.edits.size());
    }
    EXPECT_EQ(torn, 0);
}

// ---- baked light (docs/baked.md, "In the game")

namespace {

// The caves with their veins, the GI frame on the C++ reference and the baker: what the
// headless game runs, without a GPU. Quick bake settings (the game's are finer).
struct BakedCaves {
    jobs::JobSystem jobs{no_workers()};
    ecs::World world;
    std::unique_ptr<WorldBaker> baker;
    std::unique_ptr<systems::GiFrame> frame;

    // sun_keys: the sun mixed, its bounce baked at the day's keys (the game's --bake-sun-keys).
    explicit BakedCaves(const std::string& cache_dir, int sun_keys = 0) {
        WorldOptions wo;
        wo.gi = default_game_gi();
        auto created = create_world(WorldSpec{}, world, wo);
        EXPECT_TRUE(created.ok());
        world.set_resource<BakedChunks>();
        world.set_resource<BakeStatus>();
        if (sun_keys > 0)
            world.view<Sun, DirectionalLight>().each(
                [&](ecs::Entity e, const Sun&, const DirectionalLight&) { world.patch<DirectionalLight>(e).mode = scene::LightMode::mixed; });
        BakerOptions bo;
        bo.cache_dir = cache_dir;
        bo.settings = {.resolution = 1, .margin = 2, .rays = 8, .face_rays = 8};
        bo.settings.sun_keys = sun_keys;
        bo.reach = 8;
        baker = std::make_unique<WorldBaker>(bo);
        systems::GiFrameOptions fo;
        fo.add_game_systems = [this](ecs::Schedule& s) { add_bake_system(s, *baker); };
        frame = std::make_unique<systems::GiFrame>(world, jobs, created->source, gi::make_reference_backend(nullptr),
                                                   created->config, std::move(fo));
        frame->warm_up();
        baker->finish(world);
    }
    ~BakedCaves() {
        frame.reset();
        baker.reset();
    }
    const BakeStatus& status() { return world.resource<BakeStatus>(); }
};

} // namespace

TEST(Baking, CavesHaveLavaAndCrystalVeinsWhereRockMeetsTheOpen) {
    const scene::CaveParams p{1, 0.47f, true};
    int lava = 0, crystal = 0;
    for (int z = -64; z < 64; ++z)
        for (int x = -64; x < 64; ++x) {
            const std::uint8_t c = scene::cave_cell(x, z, p);
            EXPECT_EQ(c != 0, scene::cave_wall(x, z, p));
            if (c < scene::first_material_cell) continue;
            lava += c == scene::material_cell(scene::cave_lava);
            crystal += c == scene::material_cell(scene::cave_crystal);
            const bool open_beside = !scene::cave_wall(x + 1, z, p) || !scene::cave_wall(x - 1, z, p) ||
                                     !scene::cave_wall(x, z + 1, p) || !scene::cave_wall(x, z - 1, p);
            EXPECT_TRUE(open_beside) << "a vein shows: " << x << ", " << z;
        }
    std::printf("128 x 128 tiles: %d lava, %d crystal\n", lava, crystal);
    EXPECT_GT(lava, 20);
    EXPECT_GT(crystal, 20);
    EXPECT_EQ(scene::cave_cell(3, 4, {1, 0.47f, false}), scene::cave_wall(3, 4, {1, 0.47f, false}) ? 1 : 0);
    ASSERT_EQ(scene::cave_materials().size(), 2u);
    EXPECT_GT(scene::cave_materials()[scene::cave_lava].emission.r, 0.0f);
}

// The resident chunks bake in the background (their veins and crystals), the frame gets the
// baked light, a second start reads every chunk from the cache, and a wall mined re-bakes
// only the chunks whose bake sees it.
TEST(Baking, ChunksBakeReuseTheirCacheAndAnEditRebakesOnlyWhatItReaches) {
    test::TempDir dir;
    std::uint64_t chunks = 0;
    {
        BakedCaves game(dir.path().string());
        const BakeStatus& s = game.status();
        chunks = std::uint64_t(s.chunks);
        EXPECT_GT(s.chunks, 3);
        EXPECT_EQ(s.baked, chunks);
        EXPECT_EQ(s.reused, 0u);
        EXPECT_EQ(s.pending, 0);
        EXPECT_EQ(s.published, 1u);
        const auto& light = game.world.resource<systems::BakedGi>().light;
        ASSERT_TRUE(light);
        // Some chunk holds light (the veins glow, the crystals shine).
        bool lit = false;
        for (const auto& [k, b] : game.world.resource<BakedChunks>().chunks) lit |= !b->empty;
        EXPECT_TRUE(lit);
        // A save carries the baked chunks' cache keys, and reads them back.
        const SaveState saved = capture_save(game.world, game.frame->streaming(), WorldSpec{});
        ASSERT_EQ(saved.baked.size(), chunks);
        auto read = parse_save(format_save(saved), "s.json");
        ASSERT_TRUE(read.ok()) << read.error().message;
        EXPECT_EQ(read->baked, saved.baked);
        // Mine a wall well inside chunk (0, 0)... and one on a chunk corner.
        systems::Streaming& streaming = game.frame->streaming();
        auto mine_near = [&](glm::ivec2 from) {
            for (int r = 0; r < 16; ++r)
                for (int dz = -r; dz <= r; ++dz)
                    for (int dx = -r; dx <= r; ++dx)
                        if (streaming.is_wall(from + glm::ivec2(dx, dz))) {
                            streaming.set_wall(game.world, from + glm::ivec2(dx, dz), false);
                            return from + glm::ivec2(dx, dz);
                        }
            return from;
        };
        // A chunk's bake sees its walls and margin + reach (2 + 8) tiles around it.
        auto reaching = [&](glm::ivec2 t) {
            std::uint64_t n = 0;
            for (const auto& [k, b] : game.world.resource<BakedChunks>().chunks) {
                const glm::ivec2 lo = glm::ivec2(b->id.x, b->id.z) * 32 - 10, hi = lo + 32 + 20;
                n += t.x >= lo.x && t.y >= lo.y && t.x < hi.x && t.y < hi.y;
            }
            return n;
        };
        const glm::ivec2 inner = mine_near({16, 16});
        const std::uint64_t expected = reaching(inner);
        EXPECT_GE(expected, 1u);
        game.baker->finish(game.world);
        EXPECT_EQ(s.baked, chunks + expected) << "one edit at " << inner.x << ", " << inner.y;
        EXPECT_EQ(s.published, 2u);
    }
    BakedCaves again(dir.path().string());
    EXPECT_EQ(again.status().reused + again.status().baked, chunks);
    EXPECT_GE(again.status().reused, chunks - 4) << "the chunks the edit reached are stale (the walls are new again)";
}

// Seed 004's moving sun in the game (--bake-sun-keys): the mixed sun's bounce is baked at the
// day's keys in every chunk; the day cycle moving it bakes nothing again; the probes and the
// frame's baked light follow it.
TEST(Baking, TheMovingSunIsBakedAtTheDaysKeysAndMovesWithoutABake) {
    test::TempDir dir;
    BakedCaves game(dir.path().string(), 3);
    const BakeStatus& s = game.status();
    ASSERT_GT(s.chunks, 3);
    int keyed = 0;
    for (const auto& [k, b] : game.world.resource<BakedChunks>().chunks) {
        ASSERT_FALSE(b->empty) << "the sun reaches every chunk";
        EXPECT_EQ(b->sun_keys.size(), 3u);
        keyed += b->sun_keys.size() == 3u;
    }
    EXPECT_EQ(keyed, s.chunks);
    const auto& light = game.world.resource<systems::BakedGi>().light;
    ASSERT_TRUE(light);
    EXPECT_EQ(light->sun_keys, 3);
    const std::uint64_t baked = s.baked, published = s.published;
    // Noon, then late afternoon: nothing is baked again, and the probes change with the sun.
    auto sun_at = [&](float t) {
        game.world.view<Sun, DirectionalLight>().each([&](ecs::Entity e, const Sun&, const DirectionalLight&) {
            DirectionalLight& d = game.world.patch<DirectionalLight>(e);
            d.direction = sun_direction(t);
            d.color = sun_light(t);
            d.intensity = 1.0f;
        });
        game.baker->finish(game.world);
        return game.world.resource<BakedChunks>().sun;
    };
    const gi::BakedSun noon = sun_at(0.5f);
    EXPECT_NEAR(float(noon.key) + noon.blend, 1.0f, 1e-4f) << "noon is the middle key of three";
    glm::vec2 open(0.0f);
    const systems::Streaming& streaming = game.frame->streaming();
    for (int r = 0; r < 32 && open == glm::vec2(0.0f); ++r)
        for (int x = -r; x <= r; ++x)
            if (!streaming.is_wall({16 + x, 16 + r})) {
                open = glm::vec2(16 + x, 16 + r) + 0.5f;
                break;
            }
    const glm::vec3 at_noon = game.world.resource<BakedChunks>().probes_at(open).fluence();
    const gi::BakedSun later = sun_at(0.65f);
    EXPECT_EQ(later.key, 1);
    const glm::vec3 at_later = game.world.resource<BakedChunks>().probes_at(open).fluence();
    EXPECT_EQ(s.baked, baked) << "a moving sun bakes nothing again";
    EXPECT_EQ(s.published, published);
    EXPECT_NE(at_noon, at_later) << "the probes follow the sun (" << open.x << ", " << open.y << ")";
}

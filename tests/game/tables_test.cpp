// The game's tables (lantern/game/tables.hpp): the file's format, its errors, and the tables
// applied to a running world (what --watch does when the file changes).
#include "lantern/game/tables.hpp"

#include "lantern/game/gameplay.hpp"
#include "lantern/game/world_setup.hpp"
#include "lantern/scene/procedural.hpp"

#include <gtest/gtest.h>

#include <string>

namespace {

using namespace lantern;
using namespace lantern::game;

TEST(Tables, TheDefaultsAreTheGamesOwnAndReadBackExactly) {
    const GameTables& d = default_tables();
    EXPECT_EQ(d.materials, scene::cave_materials());
    // What the game placed before there were tables: a torch, a crystal, a lamp post, the player.
    const TorchParts torch = torch_parts({1.5f, 2.5f}, 0.3f);
    EXPECT_EQ(torch.light.color, glm::vec3(1.0f, 0.62f, 0.28f));
    EXPECT_EQ(torch.light.radius, 6.5f);
    EXPECT_EQ(torch.light.height, 1.2f);
    EXPECT_EQ(torch.torch.base_intensity, 1.0f);
    EXPECT_EQ(prop_parts(PropKind::lamp_post, {0.5f, 0.5f}).light->position, glm::vec2(0.5f, 0.9f));
    auto back = parse_tables(format_tables(d), "t.json");
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_EQ(*back, d);
    auto empty = parse_tables(R"({"lantern_tables": 1})", "t.json");
    ASSERT_TRUE(empty.ok());
    EXPECT_EQ(*empty, d) << "every key is optional";
}

TEST(Tables, AFileTunesWhatItNamesAndNothingElse) {
    auto t = parse_tables(R"({"lantern_tables": 1,
  "materials": {"lava": {"emission": [1.5, 0.4, 0.05]}},
  "lights": {"torch": {"color": [0.4, 0.6, 1], "radius": 9}, "crystal": {"intensity": 2}}})",
                          "t.json");
    ASSERT_TRUE(t.ok()) << t.error().message;
    const GameTables& d = default_tables();
    EXPECT_EQ(t->materials[scene::cave_lava].emission, glm::vec3(1.5f, 0.4f, 0.05f));
    EXPECT_EQ(t->materials[scene::cave_lava].albedo, d.materials[scene::cave_lava].albedo);
    EXPECT_EQ(t->materials[scene::cave_crystal], d.materials[scene::cave_crystal]);
    EXPECT_EQ(t->torch.color, glm::vec3(0.4f, 0.6f, 1.0f));
    EXPECT_EQ(t->torch.radius, 9.0f);
    EXPECT_EQ(t->torch.intensity, d.torch.intensity);
    EXPECT_EQ(t->crystal.intensity, 2.0f);
    EXPECT_EQ(t->lamp_post, d.lamp_post);
    EXPECT_EQ(t->player, d.player);
}

TEST(Tables, MalformedFilesAreRefusedWithPositions) {
    struct Case {
        const char* text;
        const char* message;
    };
    const Case cases[] = {
        {R"({"lights": {}})", "t.json:1:1: lantern_tables: required key is missing"},
        {R"({"lantern_tables": 2})", "t.json:1:20: lantern_tables: tables format 2 is not supported"},
        {R"({"lantern_tables": 1, "materials": {"sand": {}}})", "t.json:1:37: materials.sand: unknown material \"sand\" (the caves have lava, crystal)"},
        {R"({"lantern_tables": 1, "materials": {"lava": {"albedo": [2, 0, 0]}}})", "t.json:1:57: materials.lava.albedo[0]"},
        {R"({"lantern_tables": 1, "lights": {"lantern": {}}})", "t.json:1:34: lights.lantern: unknown key"},
        {R"({"lantern_tables": 1, "lights": {"crystal": {"height": 1}}})", "t.json:1:46: lights.crystal.height: unknown key"},
        {R"({"lantern_tables": 1, "lights": {"torch": {"radius": 0}}})", "t.json:1:54: lights.torch.radius"},
        {R"({"lantern_tables": 1, "lights": {"torch": {"color": [1, 1]}}})", "t.json:1:53: lights.torch.color"},
        {R"({"lantern_tables": 1,)", "t.json:1:"},
        {R"({"lantern_tables": 1, "materials": {"lava": {"pulse": 1}}})", "t.json:1:55: materials.lava.pulse: every pulsing material pulses at one frequency (the bake keeps one pulsing part); \"crystal\" pulses at 0.2 Hz"},
        {R"({"lantern_tables": 1, "materials": {"crystal": {"pulse": -1}}})", "t.json:1:58: materials.crystal.pulse: must be in [0, 60], got -1"},
    };
    for (const Case& c : cases) {
        auto t = parse_tables(c.text, "t.json");
        ASSERT_FALSE(t.ok()) << c.text;
        EXPECT_EQ(t.error().exit_code, 2);
        EXPECT_EQ(t.error().message.rfind(c.message, 0), 0u) << c.text << "\n" << t.error().message;
    }
    EXPECT_FALSE(read_tables("/nonexistent/lantern-tables.json").ok());
}

TEST(Tables, AppliedToARunningWorldTheyRelightWhatTheGamePlaced) {
    ecs::World world;
    world.set_resource<systems::GiConfig>();
    WorldOptions wo;
    auto created = create_world({WorldKind::caves, "", 3}, world, wo);
    ASSERT_TRUE(created.ok()) << created.error().message;
    world.resource<systems::GiConfig>() = created->config;
    const glm::vec2 at = created->spawn;
    spawn_torch(world, at + glm::vec2(1.0f, 0.0f), 0.0f);
    spawn_prop(world, PropKind::crystal, at + glm::vec2(2.0f, 0.0f)); // the tables' colour
    const ecs::Entity hued = spawn_prop(world, PropKind::crystal, at + glm::vec2(3.0f, 0.0f));
    world.get<EmissiveLight>(hued).color = {0.85f, 0.4f, 1.0f}; // one of the caves' own hues
    spawn_prop(world, PropKind::lamp_post, at + glm::vec2(0.0f, 2.0f));

    GameTables t = default_tables();
    t.torch = {{0.2f, 0.4f, 1.0f}, 1.5f, 8.0f, 1.4f};
    t.crystal = {{1.0f, 0.2f, 0.2f}, 1.7f, 5.0f, 0.0f};
    t.lamp_post = {{0.9f, 1.0f, 0.9f}, 1.1f, 9.0f, 2.0f};
    t.player = {{1.0f, 1.0f, 1.0f}, 0.5f, 5.0f, 1.1f};
    t.materials[scene::cave_lava].emission = {2.0f, 0.5f, 0.1f};
    const ecs::Tick before = world.tick();
    world.advance_tick();
    apply_tables(world, t, true);
    EXPECT_EQ(world.resource<GameTables>(), t);
    EXPECT_EQ(world.resource<systems::GiConfig>().materials, t.materials);
    int torches = 0, crystals = 0, lamps = 0;
    world.view<Torch, PointLight>().each([&](const Torch& torch, const PointLight& p) {
        ++torches;
        EXPECT_EQ(p.color, t.torch.color);
        EXPECT_EQ(p.radius, t.torch.radius);
        EXPECT_EQ(p.height, t.torch.height);
        EXPECT_EQ(torch.base_intensity, t.torch.intensity);
    });
    world.view<Player, PointLight>().each([&](const Player&, const PointLight& p) {
        EXPECT_EQ(p.color, t.player.color);
        EXPECT_EQ(p.intensity, t.player.intensity);
    });
    world.view<Prop>().each([&](ecs::Entity e, const Prop& prop) {
        if (prop.kind == PropKind::crystal) {
            const EmissiveLight& c = world.get<EmissiveLight>(e);
            ++crystals;
            EXPECT_EQ(c.intensity, t.crystal.intensity);
            EXPECT_EQ(c.radius, t.crystal.radius);
            if (e == hued) {
                EXPECT_EQ(c.color, glm::vec3(0.85f, 0.4f, 1.0f)) << "the caves' own hue stays";
            }
        }
        if (prop.kind == PropKind::lamp_post) {
            ++lamps;
            EXPECT_EQ(world.get<PointLight>(e).color, t.lamp_post.color);
            EXPECT_EQ(world.get<PointLight>(e).radius, t.lamp_post.radius);
        }
    });
    EXPECT_GE(torches, 1);
    EXPECT_GE(crystals, 2);
    EXPECT_GE(lamps, 1);
    int tabled = 0;
    world.view<Prop>().each([&](ecs::Entity e, const Prop& prop) {
        if (prop.kind == PropKind::crystal && world.get<EmissiveLight>(e).color == t.crystal.color) ++tabled;
    });
    EXPECT_GE(tabled, 1) << "a crystal of the old tables' colour takes the new one";
    // Written through patch(): the light gathering, which looks at what changed, sees them.
    EXPECT_GT(world.find_pool<PointLight>()->last_changed(), before);
    EXPECT_GT(world.find_pool<EmissiveLight>()->last_changed(), before);
}

} // namespace

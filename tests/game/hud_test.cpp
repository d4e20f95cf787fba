// The game's screen overlay and draw list without a window or GPU. The timer HUD's layout (issue 19, bug 1): Hud::draw built into a real ImGui context with
// its default font, no window and no GPU, and its draw data read back. Debian's ImGui 1.86
// drew the frame-time graph 1 px wide for PlotLines' "to the right edge" width, and long
// lines pushed the trace button and text past the HUD's right edge; both are checked from
// the vertices ImGui emits and the window's measured content width, for every gi.method's
// settings panel.
#include "app/draw_list.hpp"
#include "app/texel_world.hpp"
#include "app/hud.hpp"
#include "app/menu.hpp"

#include "lantern/game/gameplay.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/jobs/job_system.hpp"
#include "lantern/systems/world_source.hpp"
#include "lantern/gi/passes.hpp"
#include "lantern/profile/profiler.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>
#include <imgui.h>
#include <imgui_internal.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <string>

namespace lantern::game {
namespace {

constexpr ImU32 graph_colour = IM_COL32(255, 0, 255, 255); // a colour nothing else in the HUD uses

struct ImGuiFixture : ::testing::Test {
    void SetUp() override {
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        io.DisplaySize = ImVec2(1280, 720);
        io.DeltaTime = 1.0f / 60.0f;
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h); // builds the default font
        ImGui::StyleColorsDark();
        ImGui::GetStyle().Colors[ImGuiCol_PlotLines] = ImGui::ColorConvertU32ToFloat4(graph_colour);
        ImGui::GetStyle().Colors[ImGuiCol_PlotLinesHovered] = ImGui::ColorConvertU32ToFloat4(graph_colour);

        // A frame history with a varied frame time, as the game's (the graph's line then
        // spans its whole width).
        profile::reset();
        profile::set_enabled(true);
        for (int i = 0; i < 300; ++i) {
            profile::begin_frame();
            profile::record("render", 0, 1'000'000 + (i % 7) * 300'000);
            for (const char* job : {"stream_chunks", "gather_lights", "gather_proxies", "gi_cache_keys", "gi_submit"})
                profile::record(job, 0, 200'000, profile::EventKind::job);
            profile::end_frame();
        }
    }
    void TearDown() override {
        ImGui::DestroyContext();
        profile::reset();
    }

    // Realistic inputs with the HUD's longest lines: every section a player sees open.
    HudActions draw_frame(Hud& hud, scene::GiMethod method) {
        config.settings.method = method;
        config.settings.max_lights = 256;
        config.settings.max_shadow_proxies = 256;
        lights.points.resize(64);
        lights.point_candidates = 1024;
        lights.emissives.resize(4096);
        lights.suns.resize(1);
        proxies.proxies.resize(256);
        report.frame = 12345;
        gi::FrameInputs fi;
        fi.settings = config.settings;
        const gi::PassPlan plan = gi::plan_passes(fi, false);
        report.ran = plan.run;
        for (int p = 0; p < gi::registered_pass_count(); ++p)
            report.reason[std::size_t(p)] = plan.reason[p].empty() ? "" : "not needed: " + std::string(plan.reason[p]);
        report.window = gi::GiWindow{};
        report.window->width = 1024;
        report.window->height = 1024;
        report.window->resolution = 16;

        schedule.systems = {{"stream_chunks", {}, {{"Streaming", true}}, false, {}},
                            {"gather_lights", {{"Light"}, {"Transform"}}, {{"GatheredLights", true}}, false, {}},
                            {"gi_submit", {{"GatheredLights", true}, {"GatheredProxies", true}},
                             {{"FrameReport", true}, {"GiCacheKeys", true}, {"GiHistory", true}, {"BakeStatus", true}},
                             true, {}}};
        schedule.edges = {{0, 1, false, {{"Streaming", true}}, false}, {1, 2, false, {{"GatheredLights", true}}, false}};
        schedule.ambiguities = {{0, 2, {{"GiCacheKeysAndSomeLongerResourceName", true}}}};

        HudInputs in;
        in.schedule = &schedule;
        in.report = &report;
        in.config = &config;
        in.art = &art;
        in.gi_view = &view;
        in.day = &day;
        in.lights = &lights;
        in.proxies = &proxies;
        in.streaming.resident_chunks = 1024;
        in.streaming.loading_chunks = 64;
        in.streaming.edited_chunks_stored = 100000;
        in.entities = 1000000;
        in.world = "world: den312d.map (65x65 tiles), seed 1";
        in.message = "saved to /home/player/.local/share/lantern/saves/slot-3.save (12 chunks, 48 KiB)";
        in.item = "lamp post";
        in.device = "llvmpipe (LLVM 15.0.6, 256 bits)";
        ImGui::NewFrame();
        const HudActions actions = hud.draw(in);
        ImGui::Render();
        return actions;
    }

    systems::GiConfig config;
    ArtSettings art;
    GiDebugView view = GiDebugView::lit;
    DayCycle day;
    systems::GatheredLights lights;
    systems::GatheredProxies proxies;
    systems::FrameReport report;
    ecs::ScheduleInfo schedule;
};

// Opens every collapsing header of the HUD (the closed ones too) from the next frame on.
void open_every_section(ImGuiWindow* w) {
    for (const char* header : {"Systems (this frame, by worker lane)", "CPU percentiles (ms)", "GPU passes (timestamps, ms)",
                               "GI passes this frame", "Lights and proxies", "GI settings (live)", "GI views",
                               "Schedule (systems, access, order)", "Art", "World"})
        w->StateStorage.SetInt(w->GetID(header), 1);
}

// The HUD's own window (the only one Hud::draw opens, besides ImGui's debug window).
ImGuiWindow* hud_window() {
    for (ImGuiWindow* w : ImGui::GetCurrentContext()->Windows)
        if (std::string(w->Name).rfind("Lantern timer HUD", 0) == 0) return w;
    return nullptr;
}

struct Extent {
    float min_x = FLT_MAX, max_x = -FLT_MAX;
    int vertices = 0;
};

Extent graph_extent() {
    Extent e;
    const ImDrawData* data = ImGui::GetDrawData();
    for (int l = 0; l < data->CmdListsCount; ++l)
        for (const ImDrawVert& v : data->CmdLists[l]->VtxBuffer)
            if ((v.col & ~IM_COL32_A_MASK) == (graph_colour & ~IM_COL32_A_MASK) && (v.col & IM_COL32_A_MASK)) {
                e.min_x = std::min(e.min_x, v.pos.x);
                e.max_x = std::max(e.max_x, v.pos.x);
                ++e.vertices;
            }
    return e;
}

TEST_F(ImGuiFixture, FrameTimeGraphSpansTheHudAndNothingOverflowsItsRightEdge) {
    for (const scene::GiMethod method : {scene::GiMethod::heat, scene::GiMethod::radiosity, scene::GiMethod::gather}) {
        SCOPED_TRACE(std::string("gi.method ") + gi::method(method).name.data());
        Hud hud;
        // The content size ImGui measures is the previous frame's: draw a few.
        draw_frame(hud, method);
        ImGuiWindow* w = hud_window();
        ASSERT_NE(w, nullptr);
        open_every_section(w);
        for (int frame = 0; frame < 3; ++frame) draw_frame(hud, method);
        ASSERT_EQ(w, hud_window());
        const float inner = w->ContentRegionRect.GetWidth();
        ASSERT_GT(inner, 300.0f) << "the HUD's default size is 470 px";

        // Bug 1: the graph was a 1-pixel column.
        const Extent g = graph_extent();
        EXPECT_GT(g.vertices, 100) << "no frame-time graph drawn";
        EXPECT_GE(g.max_x - g.min_x, 0.9f * inner) << "the frame-time graph is " << g.max_x - g.min_x
                                                   << " px wide in a " << inner << " px HUD";
        EXPECT_GE(g.min_x, w->Pos.x);
        EXPECT_LE(g.max_x, w->Pos.x + w->Size.x);

        // Every item (the trace button, the percentile line, the counts, each settings row)
        // fits the HUD's width: ImGui's measured content width is the widest item's right edge.
        EXPECT_LE(w->ContentSize.x, inner + 0.5f) << "an item reaches " << w->ContentSize.x - inner
                                                   << " px past the HUD's right edge";
    }
}

// The hotbar (issue 19: the selected item and the counts on screen, no HUD needed): bottom
// centre, whole on the display, one slot per item.
TEST_F(ImGuiFixture, HotbarSitsWholeAtTheBottomCentre) {
    Inventory inventory;
    inventory.counts = {12, 0, 4, 999, 1};
    for (int frame = 0; frame < 3; ++frame) { // auto-resized windows take their size on the next frames
        ImGui::NewFrame();
        draw_hotbar(inventory, 1);
        ImGui::Render();
    }
    const ImGuiWindow* bar = nullptr;
    for (ImGuiWindow* w : ImGui::GetCurrentContext()->Windows)
        if (std::string(w->Name) == "##hotbar") bar = w;
    ASSERT_NE(bar, nullptr);
    EXPECT_NEAR(bar->Pos.x + bar->Size.x * 0.5f, 640.0f, 1.0f);
    EXPECT_GE(bar->Pos.x, 0.0f);
    EXPECT_LE(bar->Pos.x + bar->Size.x, 1280.0f);
    EXPECT_LE(bar->Pos.y + bar->Size.y, 720.0f);
    EXPECT_GE(bar->Pos.y + bar->Size.y, 700.0f);
    EXPECT_GT(bar->Size.x, 5 * 80.0f) << "five slots";
    EXPECT_LE(bar->ContentSize.x, bar->ContentRegionRect.GetWidth() + 0.5f);
}

TEST_F(ImGuiFixture, HiddenHudDrawsNothingAndAsksForNothing) {
    Hud hud;
    hud.visible = false;
    const HudActions a = draw_frame(hud, scene::GiMethod::heat);
    EXPECT_FALSE(a.export_trace || a.save || a.load || a.toggle_vsync);
    EXPECT_EQ(hud_window(), nullptr);
    EXPECT_EQ(graph_extent().vertices, 0);
}

// The draw list is a resource reused every frame: its x-ray list was never emptied, so the
// player's silhouette was drawn (behind walls) at every place it had stood, and the list grew
// by two boxes a frame.
// An open world of `size` tiles, streamed in whole (no workers), for draw list tests; walls
// where `wall` says.
struct StreamedWorld {
    scene::WallGrid grid;
    std::unique_ptr<systems::Streaming> streaming;
    ecs::World world;
    explicit StreamedWorld(glm::ivec2 size, std::vector<glm::ivec2> walls = {}) {
        grid.width = size.x;
        grid.height = size.y;
        grid.cells.assign(std::size_t(grid.width * grid.height), 0);
        for (const glm::ivec2 w : walls) grid.cells[std::size_t(w.x + w.y * grid.width)] = 1;
        streaming = std::make_unique<systems::Streaming>(std::make_shared<systems::GridSource>(grid));
        jobs::JobSystem::Config no_workers;
        no_workers.worker_threads = 0;
        jobs::JobSystem jobs(no_workers);
        streaming->load_all(world, jobs, {0.0f, 0.0f, float(size.x), float(size.y)});
    }
};

// The pause menu in a real ImGui context, clicked through ImGui's own mouse input: one frame
// with the mouse over a button and pressed, one released (as the window feeds it).
struct MenuFixture : ImGuiFixture {
    PauseMenu menu;
    PlayerSettings settings;
    MenuInputs in;
    void SetUp() override {
        ImGuiFixture::SetUp();
        in.settings = &settings;
    }
    MenuActions frame() {
        ImGui::NewFrame();
        MenuActions a = menu.draw(in);
        ImGui::Render();
        return a;
    }
    // Two frames to settle the page, then a press and a release on `label`; the actions of the
    // release frame (empty when the button is not on the page).
    std::optional<MenuActions> click(const std::string& label) {
        frame();
        frame();
        const auto& b = menu.buttons();
        const auto it = std::find_if(b.begin(), b.end(), [&](const MenuButton& m) { return m.label == label; });
        if (it == b.end()) return std::nullopt;
        ImGuiIO& io = ImGui::GetIO();
        io.MousePos = ImVec2(it->x + it->width * 0.5f, it->y + it->height * 0.5f);
        frame(); // hover
        io.MouseDown[0] = true;
        frame();
        io.MouseDown[0] = false;
        return frame();
    }
};

TEST_F(MenuFixture, QuitAsksOnlyWhenSomethingIsUnsaved) {
    menu.open();
    in.unsaved = false;
    auto a = click("Quit");
    ASSERT_TRUE(a);
    EXPECT_TRUE(a->quit) << "nothing unsaved: quit at once";
    in.unsaved = true;
    a = click("Quit");
    ASSERT_TRUE(a);
    EXPECT_FALSE(a->quit);
    EXPECT_EQ(menu.page(), MenuPage::confirm_quit);
    a = click("Cancel");
    ASSERT_TRUE(a && !a->quit);
    EXPECT_EQ(menu.page(), MenuPage::main);
    ASSERT_TRUE(click("Quit"));
    a = click("Save to slot 1 and quit");
    ASSERT_TRUE(a);
    EXPECT_TRUE(a->save_and_quit);
    EXPECT_FALSE(a->quit) << "quits after the save, if it worked";
    menu.open();
    ASSERT_TRUE(click("Quit"));
    a = click("Quit without saving");
    ASSERT_TRUE(a && a->quit);
    // The scene editor's unsaved edits: the question says so, and its save saves them too.
    menu.open();
    in.unsaved_scene = "level.json";
    ASSERT_TRUE(click("Quit"));
    EXPECT_FALSE(click("Save to slot 1 and quit")) << "not offered: it would drop the scene's edits";
    a = click("Save the scene and slot 1, and quit");
    ASSERT_TRUE(a);
    EXPECT_TRUE(a->save_and_quit);
}

TEST_F(MenuFixture, BackWalksUpThePagesAndButtonsStayPut) {
    menu.open();
    ASSERT_TRUE(click("Settings"));
    EXPECT_EQ(menu.page(), MenuPage::settings);
    ASSERT_TRUE(click("Key bindings"));
    EXPECT_EQ(menu.page(), MenuPage::keys);
    menu.back();
    EXPECT_EQ(menu.page(), MenuPage::settings);
    menu.back();
    EXPECT_EQ(menu.page(), MenuPage::main);
    menu.back();
    EXPECT_FALSE(menu.is_open());
    EXPECT_TRUE(frame().load_path.empty());
    EXPECT_TRUE(menu.buttons().empty()) << "a closed menu draws nothing";
    // A page's buttons are where its first frame drew them (a script clicks what the status
    // file listed), and settled_buttons() holds them back until the second.
    menu.open();
    frame();
    EXPECT_TRUE(menu.settled_buttons().empty());
    const std::vector<MenuButton> first = menu.buttons();
    frame();
    ASSERT_EQ(menu.settled_buttons().size(), first.size());
    for (std::size_t i = 0; i < first.size(); ++i) {
        EXPECT_EQ(menu.buttons()[i].label, first[i].label);
        EXPECT_EQ(menu.buttons()[i].x, first[i].x) << first[i].label;
        EXPECT_EQ(menu.buttons()[i].y, first[i].y) << first[i].label;
        EXPECT_EQ(menu.buttons()[i].width, first[i].width) << first[i].label;
    }
}

TEST_F(MenuFixture, SettingsPageEditsTheSettingsAndSlotsSaveAndLoad) {
    menu.open();
    ASSERT_TRUE(click("Settings"));
    ASSERT_TRUE(click("high"));
    EXPECT_EQ(settings.gi_preset, GiPreset::high);
    ASSERT_TRUE(click("vsync: on"));
    EXPECT_FALSE(settings.vsync);
    ASSERT_TRUE(click("+##pixel_scale"));
    ASSERT_TRUE(click("+##pixel_scale"));
    EXPECT_EQ(settings.pixel_scale, 2);
    ASSERT_TRUE(click("gameboy##palette"));
    EXPECT_EQ(std::string(palette_names[settings.palette]), "gameboy");
    ASSERT_TRUE(click("off##palette"));
    EXPECT_EQ(settings.palette, 0);
    ASSERT_TRUE(click("Back##settings"));
    in.save_slots = {{"slot 1", "a.json", true, "2026-11-27 01:00:00"}, {"slot 2", "b.json", false, ""}, {"slot 3", "c.json", false, ""}};
    in.load_slots = in.save_slots;
    ASSERT_TRUE(click("Save"));
    auto a = click("Save to slot 2");
    ASSERT_TRUE(a);
    EXPECT_EQ(a->save_slot, 2);
    ASSERT_TRUE(click("Back##save"));
    ASSERT_TRUE(click("Load"));
    a = click("Load slot 2");
    ASSERT_TRUE(a);
    EXPECT_TRUE(a->load_path.empty()) << "an empty slot cannot be loaded";
    a = click("Load slot 1");
    ASSERT_TRUE(a);
    EXPECT_EQ(a->load_path, "a.json");
}

TEST(DrawList, EachFrameStartsFromAnEmptyList) {
    StreamedWorld open({20, 20});
    ecs::World& world = open.world;
    const systems::Streaming& streaming = *open.streaming;
    spawn_player(world, {10.5f, 10.5f}, true);
    DrawContext ctx;
    ctx.camera = follow_camera({10.5f, 0.0f, 10.5f}, CameraRig{});
    DrawList list;
    build_draw_list(world, streaming, ctx, list);
    const std::size_t boxes = list.boxes.size(), xray = list.xray.size();
    EXPECT_EQ(xray, 2u); // body and head
    EXPECT_EQ(list.late.size(), 3u); // the player's own parts: body, head, backpack
    for (int frame = 0; frame < 3; ++frame) {
        world.view<Player, Transform>().each([&](const Player&, Transform& t) { t.position.x += 0.25f; });
        build_draw_list(world, streaming, ctx, list);
        EXPECT_EQ(list.xray.size(), xray);
        EXPECT_EQ(list.boxes.size(), boxes);
        EXPECT_EQ(list.late.size(), 3u);
    }
    // The silhouette follows the player: its body box is where the player is now.
    EXPECT_NEAR(list.xray[0].center.x, 11.25f, 1e-5f);
}

// Texel lighting (docs/texel.md, "In the game"): the same boxes, but the player's, the tree's
// and the torch's are texel_lit boxes, each naming its part (model and centre: the box is the
// model's); the lights reach the texel passes at their heights, the crystal's without shadows.
TEST(DrawList, TexelLightingMakesModelsTexelLitParts) {
    StreamedWorld open({20, 20});
    ecs::World& world = open.world;
    const systems::Streaming& streaming = *open.streaming;
    spawn_player(world, {10.5f, 10.5f}, true);
    spawn_torch(world, {8.5f, 9.5f}, 0.0f);
    spawn_prop(world, PropKind::tree, {12.5f, 9.5f});
    spawn_prop(world, PropKind::crystal, {9.5f, 11.5f});
    DrawContext ctx;
    ctx.camera = follow_camera({10.5f, 0.0f, 10.5f}, CameraRig{});
    DrawList plain, texel;
    build_draw_list(world, streaming, ctx, plain);
    std::vector<texel::TexelLight> none;
    gather_texel_lights(world, ctx, none);
    EXPECT_TRUE(none.empty());
    EXPECT_TRUE(plain.texel_parts.empty());
    ctx.texel_lighting = true;
    build_draw_list(world, streaming, ctx, texel);
    ASSERT_EQ(texel.boxes.size(), plain.boxes.size());
    ASSERT_EQ(texel.late.size(), plain.late.size());
    EXPECT_EQ(texel.texel_parts.size(), 8u); // body, head, backpack, trunk, crown, torch stick, two crystal shards
    int texel_boxes = 0;
    for (const auto& [with, without] : {std::pair{&texel.boxes, &plain.boxes}, std::pair{&texel.late, &plain.late}})
        for (std::size_t i = 0; i < with->size(); ++i) {
            const BoxInstance& b = (*with)[i];
            if (int(b.material) != int(Material::texel_lit)) continue;
            ++texel_boxes;
            ASSERT_LT(std::size_t(b.emissive), texel.texel_parts.size());
            const TexelPart& part = texel.texel_parts[std::size_t(b.emissive)];
            EXPECT_EQ(part.center, b.center);
            EXPECT_EQ(texel_model_half(TexelModel(part.model)), b.half);
            EXPECT_EQ((*without)[i].center, b.center); // where the plain box was, the same size
            EXPECT_EQ((*without)[i].half, b.half);
        }
    EXPECT_EQ(texel_boxes, 8);
    // The crystal's shards glow, in the crystal's colour (their boxes' tint); nothing else does.
    int glowing = 0;
    for (const BoxInstance& b : texel.boxes) {
        if (int(b.material) != int(Material::texel_lit)) continue;
        const TexelPart& part = texel.texel_parts[std::size_t(b.emissive)];
        const bool crystal = part.model == int(TexelModel::crystal) || part.model == int(TexelModel::crystal_shard);
        if (!crystal) {
            EXPECT_EQ(part.glow, 0.0f);
            EXPECT_EQ(b.color, glm::vec3(1.0f));
            continue;
        }
        ++glowing;
        EXPECT_GT(part.glow, 0.5f);
        EXPECT_EQ(b.color, default_tables().crystal.color);
    }
    EXPECT_EQ(glowing, 2);
    std::vector<texel::TexelLight> lights;
    gather_texel_lights(world, ctx, lights);
    ASSERT_EQ(lights.size(), 3u); // the player's lantern, the torch, the crystal
    int unshadowed = 0;
    for (const texel::TexelLight& l : lights) {
        EXPECT_GT(l.position_range.y, 0.0f); // at a height
        unshadowed += int(l.color_type.w) == int(texel::ShadowType::none);
    }
    EXPECT_EQ(unshadowed, 1);
    // Seed 001's ambient per light: the tables' colour for each game light, in its hue.
    for (const texel::TexelLight& l : lights) {
        const glm::vec3 fill(l.ambient);
        EXPECT_GT(fill.r + fill.g + fill.b, 0.0f);
        if (int(l.color_type.w) == int(texel::ShadowType::none)) {
            EXPECT_EQ(fill, default_tables().crystal.ambient); // a crystal at the table's intensity
        }
    }
    // A scene's own light (no torch, prop or player) has none.
    const ecs::Entity own = world.create();
    world.emplace<PointLight>(own, PointLight{{9.5f, 10.5f}, 1.0f, {1.0f, 1.0f, 1.0f}, 1.0f, 5.0f});
    gather_texel_lights(world, ctx, lights);
    ASSERT_EQ(lights.size(), 4u);
    int without = 0;
    for (const texel::TexelLight& l : lights) without += glm::vec3(l.ambient) == glm::vec3(0.0f);
    EXPECT_EQ(without, 1);
    // The models' textures are painted: every face texel has a colour.
    for (int m = 0; m < int(TexelModel::count); ++m) {
        const texel::Model& model = texel_model(TexelModel(m));
        for (const glm::ivec4& f : model.faces)
            for (int j = 0; j < f.w; ++j)
                for (int i = 0; i < f.z; ++i)
                    EXPECT_GT(model.albedo[std::size_t(f.y + j) * std::size_t(model.size) + std::size_t(f.x + i)].a, 0.0f);
    }
}

// Issue 19's dropped items, through the game's own systems (add_gameplay_systems): mining a
// wall drops its block where the wall stood, not straight into the inventory; after its hop
// the player, standing near, collects it (it glides over: the count rises, a pick-up cue, an
// edit). A torch taken off the ground drops too. An item out of reach stays, and so does one
// whose stack is full. The draw list draws each as its item's small model, a moving part.
TEST(Gameplay, MinedThingsDropAsItemsThatThePlayerCollectsByWalkingNear) {
    scene::WallGrid grid;
    grid.width = 24;
    grid.height = 16;
    grid.cells.assign(std::size_t(grid.width * grid.height), 0);
    grid.cells[std::size_t(12 + 8 * grid.width)] = 1;
    ecs::World world;
    jobs::JobSystem::Config no_workers;
    no_workers.worker_threads = 0;
    jobs::JobSystem jobs(no_workers);
    world.set_resource<systems::Streaming>(std::make_shared<systems::GridSource>(grid));
    world.resource<systems::Streaming>().load_all(world, jobs, {0.0f, 0.0f, 24.0f, 16.0f});
    world.set_resource<Controls>();
    world.set_resource<GameClock>();
    world.set_resource<CameraRig>();
    world.set_resource<DayCycle>();
    world.set_resource<systems::GiConfig>();
    world.set_resource<Inventory>();
    world.set_resource<WorldEdits>();
    world.set_resource<SoundCues>();
    const ecs::Entity player = spawn_player(world, {10.5f, 8.5f}, false);
    const ecs::Entity camera = world.create();
    world.emplace<Camera>(camera, Camera{follow_camera({10.5f, 0.0f, 8.5f}, CameraRig{})});
    ecs::Schedule schedule(jobs);
    add_gameplay_systems(schedule);
    const auto frame = [&] {
        schedule.run(world);
        world.resource<Controls>() = Controls{}; // a click lasts one frame
    };
    frame(); // the camera follows the player
    const auto click_at = [&](glm::vec3 point) {
        const auto* view = std::get_if<scene::PerspectiveCamera>(&world.get<Camera>(camera).view);
        ASSERT_NE(view, nullptr);
        const auto ndc = project_to_ndc(*view, point);
        ASSERT_TRUE(ndc);
        Controls& c = world.resource<Controls>();
        c.has_cursor = true;
        c.cursor_ndc = *ndc;
        c.mine = true;
    };
    const auto items = [&] {
        std::vector<DroppedItem> out;
        world.view<DroppedItem>().each([&](const DroppedItem& d) { out.push_back(d); });
        return out;
    };
    const Inventory start = world.resource<Inventory>();
    const std::uint64_t edits = world.resource<WorldEdits>().count;
    // Mine the wall 2 tiles east (its top's centre under the cursor).
    click_at({12.5f, 1.99f, 8.5f});
    frame();
    EXPECT_FALSE(world.resource<systems::Streaming>().is_wall({12, 8}));
    auto dropped = items();
    ASSERT_EQ(dropped.size(), 1u);
    EXPECT_EQ(dropped[0].item, Item::wall);
    EXPECT_EQ(dropped[0].position, glm::vec2(12.5f, 8.5f));
    EXPECT_EQ(world.resource<Inventory>()[Item::wall], start[Item::wall]) << "mined straight into the inventory";
    // The draw list shows it: the block's small model, moving (lit live).
    {
        DrawContext ctx;
        ctx.camera = follow_camera({10.5f, 0.0f, 8.5f}, CameraRig{});
        ctx.texel_lighting = true;
        DrawList list;
        build_draw_list(world, world.resource<systems::Streaming>(), ctx, list);
        int blocks = 0;
        for (const TexelPart& p : list.texel_parts)
            if (p.model == int(TexelModel::item_block)) {
                ++blocks;
                EXPECT_TRUE(p.moves);
                EXPECT_NEAR(p.center.x, 12.5f, 1e-4f);
            }
        EXPECT_EQ(blocks, 1);
    }
    // 2 tiles away: beyond the magnet. The player steps east; the block glides over and in.
    for (int i = 0; i < 30; ++i) frame();
    EXPECT_EQ(items().size(), 1u) << "collected from beyond the magnet's reach";
    world.get<Transform>(player).position = glm::vec3(11.2f, 0.0f, 8.5f);
    int frames = 0;
    while (!items().empty() && frames < 120) frame(), ++frames;
    EXPECT_TRUE(items().empty()) << "not collected after " << frames << " frames";
    EXPECT_GT(frames, 1) << "it should glide over, not jump";
    EXPECT_EQ(world.resource<Inventory>()[Item::wall], start[Item::wall] + 1);
    EXPECT_GT(world.resource<WorldEdits>().count, edits + 1); // the dig and the pick-up
    bool cue = false;
    for (const SoundCues::Entry& e : world.resource<SoundCues>().entries) cue |= e.cue == SoundCue::pick_up;
    EXPECT_TRUE(cue);
    // A torch taken off the ground drops as a torch; with the torches' stack full it stays put.
    spawn_torch(world, {9.5f, 8.5f}, 0.0f);
    world.resource<Inventory>()[Item::torch] = Inventory::max_stack;
    click_at({9.5f, 0.0f, 8.5f});
    frame();
    dropped = items();
    ASSERT_EQ(dropped.size(), 1u);
    EXPECT_EQ(dropped[0].item, Item::torch);
    for (int i = 0; i < 60; ++i) frame();
    dropped = items();
    ASSERT_EQ(dropped.size(), 1u) << "collected into a full stack";
    EXPECT_EQ(dropped[0].position, glm::vec2(9.5f, 8.5f));
    world.resource<Inventory>()[Item::torch] = 3;
    for (int i = 0; i < 60 && !items().empty(); ++i) frame();
    EXPECT_TRUE(items().empty());
    EXPECT_EQ(world.resource<Inventory>()[Item::torch], 4);
}

// The day cycle moves the sun in steps of 1/sun_steps_per_day of a day: at the game's day
// length (60 s a day, 60 frames a second) the sun changes every fifth frame, so between
// steps its GI pass stays cached while torches flicker; each step is half a degree.
TEST(Gameplay, TheDayCycleMovesTheSunInSteps) {
    ecs::World world;
    jobs::JobSystem::Config no_workers;
    no_workers.worker_threads = 0;
    jobs::JobSystem jobs(no_workers);
    scene::WallGrid grid;
    grid.width = grid.height = 16;
    grid.cells.assign(std::size_t(grid.width * grid.height), 0);
    world.set_resource<systems::Streaming>(std::make_shared<systems::GridSource>(grid));
    world.set_resource<Controls>();
    world.set_resource<GameClock>();
    world.set_resource<CameraRig>();
    world.set_resource<DayCycle>(DayCycle{true, 0.4f, 60.0f, true});
    world.set_resource<systems::GiConfig>();
    world.set_resource<Inventory>();
    world.set_resource<WorldEdits>();
    world.set_resource<SoundCues>();
    spawn_player(world, {8.5f, 8.5f}, false);
    const ecs::Entity sun = world.create();
    world.emplace<Sun>(sun);
    world.emplace<DirectionalLight>(sun, DirectionalLight{sun_direction(0.4f), sun_light(0.4f), 1.0f, 4.0f, 0.5f});
    ecs::Schedule schedule(jobs);
    add_gameplay_systems(schedule);
    schedule.run(world);
    glm::vec3 last = world.get<DirectionalLight>(sun).direction;
    long last_step = std::lround(sun_step_time(world.resource<DayCycle>().time_of_day) * float(sun_steps_per_day));
    int changes = 0;
    for (int f = 0; f < 120; ++f) {
        schedule.run(world);
        const DirectionalLight& d = world.get<DirectionalLight>(sun);
        const float shown = sun_step_time(world.resource<DayCycle>().time_of_day);
        EXPECT_EQ(d.direction, sun_direction(shown)) << "frame " << f;
        EXPECT_EQ(d.color, sun_light(shown)) << "frame " << f;
        const long step = std::lround(shown * float(sun_steps_per_day));
        if (d.direction != last) {
            ++changes;
            EXPECT_EQ(step, last_step + 1) << "frame " << f << ": one step at a time";
            const float degrees = glm::degrees(std::acos(std::clamp(glm::dot(d.direction, last), -1.0f, 1.0f)));
            EXPECT_LT(degrees, 0.51f) << "frame " << f;
        } else {
            EXPECT_EQ(step, last_step) << "frame " << f;
        }
        last = d.direction;
        last_step = step;
    }
    EXPECT_GE(changes, 23);
    EXPECT_LE(changes, 25) << "120 frames of 1/3600 of a day: one step every five frames";
}

// Seed 001's static lights in the game: under a bake (context.probes), the crystal's light
// (baked mode) is marked to be baked into the models' texels; the player's lantern and the
// torch stay live (realtime), as does the lamp post's (mixed: its direct light is live).
// The player's parts are the ones that move.
TEST(DrawList, BakedModeLightsAreBakedIntoTheTexelsUnderABakeAndThePlayerMoves) {
    StreamedWorld open({20, 20});
    ecs::World& world = open.world;
    const systems::Streaming& streaming = *open.streaming;
    spawn_player(world, {10.5f, 10.5f}, true);
    spawn_torch(world, {8.5f, 9.5f}, 0.0f);
    spawn_prop(world, PropKind::crystal, {9.5f, 11.5f});
    spawn_prop(world, PropKind::lamp_post, {11.5f, 8.5f});
    DrawContext ctx;
    ctx.camera = follow_camera({10.5f, 0.0f, 10.5f}, CameraRig{});
    ctx.texel_lighting = true;
    std::vector<texel::TexelLight> lights;
    gather_texel_lights(world, ctx, lights);
    ASSERT_EQ(lights.size(), 4u);
    for (const texel::TexelLight& l : lights) EXPECT_FALSE(texel::is_baked(l)) << "no bake in use: every light is live";
    const BakedChunks baked;
    ctx.probes = &baked;
    gather_texel_lights(world, ctx, lights);
    ASSERT_EQ(lights.size(), 4u);
    int marked = 0;
    for (const texel::TexelLight& l : lights) {
        if (!texel::is_baked(l)) continue;
        ++marked;
        EXPECT_EQ(int(l.color_type.w), int(texel::ShadowType::none)); // the crystal's
    }
    EXPECT_EQ(marked, 1);
    DrawList list;
    build_draw_list(world, streaming, ctx, list);
    int moving = 0;
    for (const TexelPart& p : list.texel_parts) {
        const bool player = p.model == int(TexelModel::player_body) || p.model == int(TexelModel::player_head) ||
                            p.model == int(TexelModel::backpack);
        EXPECT_EQ(p.moves, player) << "model " << p.model;
        moving += p.moves;
    }
    EXPECT_EQ(moving, 3);
}

// Trees' crowns sway in the wind: between two times the crown moves a little and the trunk
// stays; the crown is a moving part (lit live, carried again by UV to world), the trunk not.
TEST(DrawList, TreeCrownsSwayAsMovingPartsAndTrunksStandStill) {
    StreamedWorld open({20, 20});
    spawn_prop(open.world, PropKind::tree, {9.5f, 8.5f});
    DrawContext ctx;
    ctx.camera = follow_camera({10.5f, 0.0f, 10.5f}, CameraRig{});
    ctx.texel_lighting = true;
    DrawList a, b;
    ctx.time = 10.0;
    build_draw_list(open.world, *open.streaming, ctx, a);
    ctx.time = 10.5;
    build_draw_list(open.world, *open.streaming, ctx, b);
    const auto find = [](const DrawList& l, TexelModel m) -> const TexelPart* {
        for (const TexelPart& p : l.texel_parts)
            if (p.model == int(m)) return &p;
        return nullptr;
    };
    const TexelPart *crown_a = find(a, TexelModel::tree_crown), *crown_b = find(b, TexelModel::tree_crown);
    const TexelPart *trunk_a = find(a, TexelModel::tree_trunk), *trunk_b = find(b, TexelModel::tree_trunk);
    ASSERT_TRUE(crown_a && crown_b && trunk_a && trunk_b);
    EXPECT_TRUE(crown_a->moves);
    EXPECT_FALSE(trunk_a->moves);
    EXPECT_EQ(trunk_a->center, trunk_b->center);
    const glm::vec3 d = crown_b->center - crown_a->center;
    EXPECT_EQ(d.y, 0.0f);
    EXPECT_GT(glm::length(d), 1e-3f) << "the crown did not sway";
    EXPECT_LE(std::abs(crown_a->center.x - 9.5f), crown_sway_tiles + 1e-6f);
    EXPECT_LE(std::abs(crown_a->center.z - 8.5f), crown_sway_tiles + 1e-6f);
}

// Issue 19: a lower level of detail for far models. A part farther than texel_lod_distance
// from the point the camera looks at takes LOD 1: the same box, its art at half the texels per
// unit (a quarter of the texels to light), painted on every face texel.
TEST(DrawList, FarModelsTakeTheCoarserLevelOfDetail) {
    StreamedWorld open({60, 60});
    ecs::World& world = open.world;
    const systems::Streaming& streaming = *open.streaming;
    spawn_player(world, {30.5f, 30.5f}, false);
    spawn_prop(world, PropKind::tree, {32.5f, 30.5f});                    // near
    spawn_prop(world, PropKind::tree, {30.5f + texel_lod_distance + 2.0f, 30.5f}); // far, still in view
    DrawContext ctx;
    ctx.camera = follow_camera({30.5f, 0.0f, 30.5f}, CameraRig{});
    ctx.texel_lighting = true;
    DrawList list;
    build_draw_list(world, streaming, ctx, list);
    int near = 0, far = 0;
    for (const TexelPart& p : list.texel_parts) {
        const bool is_far = p.center.x > 30.5f + texel_lod_distance;
        EXPECT_EQ(p.lod, is_far ? 1 : 0) << p.center.x;
        (is_far ? far : near) += 1;
    }
    EXPECT_EQ(far, 2); // the far tree's trunk and crown
    EXPECT_GE(near, 5); // the player's three parts, the near tree's two
    for (const TexelPart& p : list.texel_parts) EXPECT_EQ(p.probe, -1) << "no baked light: no probe record";
    // With baked light, each part names its own probe record (its side faces take the baked
    // light's direction; WorldRendererTest.ProbesLightATexelLitFaceFromWhereTheBakedLightComes).
    const BakedChunks baked;
    ctx.probes = &baked;
    build_draw_list(world, streaming, ctx, list);
    ASSERT_EQ(list.probes.size(), list.texel_parts.size());
    for (std::size_t k = 0; k < list.texel_parts.size(); ++k) EXPECT_EQ(list.texel_parts[k].probe, int(k));
    for (int m = 0; m < int(TexelModel::count); ++m) {
        const texel::Model& fine = texel_model(TexelModel(m), 0);
        const texel::Model& coarse = texel_model(TexelModel(m), 1);
        // Fewer texels, except where the art is one or two texels a side already (a face is
        // at least one texel: the crystal's small shard).
        bool small = true;
        for (const glm::ivec4& f : fine.faces) small = small && f.z <= 2 && f.w <= 2;
        if (small)
            EXPECT_LE(coarse.size, fine.size) << m;
        else
            EXPECT_LT(coarse.size, fine.size) << m;
        EXPECT_EQ(coarse.faces.size(), fine.faces.size());
        for (const glm::ivec4& f : coarse.faces)
            for (int j = 0; j < f.w; ++j)
                for (int i = 0; i < f.z; ++i)
                    EXPECT_GT(coarse.albedo[std::size_t(f.y + j) * std::size_t(coarse.size) + std::size_t(f.x + i)].a, 0.0f);
    }
}

// Seed 004's per-object anchor override: a tree with a ProbeAnchor takes the baked light's
// probes at its anchor (plain boxes: one record for the object; texel-lit: one per part, all
// at the anchor); one without takes them at its own position.
TEST(DrawList, AProbeAnchorMovesWhereAnObjectSamplesTheProbes) {
    StreamedWorld open({32, 32});
    ecs::World& world = open.world;
    const systems::Streaming& streaming = *open.streaming;
    // Chunk (0, 0)'s probes hold their own x as fluence: what a record holds says where it
    // was sampled.
    auto chunk = std::make_shared<bake::ChunkBake>();
    chunk->empty = false;
    chunk->resolution = 1;
    chunk->probes.resize(std::size_t(bake::chunk_probes * bake::chunk_probes));
    chunk->probe_valid.assign(chunk->probes.size(), 1);
    for (int j = 0; j < bake::chunk_probes; ++j)
        for (int i = 0; i < bake::chunk_probes; ++i)
            chunk->probes[std::size_t(j * bake::chunk_probes + i)].c[0] = glm::vec3(float(i * bake::probe_spacing) + 0.5f);
    BakedChunks baked;
    baked.chunks[chunk_id_key({0, 0})] = chunk;
    spawn_player(world, {10.5f, 10.5f}, true);
    // The game's trees carry an anchor at their base (Saves.ATreesProbeAnchorIsItsBaseAndSavesKeepIt):
    // the plain one loses it, the anchored one gets one elsewhere.
    const ecs::Entity plain = spawn_prop(world, PropKind::tree, {12.5f, 9.5f});
    const ecs::Entity anchored = spawn_prop(world, PropKind::tree, {8.5f, 9.5f});
    world.remove<ProbeAnchor>(plain);
    world.emplace_or_replace<ProbeAnchor>(anchored, ProbeAnchor{{20.5f, 9.5f}});
    DrawContext ctx;
    ctx.camera = follow_camera({10.5f, 0.0f, 10.5f}, CameraRig{});
    ctx.probes = &baked;
    DrawList list;
    build_draw_list(world, streaming, ctx, list);
    std::vector<float> sampled; // each lit_probes box's record's fluence (its x)
    for (const BoxInstance& b : list.boxes)
        if (int(b.material) == int(Material::lit_probes)) sampled.push_back(list.probes[std::size_t(b.emissive)].c[0].x);
    ASSERT_EQ(sampled.size(), 4u); // two trees, trunk and crown each
    EXPECT_EQ(std::count(sampled.begin(), sampled.end(), 12.5f), 2) << "the plain tree, at its position";
    EXPECT_EQ(std::count(sampled.begin(), sampled.end(), 20.5f), 2) << "the anchored tree, at its anchor";
    ctx.texel_lighting = true;
    build_draw_list(world, streaming, ctx, list);
    int at_anchor = 0;
    for (const TexelPart& p : list.texel_parts) {
        ASSERT_GE(p.probe, 0);
        const float x = list.probes[std::size_t(p.probe)].c[0].x;
        if (std::abs(p.center.x - 8.5f) < crown_sway_tiles + 0.01f) { // the anchored tree (its crown sways)
            EXPECT_EQ(x, 20.5f);
            ++at_anchor;
        } else {
            EXPECT_NEAR(x, p.center.x, 1e-4f) << "a part without an anchor samples at its centre";
        }
    }
    EXPECT_EQ(at_anchor, 2);
}

// Issue 19: a scene file's lights were invisible (no light or shadow may come from nothing).
// The draw list now carries a lamp for each point light that no torch, prop or player owns
// and a glowing slab for each such emissive light, in the light's hue; the game's own
// torches, props and the player's lantern keep their models only; lights inside walls and
// out of view are not drawn.
TEST(DrawList, SceneLightsAreDrawnAndTheGamesOwnAreNotDrawnTwice) {
    StreamedWorld walled({40, 30}, {{12, 10}}); // a wall tile at (12, 10)
    ecs::World& world = walled.world;
    const systems::Streaming& streaming = *walled.streaming;
    const glm::vec2 player(10.5f, 10.5f);
    spawn_player(world, player, true); // carries a lantern (a PointLight)
    spawn_torch(world, {8.5f, 9.5f}, 0.0f);
    spawn_prop(world, PropKind::crystal, {11.5f, 8.5f}); // a Prop with an EmissiveLight
    const auto light = [&](glm::vec2 at, glm::vec3 color) {
        const ecs::Entity e = world.create();
        PointLight l;
        l.position = at;
        l.color = color;
        l.height = 1.2f;
        world.emplace<PointLight>(e, l);
    };
    light({9.5f, 12.5f}, {0.2f, 0.4f, 0.8f});  // a scene's blue lamp
    light({12.5f, 10.5f}, {1.0f, 0.0f, 0.0f}); // inside the wall tile: not drawn
    light({39.5f, 29.5f}, {0.0f, 1.0f, 0.0f}); // far out of view
    const ecs::Entity lava = world.create();
    EmissiveLight pool;
    pool.position = {7.5f, 11.5f};
    pool.color = {2.0f, 0.6f, 0.1f};
    world.emplace<EmissiveLight>(lava, pool);

    DrawContext ctx;
    ctx.camera = follow_camera({player.x, 0.0f, player.y}, CameraRig{});
    DrawList list;
    build_draw_list(world, streaming, ctx, list);
    const auto glow_at = [&](glm::vec2 at) {
        std::vector<const BoxInstance*> found;
        for (const BoxInstance& b : list.boxes)
            if (b.material == float(Material::glow) && glm::distance(glm::vec2(b.center.x, b.center.z), at) < 0.2f)
                found.push_back(&b);
        return found;
    };
    const auto blue = glow_at({9.5f, 12.5f});
    ASSERT_EQ(blue.size(), 1u) << "the scene's point light has no lamp";
    EXPECT_NEAR(blue[0]->center.y, 1.2f, 1e-5f) << "the lamp hangs at the light's height";
    EXPECT_NEAR(blue[0]->color.b, 1.0f, 1e-5f);
    EXPECT_NEAR(blue[0]->color.r, 0.25f, 1e-5f) << "the light's hue, brightest channel 1";
    EXPECT_TRUE(glow_at({12.5f, 10.5f}).empty()) << "a light inside a wall is drawn";
    EXPECT_TRUE(glow_at({39.5f, 29.5f}).empty()) << "a light out of view is drawn";
    const auto slab = glow_at({7.5f, 11.5f});
    ASSERT_EQ(slab.size(), 1u) << "the scene's emissive light has no slab";
    EXPECT_LT(slab[0]->center.y, 0.1f);
    EXPECT_NEAR(slab[0]->color.g, 0.3f, 1e-5f);
    // The game's own: one flame for the torch, the crystal's two glowing boxes, and nothing
    // glowing at the player (its lantern is part of its model).
    EXPECT_EQ(glow_at({8.5f, 9.5f}).size(), 1u);
    EXPECT_EQ(glow_at({11.5f, 8.5f}).size(), 2u);
    EXPECT_TRUE(glow_at(player).empty());
}

} // namespace
} // namespace lantern::game

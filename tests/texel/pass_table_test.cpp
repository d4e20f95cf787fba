// The texel pass table (engine/texel/pass_table.hpp): which rows a frame runs and why the
// others do not, that the reference backend's planned frames equal every pass run afresh,
// and that the light lists leave out only lights that add nothing.
#include "lantern/texel/pass_table.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace lantern::texel {
namespace {

glm::mat4 at(float x, float z) { return glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, z)); }

// A room (walls around, a pillar), a walking player, two crates and a tall post.
struct Room {
    scene::WallGrid grid;
    Model player = box_model(glm::vec3(-0.3f, 0.0f, -0.2f), glm::vec3(0.3f, 1.2f, 0.2f), 6);
    Model crate = box_model(glm::vec3(-0.4f, 0.0f, -0.4f), glm::vec3(0.4f, 0.8f, 0.4f), 6);
    Model post = box_model(glm::vec3(-0.1f, 0.0f, -0.1f), glm::vec3(0.1f, 1.6f, 0.1f), 6);
    std::vector<Placement> placements;
    TexelScene scene;
    std::vector<TexelLight> lights;

    Room() {
        grid.width = 14;
        grid.height = 12;
        grid.cells.assign(std::size_t(grid.width) * grid.height, 0);
        for (int x = 0; x < 14; ++x) wall(x, 0), wall(x, 11);
        for (int z = 0; z < 12; ++z) wall(0, z), wall(13, z);
        wall(6, 5), wall(6, 6);
        placements = {{&player, at(3.5f, 4.5f), true}, {&crate, at(8.5f, 3.5f)}, {&crate, at(9.5f, 8.5f)}, {&post, at(4.5f, 8.5f)}};
        lights = {make_light({5.0f, 1.0f, 5.0f}, {1.0f, 0.7f, 0.4f}, 1.5f, 6.0f),
                  make_light({10.5f, 1.2f, 6.0f}, {0.4f, 0.6f, 1.0f}, 1.0f, 5.0f, ShadowType::blurred, 1.0f, 1.0f, {0.05f, 0.0f, 0.1f}),
                  as_baked(make_light({7.0f, 3.0f, 6.0f}, {0.9f, 0.9f, 0.8f}, 1.0f, 9.0f)),
                  make_light({2.0f, 0.5f, 10.0f}, {0.2f, 1.0f, 0.2f}, 1.0f, 1.5f), // reaches nothing
                  make_sun({0.6f, -0.5f, 0.3f}, {0.4f, 0.4f, 0.35f}, 1.0f, ShadowType::hard, 20.0f)};
        rebuild();
    }
    void wall(int x, int z, std::uint8_t v = 1) { grid.cells[std::size_t(x) + std::size_t(z) * grid.width] = v; }
    void rebuild() { scene = build_scene(placements, gi::WallView::of(grid), 2.0f, 10.0f); }
    void move(std::uint32_t k, float x, float z) {
        placements[k].transform = at(x, z);
        move_placement(scene, k, *placements[k].model, placements[k].transform);
    }
};

std::string runs(const TexelPlan& plan) {
    std::string out;
    for (const TexelRow& row : texel_rows())
        if (plan.runs(row.pass)) out += (out.empty() ? "" : ", ") + std::string(row.name);
    return out;
}

bool same_bits(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
    if (a.size() != b.size()) return false;
    return a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec4)) == 0; // (no memcmp of nullptr)
}

// Every pass afresh: what a planned frame must equal.
std::vector<glm::vec4> afresh(const Room& r) {
    const std::vector<TexelSurface> s = uv_to_world(r.scene);
    std::vector<TexelLight> fixed;
    for (const TexelLight& l : r.lights)
        if (is_baked(l)) fixed.push_back(l);
    return reference_light(r.scene, s, r.lights, reference_light(r.scene, s, fixed));
}

// Frame after frame a row runs when, and only when, something it reads changed; the planned
// frames on the reference backend equal every pass run afresh, bit for bit.
TEST(TexelPassTable, ARowRunsWhenWhatItReadsChangedAndTheFramesEqualEveryPassAfresh) {
    Room r;
    TexelHistory history;
    TexelReferenceStore store;
    const auto frame = [&](const char* what, const std::string& expected_runs) {
        const TexelFrame f{r.scene, r.lights};
        const TexelPlan plan = plan_texel_frame(f, history);
        EXPECT_EQ(runs(plan), expected_runs) << what;
        execute_reference(f, plan, store);
        EXPECT_TRUE(same_bits(store.lit, afresh(r))) << what << ": the planned frame differs from every pass afresh";
        return plan;
    };
    TexelPlan p = frame("the first frame", "texel uv to world, texel bake, texel light");
    EXPECT_TRUE(p.upload_layout);
    EXPECT_TRUE(p.moved.empty()); // every texel
    p = frame("nothing changed", "");
    EXPECT_STREQ(p.why_not[std::size_t(TexelPass::light)], "unchanged");
    EXPECT_FALSE(p.upload_layout || p.upload_triangles || p.upload_walls);

    r.move(0, 3.9f, 4.6f); // the player walks: its texels again, the realtime pass; no bake
    p = frame("the player walked", "texel uv to world, texel light");
    EXPECT_EQ(p.moved, std::vector<std::uint32_t>{0u});
    EXPECT_TRUE(p.upload_triangles);
    EXPECT_FALSE(p.upload_layout);

    r.lights[0].color_type *= 0.9f; // a torch flickers
    frame("a live light changed", "texel light");
    r.lights[2].color_type *= 0.5f; // the static lamp dims
    frame("a static light changed", "texel bake, texel light");

    r.wall(6, 6, 0); // the pillar mined
    r.rebuild();
    p = frame("a wall mined", "texel bake, texel light");
    EXPECT_TRUE(p.upload_walls);

    r.move(1, 8.0f, 3.0f); // a crate pushed: its texels again, and a new bake
    p = frame("a still model moved", "texel uv to world, texel bake, texel light");
    EXPECT_EQ(p.moved, std::vector<std::uint32_t>{1u});

    r.placements.pop_back(); // the post leaves the view: a new layout
    r.rebuild();
    p = frame("a model left", "texel uv to world, texel bake, texel light");
    EXPECT_TRUE(p.upload_layout);

    r.placements.clear();
    r.rebuild();
    p = frame("nothing in view", "");
    EXPECT_STREQ(p.why_not[std::size_t(TexelPass::light)], "no texels");
}

// A history reset (a frame whose plan was not run) runs every row again.
TEST(TexelPassTable, AResetHistoryRunsEveryRow) {
    Room r;
    TexelHistory history;
    const TexelFrame f{r.scene, r.lights};
    (void)plan_texel_frame(f, history);
    history.reset();
    const TexelPlan p = plan_texel_frame(f, history);
    EXPECT_EQ(runs(p), "texel uv to world, texel bake, texel light");
    EXPECT_TRUE(p.upload_layout);
}

// The light lists leave out only lights that add nothing to a placement's texels: on random
// rooms, every texel's sum over its list is the sum over all lights, bit for bit, in both
// passes; and lights out of reach are left out.
TEST(TexelPassTable, LightListsLeaveOutOnlyLightsThatAddNothing) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> x(0.5f, 13.5f), z(0.5f, 11.5f), y(0.2f, 3.0f), range(0.5f, 7.0f), c(0.1f, 1.0f);
    int left_out = 0;
    for (int round = 0; round < 6; ++round) {
        Room r;
        r.lights.clear();
        for (int i = 0; i < 24; ++i) {
            const float lx = x(rng), ly = y(rng), lz = z(rng), lr = range(rng), cr = c(rng), cg = c(rng);
            TexelLight l = make_light({lx, ly, lz}, {cr, cg, 0.5f}, 1.0f, lr,
                                      i % 3 == 0 ? ShadowType::blurred : ShadowType::hard, 1.0f, 1.0f, {0.02f, 0.01f, 0.0f});
            r.lights.push_back(i % 4 == 0 ? as_baked(l) : l);
        }
        r.lights.push_back(make_sun({0.5f, -0.6f, -0.2f}, {0.3f, 0.3f, 0.3f}, 1.0f));
        const std::vector<TexelSurface> s = uv_to_world(r.scene);
        for (const LightPass pass : {LightPass::bake, LightPass::realtime}) {
            const std::vector<std::uint32_t> lists = light_lists(r.scene, r.lights, pass);
            const std::size_t count = r.scene.placements.size();
            for (std::size_t k = 0; k < count; ++k) {
                const GpuPlacement& p = r.scene.placements[k];
                std::vector<TexelLight> mine;
                for (std::uint32_t j = 0; j < lists[2 * k + 1]; ++j) mine.push_back(r.lights[lists[2 * count + lists[2 * k] + j]]);
                if (pass == LightPass::realtime) left_out += int(r.lights.size() - mine.size());
                for (std::uint32_t i = p.ranges.z; i < p.ranges.z + p.ranges.w * p.ranges.w; ++i) {
                    const glm::vec3 all = texel_light(r.scene, r.lights, s[i], pass);
                    const glm::vec3 listed = texel_light(r.scene, mine, s[i], pass);
                    ASSERT_EQ(std::memcmp(&all, &listed, sizeof(all)), 0)
                        << "round " << round << " placement " << k << " texel " << i;
                }
            }
        }
    }
    EXPECT_GT(left_out, 100) << "the lists left nothing out: nothing was culled";
}

} // namespace
} // namespace lantern::texel

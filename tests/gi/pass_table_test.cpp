// The pass table (engine/gi pass_table.hpp) proves itself:
//  - every gi setting, perturbed on a scene that runs every pass: each pass whose cache key
//    did not change leaves exactly the same outputs (so a setting that changes a pass's
//    output but is missing from its row fails here), and when the plan, window and inputs
//    stay the same the keys that change are exactly those of the rows listing the setting,
//    the rows downstream of them and the producers they overwrite in place;
//  - a row with a setting taken off is caught by that check;
//  - allocation follows the planned rows' writes; every row names settings that exist.
#include "lantern/gi/pass_table.hpp"

#include "lantern/scene/loader.hpp"
#include "test_scenes.hpp"

#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

using namespace lantern;
using namespace lantern::gi;

namespace {

// Rooms with point lights and an emissive, plus a sun and a shadow proxy, and (with_bake) a
// baked light: every pass runs.
scene::Scene every_pass_scene() {
    scene::Scene s = gi_test::comparison_scene("rooms").scene;
    scene::DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.4f, -0.8f, -0.3f));
    sun.color = {1.0f, 0.9f, 0.8f};
    sun.intensity = 0.4f;
    s.directional_lights.push_back(sun);
    scene::ShadowProxy proxy;
    proxy.position = {6.5f, 6.5f};
    proxy.size = {0.4f, 0.4f};
    s.shadow_proxies.push_back(proxy);
    s.gi.heat_rounds = 6;
    s.point_lights[1].mode = scene::LightMode::mixed; // its direct light by the mixed row
    return s;
}

// A different valid value for each gi key, as `--set` takes it; nullopt for a key with one
// possible value. A key missing here fails EverySettingHasAPerturbation.
std::optional<std::string> perturbed(const std::string& key, const scene::GiSettings& gi) {
    const double v = *scene::gi_setting_value(gi, key);
    // Two candidates each: the first that differs from the scene's value.
    const std::map<std::string, std::pair<double, std::string>> values = {
        {"resolution", {3, "3"}},
        {"padding", {1.3, "1.3"}},
        {"window_snap", {double(int(scene::WindowSnap::texel)), "texel"}},
        {"sun_shadow_method", {double(int(scene::SunShadowMethod::shadow_map)), "shadow_map"}},
        {"shadow_method", {double(int(scene::ShadowMethod::dda)), "dda"}},
        {"proxy_wall_shadows", {double(int(scene::ProxyWallShadows::unfold)), "unfold"}},
        {"heat_rounds", {9, "9"}},
        {"heat_scale", {double(int(scene::HeatScale::half)), "half"}},
        {"diffusion_rate", {0.7, "0.7"}},
        {"diffusion_distance", {1.6, "1.6"}},
        {"emission_strength", {0.6, "0.6"}},
        {"range_boost", {0.5, "0.5"}},
        {"intensity_multiplier", {1.3, "1.3"}},
        {"light_softness", {2.0, "2.0"}},
        {"wall_face_exponent", {2.0, "2.0"}},
        {"ao.radius", {2.5, "2.5"}},
        {"ao.power", {2.5, "2.5"}},
        {"ao.strength", {0.4, "0.4"}},
        {"tone_map", {double(int(scene::ToneMap::reinhard)), "reinhard"}},
        {"white_point", {2.0, "2.0"}},
        {"directional_angle_scale", {0.5, "0.5"}},
        {"max_lights", {1, "1"}},
        {"max_shadow_proxies", {0, "0"}},
        {"method", {double(int(scene::GiMethod::radiosity)), "radiosity"}},
        {"radiosity.scale", {double(int(scene::HeatScale::half)), "half"}},
        {"radiosity.rays", {7, "7"}},
        {"radiosity.steps", {9, "9"}},
        {"radiosity.epsilon", {1.5, "1.5"}},
        {"radiosity.feedback", {0.25, "0.25"}},
        {"radiosity.accumulate", {3, "3"}},
        {"radiosity.noise", {double(int(scene::NoiseShift::golden)), "golden"}},
        {"radiosity.frames", {5, "5"}},
        {"gather.scale", {double(int(scene::HeatScale::quarter)), "quarter"}},
        {"gather.rays", {7, "7"}},
        {"gather.face_rays", {9, "9"}},
        {"gather.bounces", {3, "3"}},
        {"gather.frames", {5, "5"}},
        {"gather.margin", {2, "2"}},
        {"wall_albedo", {0.3, "0.3"}},
        {"albedo_boost", {2.0, "2.0"}},
        {"baked_intensity", {0.5, "0.5"}},
        {"probe_rays", {8, "8"}},
    };
    const std::map<std::string, std::string> second = {
        {"resolution", "5"}, {"padding", "1.5"}, {"window_snap", "tile"}, {"sun_shadow_method", "dda"}, {"shadow_method", "shadow_map"}, {"proxy_wall_shadows", "full"}, {"heat_rounds", "11"}, {"heat_scale", "quarter"},
        {"diffusion_rate", "0.5"}, {"diffusion_distance", "2.0"}, {"emission_strength", "0.8"},
        {"range_boost", "0.8"}, {"intensity_multiplier", "1.6"}, {"light_softness", "3.0"},
        {"wall_face_exponent", "3.0"}, {"ao.radius", "3.0"}, {"ao.power", "3.5"}, {"ao.strength", "0.7"}, {"tone_map", "aces"},
        {"white_point", "3.0"}, {"directional_angle_scale", "0.8"}, {"max_lights", "2"},
        {"max_shadow_proxies", "1"}, {"method", "heat"}, {"radiosity.scale", "quarter"}, {"radiosity.rays", "5"},
        {"radiosity.steps", "11"}, {"radiosity.epsilon", "2.5"}, {"radiosity.feedback", "0.75"},
        {"radiosity.accumulate", "5"}, {"radiosity.noise", "off"}, {"radiosity.frames", "7"},
        {"gather.scale", "full"}, {"gather.rays", "5"}, {"gather.face_rays", "6"}, {"gather.bounces", "1"},
        {"gather.frames", "7"}, {"gather.margin", "3"}, {"wall_albedo", "0.7"},
        {"albedo_boost", "3.0"}, {"baked_intensity", "2.0"}, {"probe_rays", "12"},
    };
    if (auto it = values.find(key); it != values.end())
        return it->second.first != v ? it->second.second : second.at(key);
    for (const char* toggle : {"per_channel", "segment_check", "ao.enabled", "ao.dither", "ao.walls", "blur",
                               "wall_lighting", "wall_faces.px", "wall_faces.nx", "wall_faces.pz", "wall_faces.nz"})
        if (key == toggle) return v != 0.0 ? "false" : "true";
    return std::string(); // no perturbation known
}

struct FrameRun {
    FrameInputs in;
    PassPlan plan;
    InputKeys inputs;
    std::array<std::uint64_t, pass_count> keys{};
    ReferenceStore store;
};

// A baked light over the rooms, fixed in the world (a window change does not change it),
// and the scene's mixed lights as a bake has them.
void with_bake(FrameInputs& in, const scene::Scene& s) {
    in.baked = gi_test::synthetic_bake(in.walls, {-16, -16}, {64, 64}, 2, 0.01f, std::uint64_t(in.walls.width));
    split_for_bake(in, s);
}

FrameRun run(const scene::Scene& s, const Method* keys_method = nullptr) {
    FrameRun r;
    auto window = compute_window(s.view, s.gi);
    EXPECT_TRUE(window);
    r.in = gather_frame_inputs(s, *window);
    with_bake(r.in, s);
    r.plan = plan_passes(r.in, true);
    r.inputs = input_keys_of(r.in);
    r.keys = keys_method ? derive_keys(*keys_method, r.in, r.plan, r.inputs) : derive_keys(r.in, r.plan, r.inputs);
    execute_reference(r.in, r.plan, r.plan.run, {}, r.store);
    return r;
}

bool same(const Texture& a, const Texture& b) {
    return a.width == b.width && a.height == b.height && a.texels == b.texels;
}

// Textures whose final contents came from a row whose key did not change, but differ: the
// row's key misses something that changed its output. One line per violation.
std::vector<std::string> stale_outputs(const FrameRun& a, const FrameRun& b, const std::string& what) {
    std::vector<std::string> out;
    const Method& m = method(a.in.settings.method);
    for (int t = 0; t < registered_texture_count(); ++t) {
        // The last planned writer of the texture in each run.
        const PassRow* last_a = nullptr;
        const PassRow* last_b = nullptr;
        for (const PassRow* row : m.rows) {
            if (a.plan.run.has(row->pass) && row->outputs(a.in).has(Tex(t))) last_a = row;
            if (b.plan.run.has(row->pass) && row->outputs(b.in).has(Tex(t))) last_b = row;
        }
        if (!last_a || last_a != last_b || a.keys[int(last_a->pass)] != b.keys[int(last_b->pass)]) continue;
        const Texture* ta = a.store.find(Tex(t));
        const Texture* tb = b.store.find(Tex(t));
        if (!ta && !tb) continue; // GPU scratch (heat ping-pong, tap masks): the reference has none
        if (!ta || !tb || !same(*ta, *tb))
            out.push_back(what + ": " + std::string(last_a->name) + " kept its key but its output " + tex_name(Tex(t)) +
                          " changed");
    }
    if (a.plan.run.has(Pass::lit) && b.plan.run.has(Pass::lit) && a.keys[int(Pass::lit)] == b.keys[int(Pass::lit)] &&
        (!a.store.lit || !b.store.lit || a.store.lit->rgb != b.store.lit->rgb))
        out.push_back(what + ": lit kept its key but the lit image changed");
    return out;
}

// The passes a change of `setting` must rerun: the rows listing it, the earlier producers
// they overwrite in place, and everything downstream (by reads) of those.
std::set<Pass> expected_changes(const FrameRun& r, const std::string& setting) {
    const Method& m = method(r.in.settings.method);
    std::set<Pass> changed;
    for (std::size_t i = 0; i < m.rows.size(); ++i) {
        const PassRow& row = *m.rows[i];
        if (!r.plan.run.has(row.pass)) continue;
        for (std::string_view k : row.settings)
            if (k == setting) changed.insert(row.pass);
    }
    for (std::size_t i = 0; i < m.rows.size(); ++i) { // producers overwritten in place
        const PassRow& row = *m.rows[i];
        if (!r.plan.run.has(row.pass)) continue;
        for (std::size_t j = i + 1; j < m.rows.size(); ++j)
            if (changed.count(m.rows[j]->pass) && m.rows[j]->outputs(r.in).intersects(row.outputs(r.in)))
                changed.insert(row.pass);
    }
    std::array<bool, tex_count> dirty{};
    for (const PassRow* row : m.rows) { // downstream, in pipeline order
        if (!r.plan.run.has(row->pass)) continue;
        bool reads_dirty = false;
        for (Tex t : row->reads) reads_dirty |= dirty[std::size_t(t)];
        if (reads_dirty) changed.insert(row->pass);
        const TexSet out = row->outputs(r.in);
        for (int t = 0; t < registered_texture_count(); ++t)
            if (out.has(Tex(t))) dirty[std::size_t(t)] = changed.count(row->pass) > 0;
    }
    return changed;
}

TEST(PassTable, EverySettingHasAPerturbationAndEveryRowSettingExists) {
    const scene::Scene s = every_pass_scene();
    for (const std::string& key : scene::gi_setting_keys()) {
        const auto p = perturbed(key, s.gi);
        EXPECT_TRUE(!p || !p->empty()) << "gi." << key << " has no perturbation in this test: add one";
    }
    const auto keys = scene::gi_setting_keys();
    for (const Method* m : methods())
        for (const PassRow* row : m->rows)
            for (std::string_view k : row->settings)
                EXPECT_NE(std::find(keys.begin(), keys.end(), std::string(k)), keys.end())
                    << row->name << " lists '" << k << "', which is not a gi key";
}

// The passes of a method, as a set.
PassSet rows_of(const Method& m) {
    PassSet set;
    for (const PassRow* row : m.rows) set.add(row->pass);
    return set;
}

class PassTableMethods : public ::testing::TestWithParam<scene::GiMethod> {};

TEST_P(PassTableMethods, EverySettingChangesExactlyTheKeysOfThePassesItAffects) {
    scene::Scene base_scene = every_pass_scene();
    base_scene.gi.method = GetParam();
    const FrameRun base = run(base_scene);
    EXPECT_EQ(base.plan.run, rows_of(method(GetParam()))) << "every row of the method runs";
    for (const std::string& key : scene::gi_setting_keys()) {
        const auto value = perturbed(key, base_scene.gi);
        if (!value || value->empty()) continue;
        scene::Scene s = base_scene;
        auto ok = scene::apply_override(s, "gi." + key + "=" + *value);
        ASSERT_TRUE(ok) << ok.error().message;
        const FrameRun changed = run(s);
        for (const std::string& v : stale_outputs(base, changed, "gi." + key + "=" + *value)) ADD_FAILURE() << v;
        const bool same_frame = changed.plan.run == base.plan.run && changed.in.window == base.in.window &&
                                changed.inputs.lights == base.inputs.lights && changed.inputs.proxies == base.inputs.proxies;
        if (!same_frame) continue; // a plan, window or input change: outputs checked above
        const std::set<Pass> expected = expected_changes(base, key);
        for (int p = 0; p < registered_pass_count(); ++p) {
            const bool key_changed = base.keys[std::size_t(p)] != changed.keys[std::size_t(p)];
            EXPECT_EQ(key_changed, expected.count(Pass(p)) > 0)
                << "gi." << key << "=" << *value << ": the key of " << pass_name(Pass(p))
                << (key_changed ? " changed, but its row does not list the setting and reads nothing that does"
                                : " did not change, but its row (or one upstream) lists the setting");
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, PassTableMethods,
                         ::testing::Values(scene::GiMethod::heat, scene::GiMethod::radiosity, scene::GiMethod::gather),
                         [](const auto& p) { return std::string(method(p.param).name); });

TEST(PassTable, ARowMissingASettingIsCaught) {
    // The direct row without light_softness: its key ignores the setting, its output does not.
    const Method& heat = method(scene::GiMethod::heat);
    const PassRow* direct = find_row(heat, Pass::direct);
    ASSERT_NE(direct, nullptr);
    PassRow forgetful = *direct;
    forgetful.settings = {};
    std::vector<const PassRow*> rows(heat.rows.begin(), heat.rows.end());
    for (const PassRow*& row : rows)
        if (row == direct) row = &forgetful;
    const Method broken{heat.id, "heat without light_softness in direct", rows};
    scene::Scene s = every_pass_scene();
    const FrameRun a = run(s, &broken);
    ASSERT_TRUE(scene::apply_override(s, "gi.light_softness=2.0"));
    const FrameRun b = run(s, &broken);
    const auto stale = stale_outputs(a, b, "gi.light_softness");
    // The baked pass adds the mixed lights into the direct textures in place (its key follows
    // the direct row's), so the rows reading the direct light are the ones caught: emission
    // first, heat and the probes after it.
    bool caught = false;
    for (const std::string& v : stale) caught |= v.find(": emission kept its key") != std::string::npos;
    EXPECT_TRUE(caught) << "the check did not notice the direct row's missing setting";
    EXPECT_GE(stale.size(), 2u);
}

TEST(PassTable, AllocationFollowsThePlannedRowsWrites) {
    scene::Scene s = every_pass_scene();
    FrameRun all = run(s);
    const TexSet written = textures_written(all.in, all.plan);
    EXPECT_TRUE(written.has(Tex::direct_sun)) << "suns: the directional pass writes their own set";
    EXPECT_TRUE(written.has(Tex::ao));
    EXPECT_TRUE(written.has(Tex::blur_temp));
    s.directional_lights.clear();
    ASSERT_TRUE(scene::apply_override(s, "gi.ao.enabled=false"));
    ASSERT_TRUE(scene::apply_override(s, "gi.blur=false"));
    const FrameRun fewer = run(s);
    const TexSet w2 = textures_written(fewer.in, fewer.plan);
    EXPECT_FALSE(w2.has(Tex::direct_sun));
    EXPECT_FALSE(w2.has(Tex::ao));
    EXPECT_FALSE(w2.has(Tex::blur_temp));
    EXPECT_TRUE(w2.has(Tex::direct));
    EXPECT_EQ(fewer.plan.reason[int(Pass::ao)], "AO disabled");
    EXPECT_EQ(fewer.plan.reason[int(Pass::directional)], "no directional lights");
    // The reference holds every contract texture that was written, and nothing else.
    for (int t = 0; t < registered_texture_count(); ++t) {
        const bool held = fewer.store.find(Tex(t)) != nullptr;
        if (held) {
            EXPECT_TRUE(w2.has(Tex(t))) << tex_name(Tex(t)) << " held but not written";
        }
        if (!texture_row(Tex(t)).internal) {
            EXPECT_EQ(held, w2.has(Tex(t))) << tex_name(Tex(t));
        }
    }
}

// Memory is estimated before it is allocated: the per-texel figures docs/gi.md quotes, the
// budget's edge on both storages, and one line naming the need and the limit.
TEST(PassTable, TextureBudget) {
    scene::Scene s = every_pass_scene();
    s.gi.heat_scale = scene::HeatScale::full;
    s.gi.probe_rays = 0; // the live probes' texture is per probe (40 bytes every 2 x 2 tiles), not per texel
    auto window = compute_window(s.view, s.gi);
    ASSERT_TRUE(window);
    FrameInputs in = gather_frame_inputs(s, *window); // without a bake: the figures docs/gi.md quotes
    const PassPlan plan = plan_passes(in, true);
    PassSet live = rows_of(method(scene::GiMethod::heat));
    live.bits &= ~((1u << int(Pass::mixed)) | (1u << int(Pass::baked_sample)) | (1u << int(Pass::baked)) |
                   (1u << int(Pass::probes)));
    ASSERT_EQ(plan.run, live) << "every pass runs but those of a bake and the probes";
    const std::uint64_t texels = std::uint64_t(in.window.width) * std::uint64_t(in.window.height);
    ASSERT_EQ(in.window.width % 4, 0); // no row padding in the per-texel figure
    EXPECT_EQ(texture_bytes(in, plan, TextureStorage::gpu), 166 * texels);
    EXPECT_EQ(texture_bytes(in, plan, TextureStorage::reference), 336 * texels);
    EXPECT_TRUE(check_texture_budget(in, plan, TextureStorage::gpu).ok());
    in.window.width = in.window.height = 4000; // 4000^2 x 166 bytes: 2533 MiB
    auto over = check_texture_budget(in, plan, TextureStorage::gpu);
    ASSERT_FALSE(over.ok());
    EXPECT_EQ(over.error().exit_code, 2);
    EXPECT_EQ(over.error().message,
              "GI window of 4000 x 4000 texels needs 2533 MiB of GPU textures, over the budget of 2048 MiB (docs/gi.md, "
              "\"Memory budget\"); lower gi.resolution or gi.padding");
    in.window.width = in.window.height = 3500;
    EXPECT_TRUE(check_texture_budget(in, plan, TextureStorage::gpu).ok());
    EXPECT_FALSE(check_texture_budget(in, plan, TextureStorage::reference).ok());
    in.window.width = in.window.height = 2500;
    EXPECT_TRUE(check_texture_budget(in, plan, TextureStorage::reference).ok());
}

TEST(PassTable, TexturesByName) {
    for (int t = 0; t < registered_texture_count(); ++t) EXPECT_EQ(texture_by_name(tex_name(Tex(t))), Tex(t));
    EXPECT_FALSE(texture_by_name("no such texture"));
}

} // namespace

// Passes added to the pass table from outside the engine (docs/gi.md, "A new pass"): a
// "tint" row repeated twice with a colour per iteration, and an "accumulate" row that
// converges over frames. Each is a shader (tests/gi/shaders/), a reference function and one
// row; both backends run them through the same sequencer as the built-in rows, and the
// Vulkan results are compared with the reference texel by texel.
//
// Registering rows changes the heat method for the whole process, which is why these tests
// have an executable of their own.
#include "gi_compare.hpp"
#include "test_scenes.hpp"

#include "gpu_test_support.hpp"
#include "shared_renderer.hpp"
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/vulkan/pass_recorder.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern_gi_test_shaders.hpp"

#include <gtest/gtest.h>

#include <glm/vec4.hpp>

using namespace lantern::gi;

namespace {

// ---- the tint row: indirect x colour, twice -----------------------------------------------

constexpr glm::vec3 tint_colours[] = {{1.0f, 0.5f, 0.25f}, {0.5f, 1.0f, 2.0f}};

struct TintParams {
    float r = 0, g = 0, b = 0;
    std::int32_t pad0 = 0, pad1 = 0, pad2 = 0, pad3 = 0, pad4 = 0;
};

// An rgba16f window texture added to the table (called once per name).
Tex add_test_texture(std::string_view name) {
    auto added = add_texture({.name = name, .format = TexFormat::rgba16f});
    EXPECT_TRUE(added.ok()) << added.error().message;
    return *added;
}

Tex tinted_tex() {
    static const Tex t = add_test_texture("tinted");
    return t;
}

void record_tint(vk::PassRecorder& r) {
    const GiWindow& w = r.in.window;
    const Tex source = r.iteration == 0 ? Tex::indirect : tinted_tex();
    r.cmd.bind(r.pipeline<TintParams>("test_tint.comp"));
    r.cmd.push_descriptors(
        lantern::gpu::DescriptorWrites().uniform_texel_buffer(0, r.view(source)).storage_buffer(1, r.buffer(tinted_tex())));
    auto p = r.params<TintParams>(w.width, w.height);
    const glm::vec3 c = tint_colours[r.iteration];
    p.pass = {.r = c.r, .g = c.g, .b = c.b};
    r.cmd.push_constants(p);
    r.dispatch(w.width, w.height);
    r.cmd.barrier_compute_to_compute();
}

void reference_tint(ReferenceContext& c) {
    const Texture& source = c.store.at(c.iteration == 0 ? Tex::indirect : tinted_tex());
    Texture out("tinted", TexFormat::rgba16f, source.width, source.height);
    const glm::vec3 tint = tint_colours[c.iteration];
    for (int y = 0; y < source.height; ++y)
        for (int x = 0; x < source.width; ++x) {
            const float* v = source.at(x, y);
            const float values[4] = {v[0] * tint.r, v[1] * tint.g, v[2] * tint.b, v[3]};
            out.store(x, y, values);
        }
    c.store.put(tinted_tex(), std::move(out));
}

int two_iterations(const FrameInputs&) { return 2; }

// ---- the accumulate row: the emission summed over four frames, a quarter each -------------

constexpr int accumulate_frames = 4;

struct AccumulateParams {
    float weight = 0;
    std::int32_t history = 0, pad0 = 0, pad1 = 0, pad2 = 0, pad3 = 0, pad4 = 0, pad5 = 0;
};

Tex accumulated_tex() {
    static const Tex t = add_test_texture("accumulated");
    return t;
}

void record_accumulate(vk::PassRecorder& r) {
    const GiWindow& w = r.in.window;
    r.cmd.bind(r.pipeline<AccumulateParams>("test_accumulate.comp"));
    r.cmd.push_descriptors(lantern::gpu::DescriptorWrites()
                               .uniform_texel_buffer(0, r.view(Tex::emission))
                               .uniform_texel_buffer(1, r.view(accumulated_tex()))
                               .storage_buffer(2, r.buffer(accumulated_tex())));
    auto p = r.params<AccumulateParams>(w.width, w.height);
    p.pass = {.weight = 1.0f / float(accumulate_frames), .history = r.history};
    r.cmd.push_constants(p);
    r.dispatch(w.width, w.height);
    r.cmd.barrier_compute_to_compute();
}

void reference_accumulate(ReferenceContext& c) {
    const Texture& emission = c.store.at(Tex::emission);
    const Texture* previous = c.history == 0 ? nullptr : c.store.find(accumulated_tex());
    Texture out("accumulated", TexFormat::rgba16f, emission.width, emission.height);
    const float weight = 1.0f / float(accumulate_frames);
    for (int y = 0; y < emission.height; ++y)
        for (int x = 0; x < emission.width; ++x) {
            float values[4];
            for (int k = 0; k < 4; ++k) values[k] = (previous ? previous->at(x, y)[k] : 0.0f) + emission.at(x, y)[k] * weight;
            out.store(x, y, values);
        }
    c.store.put(accumulated_tex(), std::move(out));
}

int four_frames(const FrameInputs&) { return accumulate_frames; }

// ---- registration -------------------------------------------------------------------------

struct Added {
    Pass tint, accumulate;
};

const Added& added_rows() {
    static const Added added = [] {
        static const Tex tint_reads[] = {Tex::indirect, tinted_tex()};
        static const Tex tint_writes[] = {tinted_tex()};
        auto tint = add_row(lantern::scene::GiMethod::heat, Pass::blur,
                            {.name = "tint", .reads = tint_reads, .writes = tint_writes, .inputs = 0,
                             .iterations = two_iterations, .record = record_tint, .reference = reference_tint,
                             .shaders = lantern_gi_test_shaders_spirv});
        EXPECT_TRUE(tint.ok()) << tint.error().message;
        static const Tex accumulate_reads[] = {Tex::emission, accumulated_tex()};
        static const Tex accumulate_writes[] = {accumulated_tex()};
        auto accumulate = add_row(lantern::scene::GiMethod::heat, Pass::emission,
                                  {.name = "accumulate", .reads = accumulate_reads, .writes = accumulate_writes,
                                   .converge_frames = four_frames, .record = record_accumulate,
                                   .reference = reference_accumulate, .shaders = lantern_gi_test_shaders_spirv});
        EXPECT_TRUE(accumulate.ok()) << accumulate.error().message;
        return Added{*tint, *accumulate};
    }();
    return added;
}

// `named` must outlive the inputs (they point at its wall grid).
FrameInputs scene_inputs(const gi_test::NamedScene& named) {
    const lantern::scene::Scene& s = named.scene;
    auto window = compute_window(s.view, s.gi);
    EXPECT_TRUE(window.has_value());
    return gather_frame_inputs(s, *window);
}

std::vector<std::string> row_names() {
    std::vector<std::string> out;
    for (const PassRow* row : method(lantern::scene::GiMethod::heat).rows) out.emplace_back(row->name);
    return out;
}

} // namespace

TEST(PassTableExtension, AddedRowsTakeTheirPlaceInTheMethod) {
    const Added& a = added_rows();
    EXPECT_EQ(row_names(), (std::vector<std::string>{"conduction", "ao", "directional", "direct", "emission",
                                                     "accumulate", "heat", "blur", "tint", "wall_indirect", "probes", "mixed", "baked_sample", "baked", "lit"}));
    EXPECT_STREQ(pass_name(a.tint), "tint");
    EXPECT_EQ(registered_pass_count(), builtin_pass_count + 2);
    EXPECT_EQ(texture_by_name("tinted"), tinted_tex());
    EXPECT_EQ(registered_texture_count(), builtin_tex_count + 2);

    const gi_test::NamedScene rooms = gi_test::comparison_scene("rooms");
    const FrameInputs in = scene_inputs(rooms);
    PassPlan plan = plan_passes(in, true);
    EXPECT_TRUE(plan.run.has(a.tint) && plan.run.has(a.accumulate));
    EXPECT_TRUE(textures_written(in, plan).has(tinted_tex()));
    // Without blur the tint still runs; through Pass::heat it is "not requested".
    EXPECT_EQ(plan_passes(in, false, Pass::heat).reason[int(a.tint)], "not requested");
}

TEST(PassTableExtension, KeysFollowTheAddedRows) {
    const Added& a = added_rows();
    const gi_test::NamedScene rooms = gi_test::comparison_scene("rooms");
    FrameInputs in = scene_inputs(rooms);
    const InputKeys inputs = input_keys_of(in);
    PassPlan plan = plan_passes(in, true);
    const auto base = derive_keys(in, plan, inputs);
    // Upstream of the tint (blur's setting): the tint's key changes, the accumulate's does not.
    FrameInputs changed = in;
    changed.settings.blur = !in.settings.blur;
    PassPlan changed_plan = plan_passes(changed, true);
    const auto keys = derive_keys(changed, changed_plan, inputs);
    EXPECT_NE(keys[int(a.tint)], base[int(a.tint)]);
    EXPECT_EQ(keys[int(a.accumulate)], base[int(a.accumulate)]);
    EXPECT_EQ(keys[int(Pass::emission)], base[int(Pass::emission)]);
}

TEST(PassTableExtension, BadRowsAreRefusedWithAReason) {
    added_rows();
    static const std::string_view unknown_setting[] = {"no_such_setting"};
    auto bad = add_row(lantern::scene::GiMethod::heat, Pass::blur,
                       {.name = "bad", .settings = unknown_setting, .record = record_tint, .reference = reference_tint});
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("not a gi key"), std::string::npos) << bad.error().message;
    auto taken = add_row(lantern::scene::GiMethod::heat, Pass::blur,
                         {.name = "tint", .record = record_tint, .reference = reference_tint});
    ASSERT_FALSE(taken.ok());
    EXPECT_NE(taken.error().message.find("exists"), std::string::npos) << taken.error().message;
    auto no_reference = add_row(lantern::scene::GiMethod::heat, Pass::blur, {.name = "half", .record = record_tint});
    EXPECT_FALSE(no_reference.ok());
    auto bad_name = add_texture({.name = "../escape"});
    ASSERT_FALSE(bad_name.ok());
    EXPECT_NE(bad_name.error().message.find("name"), std::string::npos);
    EXPECT_EQ(registered_pass_count(), builtin_pass_count + 2); // nothing half-added
}

TEST(PassTableExtension, ReferenceTintIsIndirectTimesBothColours) {
    added_rows();
    const gi_test::NamedScene rooms = gi_test::comparison_scene("rooms");
    const FrameInputs in = scene_inputs(rooms);
    const FrameResult r = run_reference_frame(in, plan_passes(in, true));
    const Texture& indirect = r.textures.at("indirect");
    const Texture& tinted = r.textures.at("tinted");
    const glm::vec3 tint = tint_colours[0] * tint_colours[1];
    float brightest = 0.0f;
    for (int y = 0; y < tinted.height; ++y)
        for (int x = 0; x < tinted.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const float expected = quantize_half(indirect.at(x, y)[c] * tint[c]);
                EXPECT_NEAR(tinted.at(x, y)[c], expected, std::abs(expected) * 2e-3f + 1e-6f) << x << ", " << y;
                brightest = std::max(brightest, tinted.at(x, y)[c]);
            }
    EXPECT_GT(brightest, 0.0f) << "the scene has no indirect light: the test would prove nothing";
}

class PassTableExtensionGpu : public lantern::test::GpuTest {};

TEST_F(PassTableExtensionGpu, AddedRowsMatchTheReference) {
    added_rows();
    for (const char* name : {"rooms", "light_edge_cases"}) {
        const gi_test::NamedScene named = gi_test::comparison_scene(name);
        const FrameInputs in = scene_inputs(named);
        const PassPlan plan = plan_passes(in, true);
        auto gpu = run_vulkan_frame(gi_test::shared_renderer(device()), in, plan);
        ASSERT_TRUE(gpu.ok()) << gpu.error().message;
        const FrameResult ref = run_reference_frame(in, plan);
        ASSERT_TRUE(ref.textures.count("tinted") && ref.textures.count("accumulated"));
        ASSERT_EQ(gpu->textures.size(), ref.textures.size());
        for (const auto& [texture, reference] : ref.textures) {
            const float ulps = (texture == "indirect" || texture == "tinted" || texture.rfind("wall_indirect", 0) == 0)
                                   ? 4.0f
                                   : 2.0f;
            auto diff = gi_test::compare_textures(gpu->textures.at(texture), reference, ulps);
            EXPECT_EQ(diff.mismatches, 0u) << gi_test::describe(std::string(name) + " " + texture, diff);
        }
    }
}

// A still scene: the converging row and everything downstream of it run for exactly
// accumulate_frames frames, then nothing is submitted; a light change starts it afresh.
// Both backends, frame by frame, the accumulated texture compared texel by texel.
TEST_F(PassTableExtensionGpu, ConvergingRowStopsSubmittingOnceConverged) {
    const Added& a = added_rows();
    gi_test::NamedScene named = gi_test::comparison_scene("rooms");
    FrameInputs in = scene_inputs(named);
    vk::Renderer& renderer = gi_test::shared_renderer(device());
    ReferenceStore store;
    Convergence convergence;
    std::array<std::uint64_t, pass_count> last_keys{};
    bool first = true;
    auto frame = [&]() -> PassSet {
        PassPlan plan = plan_passes(in, false);
        const auto keys = derive_keys(in, plan, input_keys_of(in), &convergence);
        PassSet run;
        for (int p = 0; p < registered_pass_count(); ++p)
            if (plan.run.has(Pass(p)) && keys[std::size_t(p)] != last_keys[std::size_t(p)]) run.add(Pass(p));
        last_keys = keys;
        // Vulkan.
        EXPECT_TRUE(renderer.prepare(in, plan).ok());
        auto cmd = device().begin("extension frame");
        renderer.begin_frame(cmd);
        if (first) renderer.upload_walls(cmd, in.walls);
        renderer.upload_lights(cmd, in);
        renderer.record_plan(cmd, in, plan, run);
        device().submit(std::move(cmd));
        device().wait_idle();
        // Reference.
        execute_reference(in, plan, run, {}, store);
        convergence.advance(run);
        first = false;
        auto diff = gi_test::compare_textures(renderer.read_back(accumulated_tex()), store.at(accumulated_tex()), 2.0f);
        EXPECT_EQ(diff.mismatches, 0u) << gi_test::describe("accumulated", diff);
        return run;
    };
    const PassSet first_frame = frame();
    EXPECT_TRUE(first_frame.has(Pass::direct) && first_frame.has(a.accumulate));
    for (int f = 1; f < accumulate_frames; ++f) {
        const PassSet run = frame();
        EXPECT_TRUE(run.has(a.accumulate)) << "frame " << f;
        EXPECT_FALSE(run.has(Pass::direct) || run.has(Pass::heat)) << "frame " << f << ": upstream rows reran";
    }
    for (int f = 0; f < 3; ++f) EXPECT_EQ(frame().bits, 0u) << "a converged, still scene submitted work";
    // Converged: four quarters of the emission.
    const Texture& emission = store.at(Tex::emission);
    const Texture& accumulated = store.at(accumulated_tex());
    for (int y = 0; y < emission.height; ++y)
        for (int x = 0; x < emission.width; ++x)
            EXPECT_NEAR(accumulated.at(x, y)[0], emission.at(x, y)[0], std::abs(emission.at(x, y)[0]) * 4e-3f + 1e-6f);
    // A light moves: the direct light and the accumulation start again.
    ASSERT_FALSE(in.point_lights.empty());
    in.point_lights[0].position_radius.x += 0.5f;
    const PassSet moved = frame();
    EXPECT_TRUE(moved.has(Pass::direct) && moved.has(a.accumulate));
    int frames = 1;
    while (frame().has(a.accumulate)) ASSERT_LE(++frames, accumulate_frames);
    EXPECT_EQ(frames, accumulate_frames);
}

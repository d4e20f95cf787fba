// One chunk's bake and its key (bake.hpp).
#include "lantern/bake/bake.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/core/hash.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/gather.hpp"
#include "lantern/gi/radiosity.hpp"
#include "lantern/transport/model.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/passes.hpp"
#include "lantern/gi/reference.hpp"
#include "lantern/gi/window.hpp"
#include "lantern/scene/day.hpp"
#include "lantern/scene/loader.hpp"

#include <algorithm>
#include <cmath>

namespace lantern::bake {
namespace {

using scene::LightMode;

int floor_div(int a, int b) { // b > 0
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

// The scene's gi settings as the bake runs them: the gather method at the bake's
// resolution and margin, every face, no blur (the cache holds the solve itself).
scene::GiSettings bake_gi(const scene::Scene& s, const BakeSettings& b) {
    scene::GiSettings gi = s.gi;
    gi.method = scene::GiMethod::gather;
    gi.resolution = b.resolution;
    gi.padding = 1.0f;
    gi.window_snap = scene::WindowSnap::tile;
    gi.gather.margin = b.margin;
    gi.gather.rays = b.rays;
    gi.gather.face_rays = b.face_rays;
    // The live method's bounces over its frames, in one frame: the ground is gathered once.
    gi.gather.bounces = std::min(64, gi.gather.bounces * gi.gather.frames);
    gi.gather.frames = 1;
    gi.gather.scale = scene::HeatScale::full;
    gi.wall_lighting = true;
    gi.wall_faces = {};
    gi.blur = false;
    gi.baked_intensity = 1.0f; // a run-time knob: the bake is the same whatever it is
    gi.probe_rays = 0;         // live probes: the frame's, never the bake's (it captures its own)
    gi.max_lights = std::max(gi.max_lights, 1 << 20); // the bake is not a frame: no cap
    gi.max_shadow_proxies = std::max(gi.max_shadow_proxies, 1 << 20);
    return gi;
}

scene::OrthoView chunk_view(ChunkId c) {
    const float half = float(chunk_tiles) / 2.0f;
    return {glm::vec2(float(c.x * chunk_tiles) + half, float(c.z * chunk_tiles) + half),
            glm::vec2(float(chunk_tiles))};
}

// Which lights a solve sees.
enum class Lights { bounce, direct }; // bounce: mixed and baked; direct: baked only

bool keeps(LightMode mode, Lights which) {
    return which == Lights::bounce ? mode != LightMode::realtime : mode == LightMode::baked;
}

// The light a solve sees of `l`: in the bounce solve, scaled by its indirect multiplier
// (seed 004: 0 = no GI).
template <typename Light>
Light as_solved(Light l, Lights which) {
    if (which == Lights::bounce) l.intensity *= l.indirect;
    return l;
}

// Which glow a solve carries (seed 004's pulsing emission is baked apart): the steady
// materials' with the lights, the pulsing materials' alone without any light, or none (a sun
// key's solve: the sun alone).
enum class Glow { steady, pulsing, none };

// The mixed sun whose bounce is baked at the day's keys (BakeSettings::sun_keys): the scene's
// first mixed sun; nullptr without keys.
const scene::DirectionalLight* keyed_sun(const scene::Scene& s, const BakeSettings& b) {
    if (b.sun_keys < 2) return nullptr;
    for (const auto& l : s.directional_lights)
        if (l.mode == LightMode::mixed) return &l;
    return nullptr;
}

// The scene without its walls (the solve views the caller's), with the lights `which`
// keeps, the static shadow proxies and the bake's gi settings.
scene::Scene lights_of(const scene::Scene& s, const BakeSettings& b, Lights which, Glow glow = Glow::steady) {
    scene::Scene out;
    out.wall_height = s.wall_height;
    out.gi = bake_gi(s, b);
    out.view = s.view;
    out.materials = s.materials;
    for (scene::Material& m : out.materials) // realtime glow stays live: the bake leaves it out
        if (glow == Glow::none || m.emission_gi == scene::EmissionGi::realtime || (m.pulse > 0.0f) != (glow == Glow::pulsing))
            m.emission = glm::vec3(0.0f);
    for (const auto& p : s.shadow_proxies) // seed 004's static flag: moving proxies shadow the live light only
        if (p.is_static) out.shadow_proxies.push_back(p);
    if (glow != Glow::steady) return out;
    for (const auto& l : s.point_lights)
        if (keeps(l.mode, which)) out.point_lights.push_back(as_solved(l, which));
    for (const auto& l : s.emissive_lights)
        if (keeps(l.mode, which)) out.emissive_lights.push_back(as_solved(l, which));
    const scene::DirectionalLight* keyed = keyed_sun(s, b); // baked at the keys instead
    for (const auto& l : s.directional_lights)
        if (keeps(l.mode, which) && &l != keyed) out.directional_lights.push_back(as_solved(l, which));
    return out;
}

struct ChunkProblem {
    gi::GiWindow window;
    glm::ivec2 offset{0};  // window texel of the chunk's texel (0, 0)
    gi::FrameInputs bounce; // mixed and baked lights, the glow of steady materials
    gi::FrameInputs direct; // baked lights
    std::optional<gi::FrameInputs> pulse; // the glow of pulsing materials alone (when the scene has any)
    std::vector<gi::FrameInputs> sun_keys; // the keyed sun alone at each key (BakeSettings::sun_keys)
};

gi::FrameInputs inputs_for(const scene::Scene& s, const BakeSettings& b, Lights which, const gi::GiWindow& w,
                           Glow glow = Glow::steady) {
    gi::FrameInputs in = gi::gather_frame_inputs(lights_of(s, b, which, glow), w);
    in.walls = gi::WallView::of(s.walls);
    return in;
}

ChunkProblem make_problem(const scene::Scene& s, ChunkId c, const BakeSettings& b) {
    ChunkProblem p;
    const scene::GiSettings gi = bake_gi(s, b);
    std::optional<gi::GiWindow> w = gi::compute_window(chunk_view(c), gi);
    LANTERN_ASSERT(w.has_value(), "a chunk's window is always valid");
    p.window = *w;
    p.offset = {int(std::lround((float(c.x * chunk_tiles) - w->view.min_x) * float(b.resolution))),
                int(std::lround((float(c.z * chunk_tiles) - w->view.min_z) * float(b.resolution)))};
    p.bounce = inputs_for(s, b, Lights::bounce, p.window);
    p.direct = inputs_for(s, b, Lights::direct, p.window);
    if (scene::pulse_frequency(s.materials) > 0.0f) p.pulse = inputs_for(s, b, Lights::bounce, p.window, Glow::pulsing);
    if (const scene::DirectionalLight* sun = keyed_sun(s, b)) {
        scene::Scene lit = lights_of(s, b, Lights::bounce, Glow::none); // no light, no glow
        for (int k = 0; k < b.sun_keys; ++k) {
            // The sun alone at the key's place on the day's path, white at intensity 1: the run
            // time scales it by the sun's colour.
            scene::DirectionalLight key = *sun;
            key.direction = scene::day_sun_direction(scene::sun_key_time(k, b.sun_keys));
            key.color = glm::vec3(1.0f);
            key.intensity = 1.0f;
            lit.directional_lights = {as_solved(key, Lights::bounce)};
            gi::FrameInputs in = gi::gather_frame_inputs(lit, p.window);
            in.walls = gi::WallView::of(s.walls);
            p.sun_keys.push_back(std::move(in));
        }
    }
    return p;
}

// Whether a glowing wall lies in the solve's window (materials elsewhere send it nothing).
bool glows_in(const gi::FrameInputs& in) {
    if (!gi::has_emissive_materials(in)) return false;
    const gi::GiWindow& w = in.window;
    const int x0 = int(std::floor(w.view.min_x)), z0 = int(std::floor(w.view.min_z));
    const int x1 = int(std::ceil(w.view.min_x + w.view.width)), z1 = int(std::ceil(w.view.min_z + w.view.height));
    for (int z = z0; z < z1; ++z)
        for (int x = x0; x < x1; ++x) {
            const std::uint8_t cell = in.walls.cell(x, z);
            if (cell == 0) continue;
            const glm::vec4 e = gi::material_of(in, cell).emission;
            if (e.r > 0.0f || e.g > 0.0f || e.b > 0.0f) return true;
        }
    return false;
}

bool has_light(const gi::FrameInputs& in) {
    return !in.point_lights.empty() || !in.emissive_lights.empty() || !in.directional_lights.empty();
}

// How far beyond the window the walls can change its light: the longest light radius and
// sun shadow reach, plus a wall height for the suns' tall walls.
int wall_reach(const gi::FrameInputs& in) {
    float reach = 0.0f;
    for (const auto& l : in.point_lights) reach = std::max(reach, l.position_radius.z);
    for (const auto& l : in.directional_lights)
        reach = std::max(reach, l.direction_base.w * l.color_multiplier.w + in.wall_height);
    return int(std::ceil(std::min(reach, float(1 << 20)))) + 1;
}

void hash_walls(Hasher& h, const scene::WallGrid& g, glm::ivec2 lo, glm::ivec2 hi) {
    const int c0 = std::max(lo.x - g.origin.x, 0), c1 = std::min(hi.x - g.origin.x, g.width - 1);
    const int r0 = std::max(lo.y - g.origin.y, 0), r1 = std::min(hi.y - g.origin.y, g.height - 1);
    h.add(c0 + g.origin.x).add(c1 + g.origin.x).add(r0 + g.origin.y).add(r1 + g.origin.y);
    for (int r = r0; r <= r1 && c0 <= c1; ++r)
        h.add_bytes(&g.cells[std::size_t(r) * std::size_t(g.width) + std::size_t(c0)], std::size_t(c1 - c0 + 1));
}

void hash_inputs(Hasher& h, const gi::FrameInputs& in) {
    h.add(gi::hash_window(in.window))
        .add_span(std::span(in.point_lights))
        .add_span(std::span(in.emissive_lights))
        .add_span(std::span(in.directional_lights))
        .add_span(std::span(in.proxies))
        .add_span(std::span(in.materials));
}

// Copies the chunk's texels of a window texture (rgb) out.
std::vector<float> crop(const gi::Texture* t, const ChunkProblem& p, int side) {
    std::vector<float> out(std::size_t(side) * std::size_t(side) * 3, 0.0f);
    if (!t) return out;
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const float* v = t->at(p.offset.x + x, p.offset.y + y);
            std::copy(v, v + 3, out.begin() + (std::ptrdiff_t(y) * side + x) * 3);
        }
    return out;
}

// Each light of `in` alone, with the direction its light arrives from at a point.
struct SingleSource {
    gi::FrameInputs in;
    glm::vec2 position{0.0f}; // point and emissive lights
    bool sun = false;
    float sun_angle = 0.0f;   // suns: the angle their light arrives from
};

std::vector<SingleSource> single_sources(const gi::FrameInputs& in) {
    std::vector<SingleSource> out;
    gi::FrameInputs empty = in;
    empty.point_lights.clear();
    empty.emissive_lights.clear();
    empty.directional_lights.clear();
    for (const auto& l : in.point_lights) {
        out.push_back({empty, glm::vec2(l.position_radius), false, 0.0f});
        out.back().in.point_lights = {l};
    }
    for (const auto& l : in.emissive_lights) {
        out.push_back({empty, glm::vec2(l.position_radius), false, 0.0f});
        out.back().in.emissive_lights = {l};
    }
    for (const auto& l : in.directional_lights) {
        out.push_back({empty, glm::vec2(0.0f), true, std::atan2(-l.direction_base.z, -l.direction_base.x)});
        out.back().in.directional_lights = {l};
    }
    return out;
}

// What the probes' rays see of the bounce solve: the faces' direct light, their indirect
// light (none for seed 002's one bounce) and the weighting of seed 002's bake.
struct BounceField {
    gi::FaceTextures direct{};
    const gi::Texture* faces = nullptr;
    gi::GatherWeighting weighting;
};

// The light probe at `pos`: the bounce solve's radiance by rays (`field`, after the solve;
// none without one) and the baked lights' direct light as point sources.
CircularHarmonics capture_probe(const gi::FrameInputs& bounce, const BounceField* field,
                                const std::vector<SingleSource>& sources, glm::vec2 pos, int rays,
                                ProbeSamples* samples = nullptr) {
    constexpr float two_pi = 6.28318531f;
    CircularHarmonics h;
    if (field) {
        const gi::GatherFrame f = gi::gather_frame(bounce);
        const glm::vec2 rel = (pos - glm::vec2(f.origin_tile)) * float(gi::gather_unit);
        const glm::ivec2 fixed(int(std::lround(rel.x)), int(std::lround(rel.y)));
        const glm::ivec2 cell = fixed / gi::gather_unit; // inside the window: non-negative
        const std::vector<glm::ivec2>& dirs = gi::radiosity_directions();
        for (int k = 0; k < rays; ++k) {
            const int index = (k * 4096) / rays;
            const glm::ivec2 d = dirs[std::size_t(index)];
            const gi::GatherHit hit = gi::gather_trace(bounce, f, fixed, cell, d);
            if (hit.face < 0) continue;
            const gi::GatherWeighting& w = field->weighting;
            const glm::vec3 radiance =
                gi::gather_radiosity(bounce, field->direct, field->faces, hit.face, hit.texel, w.ambient) *
                (0.5f * w.weight(hit.distance(d)));
            h.add_ray(two_pi * float(index) / 4096.0f, radiance, two_pi / float(rays));
            if (samples) samples->add(two_pi * float(index) / 4096.0f, radiance * (two_pi / float(rays)));
        }
    }
    for (const SingleSource& s : sources) {
        const glm::vec3 fluence = transport::direct_fluence(s.in, pos);
        if (fluence == glm::vec3(0.0f)) continue;
        const glm::vec2 to = s.position - pos;
        h.add_delta(s.sun ? s.sun_angle : std::atan2(to.y, to.x), fluence);
        if (samples) samples->add(s.sun ? s.sun_angle : std::atan2(to.y, to.x), fluence);
    }
    return h;
}

// Seed 002's one-bounce bake of the bounce lights (BakeSolver::seed002) into `store`: the
// faces' direct light, then the gather's face and ground steps once, weighted, from it alone.
void solve_seed002(const gi::FrameInputs& in, const BakeSettings& b, gi::ReferenceStore& store) {
    gi::DirectTextures d = gi::reference_direct(in);
    gi::reference_directional(in, d);
    gi::FaceTextures direct{};
    for (int face = 0; face < 4; ++face) {
        gi::Texture& t = d.wall_direct[std::size_t(face)];
        if (t.width == 0) continue;
        const gi::Tex tex = gi::Tex(int(gi::Tex::wall_direct_px) + face);
        store.put(tex, std::move(t));
        direct[std::size_t(face)] = store.find(tex);
    }
    const gi::GatherWeighting weighting{b.falloff, b.ambient};
    const gi::Texture faces = gi::reference_gather_faces(in, direct, nullptr, {}, weighting);
    std::array<gi::Texture, 4> fill = gi::reference_gather_fill(in, faces);
    for (int face = 0; face < 4; ++face)
        if (fill[std::size_t(face)].width > 0)
            store.put(gi::Tex(int(gi::Tex::wall_indirect_px) + face), std::move(fill[std::size_t(face)]));
    const glm::ivec2 size = gi::gather_face_size(in);
    const gi::Texture none("gather_face", gi::TexFormat::rgba16f, size.x, size.y); // no indirect: one bounce
    const gi::Texture ground = gi::reference_gather_ground(in, direct, none, {}, weighting);
    store.put(gi::Tex::indirect, gi::reference_upsample(in, gi::gather_grid(in), ground));
}

void add(std::vector<float>& to, const std::vector<float>& from) {
    for (std::size_t i = 0; i < to.size(); ++i) to[i] += from[i];
}

} // namespace

const char* solver_name(BakeSolver solver) {
    return solver == BakeSolver::seed002 ? "seed002" : "gather";
}

Result<void> validate_settings(const BakeSettings& s) {
    if (s.resolution < 1 || s.resolution > 16)
        return make_error("bake.resolution: must be an integer in [1, 16], got " + std::to_string(s.resolution));
    if (s.margin < 0 || s.margin > 64)
        return make_error("bake.margin: must be an integer in [0, 64], got " + std::to_string(s.margin));
    if (s.rays < 1 || s.rays > 1024)
        return make_error("bake.rays: must be an integer in [1, 1024], got " + std::to_string(s.rays));
    if (s.face_rays < 1 || s.face_rays > 1024)
        return make_error("bake.face_rays: must be an integer in [1, 1024], got " + std::to_string(s.face_rays));
    if (s.solver != BakeSolver::gather && s.solver != BakeSolver::seed002)
        return make_error("bake.solver: unknown solver " + std::to_string(int(s.solver)));
    if (!(s.falloff >= 1.0f / 64.0f && s.falloff <= 4096.0f))
        return make_error("bake.falloff: must be a number in [0.015625, 4096] tiles, got " + std::to_string(s.falloff));
    if (!(s.ambient >= 0.0f && s.ambient <= 1000.0f))
        return make_error("bake.ambient: must be a number in [0, 1000], got " + std::to_string(s.ambient));
    if (!(s.eps >= 0.0f && s.eps <= 1000.0f))
        return make_error("bake.eps: must be a number in [0, 1000], got " + std::to_string(s.eps));
    if (s.max_level < 0 || s.max_level > 3)
        return make_error("bake.max_level: must be an integer in [0, 3], got " + std::to_string(s.max_level));
    if (s.sun_keys == 1 || s.sun_keys < 0 || s.sun_keys > 32)
        return make_error("bake.sun_keys: must be 0 or an integer in [2, 32], got " + std::to_string(s.sun_keys));
    if (s.density.size() > std::size_t(scene::max_bake_density_regions))
        return make_error("bake.density: " + std::to_string(s.density.size()) + " regions, above the limit of " +
                          std::to_string(scene::max_bake_density_regions));
    for (std::size_t i = 0; i < s.density.size(); ++i) {
        const scene::BakeDensity& d = s.density[i];
        const std::string at = "bake.density[" + std::to_string(i) + "]";
        if (d.resolution < 1 || d.resolution > 16)
            return make_error(at + ".resolution: must be an integer in [1, 16], got " + std::to_string(d.resolution));
        if (d.max.x < d.min.x || d.max.y < d.min.y) return make_error(at + ".max: must not be below min in x or z");
    }
    return {};
}

std::vector<ChunkId> scene_chunks(const scene::Scene& s) {
    std::vector<ChunkId> out;
    if (s.walls.width <= 0 || s.walls.height <= 0) return out;
    const int x0 = floor_div(s.walls.origin.x, chunk_tiles), x1 = floor_div(s.walls.origin.x + s.walls.width - 1, chunk_tiles);
    const int z0 = floor_div(s.walls.origin.y, chunk_tiles), z1 = floor_div(s.walls.origin.y + s.walls.height - 1, chunk_tiles);
    for (int z = z0; z <= z1; ++z)
        for (int x = x0; x <= x1; ++x) out.push_back({x, z});
    return out;
}

std::vector<ChunkId> shard_of(const std::vector<ChunkId>& chunks, int shard, int shards) {
    std::vector<ChunkId> out;
    for (std::size_t i = std::size_t(shard); i < chunks.size(); i += std::size_t(shards)) out.push_back(chunks[i]);
    return out;
}

BakeSettings chunk_settings(const BakeSettings& settings, ChunkId chunk) {
    BakeSettings out = settings;
    out.resolution = settings.resolution_at(chunk.x, chunk.z);
    out.density.clear();
    return out;
}

std::uint64_t chunk_key(const scene::Scene& s, ChunkId c, const BakeSettings& world_settings) {
    const BakeSettings b = chunk_settings(world_settings, c);
    const ChunkProblem p = make_problem(s, c, b);
    Hasher h;
    const std::string solver = std::string("lantern-bake/") + solver_name(b.solver);
    h.add_bytes(solver.c_str(), solver.size() + 1).add(bake_code_version).add(b.resolution).add(b.margin).add(b.rays).add(b.face_rays);
    if (b.solver == BakeSolver::seed002) h.add(b.falloff).add(b.ambient);
    if (!b.directional) h.add(std::uint32_t(0x4e44)); // (directional keys stay as they were)
    h.add(c.x).add(c.z);
    for (double v : scene::gi_setting_values(bake_gi(s, b))) h.add(v);
    h.add(s.wall_height);
    hash_inputs(h, p.bounce);
    hash_inputs(h, p.direct);
    if (p.pulse) hash_inputs(h, *p.pulse);
    if (!p.sun_keys.empty()) h.add(std::uint32_t(0x53554e4b)).add(b.sun_keys); // (keys without them stay as they were)
    for (const gi::FrameInputs& key : p.sun_keys) hash_inputs(h, key);
    // The walls the light can meet: the window and every light's reach around it.
    int reach = std::max(wall_reach(p.bounce), wall_reach(p.direct));
    for (const gi::FrameInputs& key : p.sun_keys) reach = std::max(reach, wall_reach(key));
    const glm::ivec2 lo(int(std::floor(p.window.view.min_x)), int(std::floor(p.window.view.min_z)));
    const glm::ivec2 hi(int(std::ceil(p.window.view.min_x + p.window.view.width)),
                        int(std::ceil(p.window.view.min_z + p.window.view.height)));
    hash_walls(h, s.walls, lo - reach, hi + reach);
    return h.value();
}

ChunkBake bake_chunk(const scene::Scene& s, ChunkId c, const BakeSettings& world_settings, std::vector<ProbeSamples>* samples) {
    const BakeSettings b = chunk_settings(world_settings, c);
    ChunkBake out;
    if (samples) samples->assign(std::size_t(chunk_probes * chunk_probes), ProbeSamples{});
    out.id = c;
    out.key = chunk_key(s, c, b);
    out.resolution = b.resolution;
    const ChunkProblem p = make_problem(s, c, b);
    const bool seed002 = b.solver == BakeSolver::seed002;
    // Seed 002's ambient fill lights every wall: then every chunk with a wall in reach bakes.
    const bool bounce = has_light(p.bounce) || glows_in(p.bounce) || (seed002 && b.ambient > 0.0f);
    const bool direct = has_light(p.direct);
    const bool pulse = p.pulse && glows_in(*p.pulse);
    if (!bounce && !direct && !pulse && p.sun_keys.empty()) return out; // no baked light reaches the chunk
    out.empty = false;
    out.probes.assign(std::size_t(chunk_probes * chunk_probes), CircularHarmonics{});
    out.probe_valid.assign(out.probes.size(), 0);
    const int side = out.side();
    // One bounce solve (the steady light, or the pulsing glow alone): its ground and faces
    // cropped to the chunk, and the probes' rays into it (with `sources`, the baked lights'
    // direct light too).
    auto solve = [&](const gi::FrameInputs& in, float ambient, std::vector<float>& ground, std::array<std::vector<float>, 4>& faces,
                     std::vector<CircularHarmonics>& probes, const std::vector<SingleSource>& sources, bool any, bool keep_samples) {
        gi::ReferenceStore store;
        BounceField field;
        if (any && !seed002) {
            // The gather converged (the live method's frames x bounces, in one frame).
            gi::Convergence convergence;
            for (int f = 0; f < in.settings.gather.frames; ++f) {
                gi::PassPlan plan = gi::plan_passes(in, false);
                gi::derive_keys(in, plan, gi::input_keys_of(in), &convergence);
                gi::execute_reference(in, plan, plan.run, {}, store);
                convergence.advance(plan.run);
            }
            for (int face = 0; face < 4; ++face)
                field.direct[std::size_t(face)] = store.find(gi::Tex(int(gi::Tex::wall_direct_px) + face));
            field.faces = store.find(gi::gather_face_target(in.settings.gather.bounces - 1));
        } else if (any) {
            BakeSettings with = b;
            with.ambient = ambient;
            solve_seed002(in, with, store);
            for (int face = 0; face < 4; ++face)
                field.direct[std::size_t(face)] = store.find(gi::Tex(int(gi::Tex::wall_direct_px) + face));
            field.weighting = {b.falloff, ambient};
        }
        ground = crop(store.find(gi::Tex::indirect), p, side);
        for (int f = 0; f < 4; ++f)
            faces[std::size_t(f)] = crop(store.find(gi::Tex(int(gi::Tex::wall_indirect_px) + f)), p, side);
        probes.assign(std::size_t(chunk_probes * chunk_probes), CircularHarmonics{});
        for (int j = 0; j < chunk_probes; ++j)
            for (int i = 0; i < chunk_probes; ++i) {
                const glm::ivec2 tile(c.x * chunk_tiles + i * probe_spacing, c.z * chunk_tiles + j * probe_spacing);
                if (s.walls.is_wall_tile(tile.x, tile.y)) continue;
                const std::size_t k = std::size_t(j * chunk_probes + i);
                probes[k] = capture_probe(in, any ? &field : nullptr, sources, glm::vec2(tile) + 0.5f, b.rays,
                                          samples && keep_samples ? &(*samples)[k] : nullptr);
                if (!b.directional) // seed 004's non-directional bake: the fluence alone
                    for (std::size_t h = 1; h < probes[k].c.size(); ++h) probes[k].c[h] = glm::vec3(0.0f);
                out.probe_valid[k] = 1;
            }
    };
    // Light probes: rays into the bounce solve, the baked lights as point sources.
    solve(p.bounce, b.ambient, out.ground, out.faces, out.probes, single_sources(p.direct), bounce, true);
    // Seed 004's pulsing emission: the pulsing glow's light alone, scaled at run time (no
    // ambient fill: the steady part holds it once).
    if (pulse) solve(*p.pulse, 0.0f, out.pulse.ground, out.pulse.faces, out.pulse.probes, {}, true, false);
    // Seed 004's moving sun: its bounce at each key, scaled and blended at run time.
    out.sun_keys.resize(p.sun_keys.size());
    for (std::size_t k = 0; k < p.sun_keys.size(); ++k) {
        LightPart& part = out.sun_keys[k];
        solve(p.sun_keys[k], 0.0f, part.ground, part.faces, part.probes, {}, true, false);
    }
    // Direct light of the baked lights, exactly as the live direct passes compute it.
    if (direct) {
        gi::DirectTextures d = gi::reference_direct(p.direct);
        gi::reference_directional(p.direct, d);
        add(out.ground, crop(&d.direct, p, side));
        for (int f = 0; f < 4; ++f)
            if (d.wall_direct[std::size_t(f)].width > 0)
                add(out.faces[std::size_t(f)], crop(&d.wall_direct[std::size_t(f)], p, side));
    }
    return out;
}

} // namespace lantern::bake

// The game's baked light (baking.hpp).
#include "lantern/game/baking.hpp"

#include "lantern/components/components.hpp"
#include "lantern/core/clock.hpp"
#include "lantern/core/hash.hpp"
#include "lantern/core/log.hpp"
#include "lantern/core/machine.hpp"
#include "lantern/game/game_components.hpp"
#include "lantern/profile/profiler.hpp"
#include "lantern/scene/day.hpp"
#include "lantern/scene/loader.hpp"
#include "lantern/systems/gi_frame.hpp"
#include "lantern/systems/streaming.hpp"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <filesystem>

#include <glm/common.hpp>

namespace lantern::game {

using systems::chunk_size;
using systems::floor_div;

std::uint64_t chunk_id_key(bake::ChunkId c) { return (std::uint64_t(std::uint32_t(c.x)) << 32) | std::uint32_t(c.z); }

bake::CircularHarmonics BakedChunks::probes_at(glm::vec2 p) const {
    // With the pulsing glow in a chunk, its probe is the steady one plus the pulsing one scaled.
    std::array<bake::CircularHarmonics, 4> summed;
    int used = 0;
    auto probe = [&](int ix, int iz) -> const bake::CircularHarmonics* {
        const int tx = ix * bake::probe_spacing, tz = iz * bake::probe_spacing;
        const bake::ChunkId c{floor_div(tx, bake::chunk_tiles), floor_div(tz, bake::chunk_tiles)};
        auto it = chunks.find(chunk_id_key(c));
        if (it == chunks.end() || it->second->empty) return nullptr;
        const int i = (tx - c.x * bake::chunk_tiles) / bake::probe_spacing, j = (tz - c.z * bake::chunk_tiles) / bake::probe_spacing;
        const std::size_t k = std::size_t(j * bake::chunk_probes + i);
        const bake::ChunkBake& b = *it->second;
        if (!b.probe_valid[k]) return nullptr;
        const bool keyed = sun.key >= 0 && std::size_t(sun.key) + 1 < b.sun_keys.size();
        if (!b.pulses() && !keyed) return &b.probes[k];
        bake::CircularHarmonics& h = summed[std::size_t(used++)];
        h = b.probes[k];
        if (b.pulses()) h += b.pulse.probes[k] * pulse;
        if (keyed) { // per channel: the sun's colour x the two keys blended (gi::BakedLight::light)
            const bake::CircularHarmonics& below = b.sun_keys[std::size_t(sun.key)].probes[k];
            const bake::CircularHarmonics& above = b.sun_keys[std::size_t(sun.key) + 1].probes[k];
            for (std::size_t n = 0; n < h.c.size(); ++n)
                h.c[n] += (sun.color * (1.0f - sun.blend)) * below.c[n] + (sun.color * sun.blend) * above.c[n];
        }
        return &h;
    };
    return bake::interpolate_probes(probe, p);
}

struct WorldBaker::Job {
    enum class Kind { chunk, compose } kind = Kind::chunk;
    bake::ChunkId id;
    std::uint64_t inputs = 0;
    scene::Scene region; // chunk: the walls, materials, lights and proxies it sees
    // compose: the resident chunks' bakes over the walls of their rectangle
    scene::WallGrid walls;
    std::vector<std::shared_ptr<const bake::ChunkBake>> bakes;
};

struct WorldBaker::Result {
    Job::Kind kind = Job::Kind::chunk;
    bake::ChunkId id;
    std::uint64_t inputs = 0;
    std::shared_ptr<const bake::ChunkBake> bake;
    bool reused = false;
    double ms = 0.0;
    std::string warning;
    std::shared_ptr<const gi::BakedLight> light;
    std::vector<std::shared_ptr<const bake::ChunkBake>> bakes; // compose: what the light holds
};

WorldBaker::WorldBaker(BakerOptions options) : options_(std::move(options)) {
    thread_ = std::thread([this] { run(); });
}

WorldBaker::~WorldBaker() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
        jobs_.clear();
    }
    wake_.notify_all();
    thread_.join();
}

void WorldBaker::run() {
    // The lowest priority: the frame (and lavapipe's threads) go first.
    lower_thread_priority();
    profile::set_thread_name("baker");
    for (;;) {
        std::unique_ptr<Job> job;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [this] { return stop_ || !jobs_.empty(); });
            if (stop_) return;
            job = std::move(jobs_.front());
            jobs_.pop_front();
            ++running_;
        }
        auto result = std::make_unique<Result>();
        result->kind = job->kind;
        result->id = job->id;
        result->inputs = job->inputs;
        const std::int64_t start = now_ns();
        if (job->kind == Job::Kind::chunk) {
            LANTERN_PROFILE_SCOPE("bake_chunk");
            const std::uint64_t key = bake::chunk_key(job->region, job->id, options_.settings);
            std::string why;
            std::optional<bake::ChunkBake> cached;
            if (!options_.cache_dir.empty()) cached = bake::load_chunk(options_.cache_dir, job->id, key, &why);
            if (cached) {
                result->reused = true;
                result->bake = std::make_shared<const bake::ChunkBake>(std::move(*cached));
            } else {
                if (!options_.cache_dir.empty() && !why.ends_with(": missing")) result->warning = why + "; baking it again";
                auto baked = std::make_shared<const bake::ChunkBake>(bake::bake_chunk(job->region, job->id, options_.settings));
                if (!options_.cache_dir.empty()) { // the folder when the first file goes in
                    std::error_code ec;
                    std::filesystem::create_directories(options_.cache_dir, ec);
                    if (auto ok = bake::save_chunk(options_.cache_dir, *baked); !ok) result->warning = ok.error().message;
                }
                result->bake = std::move(baked);
            }
        } else {
            LANTERN_PROFILE_SCOPE("bake_compose");
            std::vector<const bake::ChunkBake*> pointers;
            for (const auto& b : job->bakes) pointers.push_back(b.get());
            std::string why; // the resident chunks always fit one atlas; said if they ever do not
            result->light = bake::runtime_light(pointers, gi::WallView::of(job->walls), options_.settings.eps,
                                                options_.settings.max_level, &why);
            if (!why.empty()) result->warning = why;
            result->bakes = std::move(job->bakes);
        }
        result->ms = double(now_ns() - start) * 1e-6;
        const bool baked_one = job->kind == Job::Kind::chunk && !result->reused;
        const double result_ms = result->ms;
        std::unique_lock lock(mutex_);
        results_.push_back(std::move(result));
        --running_;
        idle_.notify_all();
        // Paced while the game plays: after a bake, rest `pace` times as long (the two cores
        // are the frame's and lavapipe's; a burst of bakes as the player walks into new
        // chunks would slow every frame it overlaps). Not at start-up (finish()).
        if (baked_one && options_.pace > 0.0 && !hurry_)
            wake_.wait_for(lock, std::chrono::duration<double, std::milli>(result_ms * options_.pace),
                           [this] { return stop_ || hurry_; });
    }
}

void WorldBaker::queue(Job job) {
    {
        std::lock_guard lock(mutex_);
        if (job.kind == Job::Kind::chunk) // a newer request replaces a queued one for the chunk
            std::erase_if(jobs_, [&](const std::unique_ptr<Job>& j) { return j->kind == Job::Kind::chunk && j->id == job.id; });
        jobs_.push_back(std::make_unique<Job>(std::move(job)));
    }
    wake_.notify_one();
}

namespace {

// The gi settings a bake depends on, from the game's (the rest at defaults, so that a HUD
// change to heat or the window re-bakes nothing).
scene::GiSettings bake_settings_of(const scene::GiSettings& g) {
    scene::GiSettings b;
    b.light_softness = g.light_softness;
    b.wall_face_exponent = g.wall_face_exponent;
    b.wall_albedo = g.wall_albedo;
    b.albedo_boost = g.albedo_boost;
    b.shadow_method = g.shadow_method;
    b.proxy_wall_shadows = g.proxy_wall_shadows;
    return b;
}

} // namespace

bool WorldBaker::scan(ecs::World& world) {
    const systems::Streaming& streaming = world.resource<systems::Streaming>();
    const systems::GiConfig& config = world.resource<systems::GiConfig>();
    // The mixed and baked lights and the proxies, as a bake sees them.
    scene::Scene statics;
    world.view<PointLight>().each([&](ecs::Entity e, const PointLight& l) {
        if (l.mode == scene::LightMode::realtime) return;
        const Torch* t = world.try_get<Torch>(e); // a torch at its base intensity, not this frame's flicker
        statics.point_lights.push_back({l.position, l.height, l.color, t ? t->base_intensity : l.intensity, l.radius, l.mode});
    });
    world.view<EmissiveLight>().each([&](const EmissiveLight& l) {
        if (l.mode != scene::LightMode::realtime) statics.emissive_lights.push_back({l.position, l.color, l.intensity, l.radius, l.mode});
    });
    world.view<ShadowProxy>().each([&](const ShadowProxy& p) { statics.shadow_proxies.push_back(p.shape); });
    // Mixed suns: with sun keys the bake follows the day's path, so where the sun stands now
    // is not an input (the day cycle moves it every frame); without, it is baked where it is.
    const bool keyed = options_.settings.sun_keys >= 2;
    world.view<DirectionalLight>().each([&](const DirectionalLight& l) {
        if (l.mode == scene::LightMode::realtime) return;
        const bool at_keys = keyed && l.mode == scene::LightMode::mixed; // baked along the day's path
        scene::DirectionalLight d;
        d.direction = at_keys ? glm::vec3(0.0f, -1.0f, 0.0f) : l.direction;
        d.color = at_keys ? glm::vec3(1.0f) : l.color;
        d.intensity = at_keys ? 1.0f : l.intensity;
        d.base_shadow_distance = l.base_shadow_distance;
        d.bounce_intensity = l.bounce_intensity;
        d.mode = l.mode;
        statics.directional_lights.push_back(d);
    });
    Hasher lights_hash;
    for (const auto& l : statics.point_lights)
        lights_hash.add(l.position.x).add(l.position.y).add(l.height).add(l.color.r).add(l.color.g).add(l.color.b).add(l.intensity).add(l.radius).add(int(l.mode));
    for (const auto& l : statics.emissive_lights)
        lights_hash.add(l.position.x).add(l.position.y).add(l.color.r).add(l.color.g).add(l.color.b).add(l.intensity).add(l.radius).add(int(l.mode));
    for (const auto& p : statics.shadow_proxies) lights_hash.add(p.position.x).add(p.position.y).add(p.size.x).add(p.size.y).add(int(p.shape));
    for (const auto& l : statics.directional_lights)
        lights_hash.add(l.direction.x).add(l.direction.y).add(l.direction.z).add(l.color.r).add(l.color.g).add(l.color.b)
            .add(l.intensity).add(l.base_shadow_distance).add(int(l.mode));
    std::vector<bake::ChunkId> resident;
    world.view<WallChunk>().each([&](const WallChunk& c) {
        if (c.state == ChunkState::resident) resident.push_back({c.coord.x, c.coord.y});
    });
    std::sort(resident.begin(), resident.end(), [](bake::ChunkId a, bake::ChunkId b) { return a.z != b.z ? a.z < b.z : a.x < b.x; });
    const bool resident_changed = resident != resident_;
    if (!resident_changed && streaming.version() == seen_version_ && lights_hash.value() == seen_lights_) return false;
    seen_version_ = streaming.version();
    seen_lights_ = lights_hash.value();
    resident_ = resident;
    if (resident.empty()) return resident_changed;
    // One snapshot of the cells every resident chunk's bake sees: the mirror where resident.
    const int border = options_.settings.margin + options_.reach;
    glm::ivec2 lo(INT_MAX), hi(INT_MIN);
    for (bake::ChunkId c : resident) {
        lo = glm::min(lo, glm::ivec2(c.x, c.z) * chunk_size - border);
        hi = glm::max(hi, glm::ivec2(c.x + 1, c.z + 1) * chunk_size + border);
    }
    const gi::WallView view = streaming.view();
    scene::WallGrid all;
    all.origin = lo;
    all.width = hi.x - lo.x;
    all.height = hi.y - lo.y;
    all.cells.resize(std::size_t(all.width) * std::size_t(all.height));
    for (int z = lo.y; z < hi.y; ++z)
        for (int x = lo.x; x < hi.x; ++x)
            all.cells[std::size_t(z - lo.y) * std::size_t(all.width) + std::size_t(x - lo.x)] =
                view.contains(x, z) ? view.cell(x, z) : streaming.cell({x, z});
    const scene::GiSettings gi = bake_settings_of(config.settings);
    for (bake::ChunkId c : resident) {
        const glm::ivec2 r0 = glm::ivec2(c.x, c.z) * chunk_size - border, r1 = glm::ivec2(c.x + 1, c.z + 1) * chunk_size + border;
        Job job;
        job.id = c;
        scene::Scene& s = job.region;
        s.gi = gi;
        s.wall_height = config.wall_height;
        s.materials = config.materials;
        s.walls.origin = r0;
        s.walls.width = r1.x - r0.x;
        s.walls.height = r1.y - r0.y;
        s.walls.cells.resize(std::size_t(s.walls.width) * std::size_t(s.walls.height));
        for (int z = r0.y; z < r1.y; ++z)
            std::copy_n(&all.cells[std::size_t(z - lo.y) * std::size_t(all.width) + std::size_t(r0.x - lo.x)], s.walls.width,
                        &s.walls.cells[std::size_t(z - r0.y) * std::size_t(s.walls.width)]);
        auto inside = [&](glm::vec2 p) { return p.x >= float(r0.x) && p.y >= float(r0.y) && p.x < float(r1.x) && p.y < float(r1.y); };
        for (const auto& l : statics.point_lights)
            if (inside(l.position)) s.point_lights.push_back(l);
        for (const auto& l : statics.emissive_lights)
            if (inside(l.position)) s.emissive_lights.push_back(l);
        for (const auto& p : statics.shadow_proxies)
            if (inside(p.position)) s.shadow_proxies.push_back(p);
        s.directional_lights = statics.directional_lights; // suns reach every chunk
        Hasher h;
        h.add_bytes(s.walls.cells.data(), s.walls.cells.size()).add(s.wall_height);
        for (const auto& m : s.materials)
            h.add(m.albedo.r).add(m.albedo.g).add(m.albedo.b).add(m.emission.r).add(m.emission.g).add(m.emission.b)
                .add(int(m.emission_gi)).add(m.opacity).add(m.pulse > 0.0f);
        for (double v : scene::gi_setting_values(s.gi)) h.add(v);
        for (const auto& l : s.point_lights) h.add(l.position.x).add(l.position.y).add(l.intensity).add(l.radius).add(int(l.mode)).add(l.color.r).add(l.color.g).add(l.color.b);
        for (const auto& l : s.emissive_lights) h.add(l.position.x).add(l.position.y).add(l.intensity).add(l.radius).add(int(l.mode)).add(l.color.r).add(l.color.g).add(l.color.b);
        for (const auto& p : s.shadow_proxies) h.add(p.position.x).add(p.position.y).add(p.size.x).add(p.size.y).add(int(p.shape));
        for (const auto& l : s.directional_lights)
            h.add(l.direction.x).add(l.direction.y).add(l.direction.z).add(l.color.r).add(l.color.g).add(l.color.b)
                .add(l.intensity).add(l.base_shadow_distance).add(int(l.mode));
        job.inputs = h.value();
        const std::uint64_t k = chunk_id_key(c);
        auto req = requested_.find(k);
        if (req != requested_.end() && req->second == job.inputs) continue; // baked or on its way
        requested_[k] = job.inputs;
        queue(std::move(job));
    }
    return resident_changed;
}

void WorldBaker::update(ecs::World& world) {
    LANTERN_PROFILE_SCOPE("bake_update"); // not "bake": the system's job has that name
    BakedChunks& baked = world.resource<BakedChunks>();
    BakeStatus& status = world.resource<BakeStatus>();
    status.enabled = true;
    // Seed 004's pulsing emission: the pulsing glow's factor at the game's time, for the frame's
    // baked light and the probes (a colour-only update: nothing is baked again).
    // In steps of 1/32: each new value reruns the baked rows and the rows they add into (about
    // 1 ms p50, 3-4 ms p95 a frame on lavapipe when every frame has a new one), and a step of
    // 3 % in a slow glow does not show; at 0.2 Hz a step comes every few frames.
    const float hz = scene::pulse_frequency(world.resource<systems::GiConfig>().materials);
    const float pulse = world.has_resource<GameClock>()
                            ? std::round(scene::pulse_factor(hz, world.resource<GameClock>().time) * 32.0f) / 32.0f
                            : 1.0f;
    world.resource<systems::BakedGi>().pulse = pulse;
    baked.pulse = pulse;
    // The moving sun's keys for the probes (the frame's GI finds them itself: gi::baked_sun_of).
    baked.sun = {};
    if (options_.settings.sun_keys >= 2)
        world.view<DirectionalLight>().each([&](const DirectionalLight& l) {
            if (l.mode != scene::LightMode::mixed || baked.sun.key >= 0 || !gi::sun_adds_light(l.color, l.intensity)) return;
            const scene::SunKeyBlend b = scene::sun_key_blend(l.direction, options_.settings.sun_keys);
            baked.sun = {b.key, b.blend, l.color * l.intensity};
        });
    status.cache_dir = options_.cache_dir;
    std::vector<std::unique_ptr<Result>> done;
    int pending = 0;
    {
        std::lock_guard lock(mutex_);
        done.swap(results_);
        for (const auto& j : jobs_) pending += j->kind == Job::Kind::chunk;
        pending += running_;
    }
    for (auto& r : done) {
        if (!r->warning.empty()) status.last_warning = r->warning;
        if (r->kind == Job::Kind::compose) {
            world.resource<systems::BakedGi>().light = r->light;
            ++status.published;
            continue;
        }
        const std::uint64_t k = chunk_id_key(r->id);
        (r->reused ? status.reused : status.baked) += 1;
        status.last_chunk_ms = r->ms;
        auto req = requested_.find(k);
        if (req == requested_.end() || req->second != r->inputs) continue; // a newer bake is on its way
        baked.chunks[k] = r->bake;
        compose_wanted_ = true;
    }
    if (scan(world)) {
        compose_wanted_ = true;
        // Chunks that left the resident area: forgotten (their cache files stay), asked for
        // again when they come back.
        auto gone = [this](std::uint64_t k) {
            for (bake::ChunkId c : resident_)
                if (chunk_id_key(c) == k) return false;
            return true;
        };
        std::erase_if(baked.chunks, [&](const auto& kv) { return gone(kv.first); });
        std::erase_if(requested_, [&](const auto& kv) { return gone(kv.first); });
    }
    {
        std::lock_guard lock(mutex_);
        pending = running_;
        for (const auto& j : jobs_) pending += j->kind == Job::Kind::chunk;
    }
    status.pending = pending;
    status.chunks = int(baked.chunks.size());
    // Compose once the chunk bakes in flight are done (not after every chunk of a burst).
    if (compose_wanted_ && pending == 0 && !baked.chunks.empty()) {
        compose_wanted_ = false;
        Job job;
        job.kind = Job::Kind::compose;
        glm::ivec2 lo(INT_MAX), hi(INT_MIN);
        for (const auto& [k, b] : baked.chunks) {
            job.bakes.push_back(b);
            lo = glm::min(lo, glm::ivec2(b->id.x, b->id.z) * chunk_size);
            hi = glm::max(hi, glm::ivec2(b->id.x + 1, b->id.z + 1) * chunk_size + 1);
        }
        lo -= 1;
        const systems::Streaming& streaming = world.resource<systems::Streaming>();
        const gi::WallView view = streaming.view();
        job.walls.origin = lo;
        job.walls.width = hi.x - lo.x;
        job.walls.height = hi.y - lo.y;
        job.walls.cells.resize(std::size_t(job.walls.width) * std::size_t(job.walls.height));
        for (int z = lo.y; z < hi.y; ++z)
            for (int x = lo.x; x < hi.x; ++x)
                job.walls.cells[std::size_t(z - lo.y) * std::size_t(job.walls.width) + std::size_t(x - lo.x)] =
                    view.contains(x, z) ? view.cell(x, z) : streaming.cell({x, z});
        queue(std::move(job));
    }
}

void WorldBaker::finish(ecs::World& world) {
    {
        std::lock_guard lock(mutex_);
        hurry_ = true; // no pacing: the caller waits
    }
    wake_.notify_all();
    update(world);
    for (;;) {
        {
            std::unique_lock lock(mutex_);
            idle_.wait(lock, [this] { return jobs_.empty() && running_ == 0; });
        }
        update(world);
        std::lock_guard lock(mutex_);
        if (jobs_.empty() && running_ == 0 && results_.empty() && !compose_wanted_) {
            hurry_ = false;
            return;
        }
    }
}

void add_bake_system(ecs::Schedule& schedule, WorldBaker& baker) {
    schedule.add("bake", [&baker](ecs::SystemContext& ctx) { baker.update(ctx.world); })
        .main_thread()
        .reads<PointLight, EmissiveLight, DirectionalLight, ShadowProxy, Torch, WallChunk>()
        .reads_resource<systems::Streaming, systems::GiConfig, GameClock>()
        .writes_resource<systems::BakedGi, BakedChunks, BakeStatus>();
}

} // namespace lantern::game

#include "lantern/systems/gi_frame.hpp"

#include "lantern/gi/pass_table.hpp"

#include "lantern/core/hash.hpp"
#include "lantern/core/log.hpp"
#include "lantern/profile/profiler.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace lantern::systems {
namespace {

// Did any component of type T change, appear or disappear at or after `tick`? (At: a
// system that ran later in the frame of `tick` may have changed it after we looked.)
template <typename T>
bool pool_changed_since(ecs::World& w, ecs::Tick tick) {
    const ecs::Pool<T>* p = w.find_pool<T>();
    if (!p) return false;
    return tick == 0 || p->last_changed() >= tick || p->last_added() >= tick || p->last_removed() >= tick;
}

std::uint64_t hash_window(const std::optional<gi::GiWindow>& w) {
    return w ? gi::hash_window(*w) : Hasher().add(0).value();
}

template <typename T>
std::uint64_t hash_vector(Hasher h, const std::vector<T>& v) {
    h.add_u64(v.size());
    if (!v.empty()) h.add_bytes(v.data(), v.size() * sizeof(T));
    return h.value();
}

// out = prefix + why, assigned only when it differs (an unchanged frame allocates nothing).
void set_reason(std::string& out, std::string_view prefix, std::string_view why) {
    if (out.size() == prefix.size() + why.size() && std::string_view(out).starts_with(prefix) &&
        std::string_view(out).ends_with(why))
        return;
    out.assign(prefix).append(why);
}

struct LightGatherState {
    std::uint64_t window_hash = ~0ull;
    bool baked = false; // a bake was used (light modes honoured)
    std::unordered_set<std::uint64_t> kept; // entities kept last time (hysteresis)
};

// The components of type T, by entity (the GPU order and the last tie-break).
template <typename T>
std::vector<std::pair<ecs::Entity, const T*>> by_entity(ecs::World& w) {
    std::vector<std::pair<ecs::Entity, const T*>> out;
    w.view<T>().each([&](ecs::Entity e, const T& c) { out.push_back({e, &c}); });
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    return out;
}

// The lights of the frame, chosen by gi::gather_offers as the scene path chooses them (one
// road: frame_inputs.hpp), with hysteresis for point lights near the cap.
void gather_lights(ecs::SystemContext& ctx, LightGatherState& state) {
    ecs::World& w = ctx.world;
    const GiView& view = w.resource<GiView>();
    const GiConfig& config = w.resource<GiConfig>();
    const std::uint64_t window_hash = hash_window(view.window);
    // With a bake, baked lights leave the live passes and mixed lights keep only their
    // direct light (the `mixed` row); without one every light is realtime.
    const bool baked = w.resource<BakedGi>().light != nullptr;
    auto live = [baked](scene::LightMode m) { return !baked || m != scene::LightMode::baked; };
    auto mixed = [baked](scene::LightMode m) { return baked && m == scene::LightMode::mixed; };
    const bool changed = window_hash != state.window_hash || baked != state.baked || pool_changed_since<PointLight>(w, ctx.last_run) ||
                         pool_changed_since<EmissiveLight>(w, ctx.last_run) ||
                         pool_changed_since<DirectionalLight>(w, ctx.last_run);
    if (!changed) return; // nothing to redo: last frame's lists stand
    state.window_hash = window_hash;
    state.baked = baked;
    GatheredLights out;
    if (view.window) {
        const gi::GiWindow& win = *view.window;
        std::vector<gi::Offer> offers;
        auto points = by_entity<PointLight>(w);
        std::erase_if(points, [&](const auto& p) { return !live(p.second->mode); });
        for (std::uint32_t i = 0; i < points.size(); ++i) {
            const auto& [e, l] = points[i];
            // Stable priority: lights kept last frame get a head start, so lights near the
            // cap do not flicker in and out as the camera moves.
            offers.push_back({l->position, l->radius, i, state.kept.count(e.bits()) ? config.light_hysteresis : 0.0f});
        }
        const std::size_t cap = std::size_t(std::max(0, config.settings.max_lights));
        const std::vector<std::uint32_t> kept = gi::gather_offers(offers, win, cap);
        out.point_candidates = 0;
        for (const gi::Offer& o : offers) out.point_candidates += gi::distance_to_window(win, o.position) <= o.reach;
        state.kept.clear();
        for (std::uint32_t i : kept) {
            const auto& [e, l] = points[i];
            state.kept.insert(e.bits());
            if (mixed(l->mode)) {
                out.mixed_points.push_back(gi::pack_light(l->position, l->color, l->intensity, l->radius));
                continue;
            }
            out.points.push_back(gi::pack_light(l->position, l->color, l->intensity, l->radius));
            out.point_entities.push_back(e);
        }
        offers.clear();
        auto emissives = by_entity<EmissiveLight>(w);
        std::erase_if(emissives, [&](const auto& p) { return !live(p.second->mode); });
        for (std::uint32_t i = 0; i < emissives.size(); ++i)
            offers.push_back({emissives[i].second->position, emissives[i].second->radius, i});
        for (std::uint32_t i : gi::gather_offers(offers, win, offers.size())) {
            const EmissiveLight& l = *emissives[i].second;
            (mixed(l.mode) ? out.mixed_emissives : out.emissives).push_back(gi::pack_light(l.position, l.color, l.intensity, l.radius));
        }
        for (const auto& [e, d] : by_entity<DirectionalLight>(w)) {
            if (!gi::sun_adds_light(d->color, d->intensity) || !live(d->mode)) continue;
            out.suns.push_back(gi::pack_directional(
                {d->direction, d->color, d->intensity, d->base_shadow_distance, d->bounce_intensity},
                config.settings.method));
            if (mixed(d->mode)) gi::mark_mixed(out.suns.back());
        }
    }
    out.hash = hash_vector(Hasher(hash_vector(Hasher(), out.points)), out.emissives);
    out.suns_hash = hash_vector(Hasher(), out.suns);
    w.resource<GatheredLights>() = std::move(out);
}

struct ProxyGatherState {
    std::uint64_t window_hash = ~0ull;
};

void gather_proxies(ecs::SystemContext& ctx, ProxyGatherState& state) {
    ecs::World& w = ctx.world;
    const GiView& view = w.resource<GiView>();
    const GiConfig& config = w.resource<GiConfig>();
    const std::uint64_t window_hash = hash_window(view.window);
    if (window_hash == state.window_hash && !pool_changed_since<ShadowProxy>(w, ctx.last_run)) return;
    state.window_hash = window_hash;
    GatheredProxies out;
    if (view.window) {
        const auto proxies = by_entity<ShadowProxy>(w);
        std::vector<gi::Offer> offers;
        for (std::uint32_t i = 0; i < proxies.size(); ++i) {
            const scene::ShadowProxy& s = proxies[i].second->shape;
            offers.push_back({s.position, gi::proxy_reach(s), i});
        }
        const std::size_t cap = std::size_t(std::max(0, config.settings.max_shadow_proxies));
        const gi::FadedOffers kept = gi::gather_offers_faded(offers, *view.window, cap, config.proxy_fade);
        for (std::size_t k = 0; k < kept.ids.size(); ++k)
            out.proxies.push_back(gi::pack_proxy(proxies[kept.ids[k]].second->shape, kept.fade[k]));
    }
    out.hash = hash_vector(Hasher(), out.proxies);
    w.resource<GatheredProxies>() = std::move(out);
}

} // namespace

std::array<std::uint64_t, gi::pass_count> pass_keys(const gi::FrameInputs& in, gi::PassPlan& plan,
                                                     std::uint64_t wall_version, std::uint64_t lights_hash,
                                                     std::uint64_t suns_hash, std::uint64_t proxies_hash,
                                                     gi::Convergence* convergence) {
    // The walls' key covers their materials too (what they reflect and emit).
    const std::uint64_t walls = in.materials.empty() ? wall_version
                                                     : Hasher().add(wall_version).add_span(std::span(in.materials)).value();
    const gi::InputKeys inputs{gi::hash_window(in.window), walls,
                               lights_hash, proxies_hash,
                               suns_hash,   gi::baked_input_key(in),
                               Hasher().add_span(std::span(in.mixed_lights)).add_span(std::span(in.mixed_emissives)).value(),
                               gi::baked_pulse_key(in), gi::mixed_suns_key(in)};
    return gi::derive_keys(in, plan, inputs, convergence);
}

GiFrame::GiFrame(ecs::World& world, jobs::JobSystem& jobs, std::shared_ptr<const WorldSource> source,
                 std::unique_ptr<gi::Backend> backend, GiConfig config, GiFrameOptions options)
    : world_(world), jobs_(jobs), backend_(std::move(backend)), schedule_(jobs), warm_up_shaders_(options.warm_up_shaders) {
    // The one owner of the wall bytes (the mirror) and of the chunk bookkeeping: a world
    // resource, so systems reach it through the world like any other, and declare it.
    world_.set_resource<Streaming>(std::move(source), options.streaming);
    world_.set_resource<GiConfig>(std::move(config));
    world_.set_resource<GiView>();
    world_.set_resource<GatheredLights>();
    world_.set_resource<GatheredProxies>();
    world_.set_resource<FramePasses>();
    world_.set_resource<WallDistanceField>();
    world_.set_resource<BakedGi>();
    gpu_lane_ = profile::add_gpu_lane(profile::intern("GPU: " + backend_->name()));
    if (options.add_game_systems) options.add_game_systems(schedule_);
    add_systems();
}

GiFrame::~GiFrame() {
    backend_->wait_idle();
    world_.remove_resource<Streaming>(); // its loads finish or are cancelled here
}

ecs::Entity GiFrame::camera() const {
    ecs::Entity found;
    const_cast<ecs::World&>(world_).view<Camera>().each([&](ecs::Entity e, Camera&) {
        if (found.is_null()) found = e;
    });
    return found;
}

void GiFrame::add_systems() {
    schedule_.add("camera_view", [](ecs::SystemContext& ctx) {
        GiView& out = ctx.world.resource<GiView>();
        const GiConfig& config = ctx.world.resource<GiConfig>();
        out = GiView{};
        bool found = false;
        ctx.world.view<Camera>().each([&](const Camera& cam) {
            if (found) return;
            found = true;
            out.window = gi::compute_window(cam.view, config.settings, &out.bail_reason);
        });
        if (!found) out.bail_reason = "no camera";
    }).reads<Camera>().reads_resource<GiConfig>().writes_resource<GiView>();

    schedule_.add("streaming", [this](ecs::SystemContext& ctx) {
        const GiView& view = ctx.world.resource<GiView>();
        if (view.window) ctx.world.resource<Streaming>().update(ctx.world, ctx.commands(), jobs_, view.window->view);
    }).main_thread().reads_resource<GiView>().writes<WallChunk>().writes_resource<Streaming>();

    auto light_state = std::make_shared<LightGatherState>();
    schedule_.add("light_gather", [light_state](ecs::SystemContext& ctx) { gather_lights(ctx, *light_state); })
        .reads<PointLight, EmissiveLight, DirectionalLight>()
        .reads_resource<GiView, GiConfig, BakedGi>()
        .writes_resource<GatheredLights>();

    auto proxy_state = std::make_shared<ProxyGatherState>();
    schedule_.add("proxy_gather", [proxy_state](ecs::SystemContext& ctx) { gather_proxies(ctx, *proxy_state); })
        .reads<ShadowProxy>()
        .reads_resource<GiView, GiConfig>()
        .writes_resource<GatheredProxies>();

    schedule_.add("cache_keys", [this](ecs::SystemContext& ctx) {
        ecs::World& w = ctx.world;
        const GiView& view = w.resource<GiView>();
        const GiConfig& config = w.resource<GiConfig>();
        FramePasses& f = w.resource<FramePasses>();
        f.run = {};
        if (!view.window) {
            for (auto& r : f.reason) r = "no GI window: " + view.bail_reason;
            return;
        }
        const GatheredLights& lights = w.resource<GatheredLights>();
        const GatheredProxies& proxies = w.resource<GatheredProxies>();
        gi::FrameInputs& in = f.inputs;
        in.window = *view.window;
        const Streaming& streaming = ctx.world.resource<Streaming>();
        in.walls = streaming.view();
        in.wall_height = config.wall_height;
        in.settings = config.settings;
        in.point_lights = lights.points;
        in.emissive_lights = lights.emissives;
        in.mixed_lights = lights.mixed_points;
        in.mixed_emissives = lights.mixed_emissives;
        in.directional_lights = lights.suns;
        in.proxies = proxies.proxies;
        in.materials.clear();
        for (const scene::Material& m : config.materials) in.materials.push_back(gi::pack_material(m));
        in.baked = w.resource<BakedGi>().light;
        in.baked_pulse = w.resource<BakedGi>().pulse;
        f.plan = gi::plan_passes(in, config.lit_image);
        // The bounce stepper: a restart starts the converging rows afresh; while they are held,
        // a step advances them by one frame (gpu_submit advances them otherwise).
        const ConvergeControl& control = config.converge;
        if (control.restarts != restarts_seen_) {
            convergence_.restart();
            held_ = {};
            restarts_seen_ = control.restarts;
        }
        if (held_.bits && (!control.hold || steps_seen_ < control.steps)) {
            convergence_.advance(held_); // what ran while held counts now
            held_ = {};
            if (control.hold) ++steps_seen_;
        }
        if (!control.hold) steps_seen_ = control.steps;
        f.keys = pass_keys(in, f.plan, streaming.version(), lights.hash, lights.suns_hash, proxies.hash, &convergence_);
        const ecs::Entity cam = camera();
        const GICache* cache = cam.is_null() ? nullptr : w.try_get<GICache>(cam);
        for (int p = 0; p < gi::registered_pass_count(); ++p) {
            if (!f.plan.run.has(gi::Pass(p))) {
                set_reason(f.reason[std::size_t(p)], "not needed: ", f.plan.reason[p]);
            } else if (cache && cache->keys[std::size_t(p)] == f.keys[std::size_t(p)]) {
                set_reason(f.reason[std::size_t(p)], "cache hit", {});
            } else {
                f.run.add(gi::Pass(p));
                f.reason[std::size_t(p)].clear();
            }
        }
    })
        .reads_resource<GiView, GiConfig, GatheredLights, GatheredProxies, Streaming, BakedGi>()
        .reads<GICache, Camera>()
        .writes_resource<FramePasses>();

    schedule_.add("wall_distance", [](ecs::SystemContext& ctx) {
        ecs::World& w = ctx.world;
        const GiView& view = w.resource<GiView>();
        if (!view.window) return;
        const FramePasses& f = w.resource<FramePasses>();
        const Streaming& streaming = w.resource<Streaming>();
        const std::uint64_t key = Hasher(gi::hash_window(*view.window))
                                      .add(streaming.version())
                                      .add(int(f.inputs.settings.radiosity.scale))
                                      .value();
        WallDistanceField& d = w.resource<WallDistanceField>();
        if (d.key == key) return;
        d.field = gi::WallDistance::build(f.inputs);
        d.key = key;
        ++d.builds;
    })
        .reads_resource<GiView, FramePasses, Streaming>()
        .writes_resource<WallDistanceField>();

    schedule_.add("gpu_submit", [this](ecs::SystemContext& ctx) {
        ecs::World& w = ctx.world;
        FramePasses& f = w.resource<FramePasses>();
        const GiView& view = w.resource<GiView>();
        report_.ran = {};
        if (view.window) {
            Streaming& streaming = w.resource<Streaming>();
            const gi::WallUpdate walls{streaming.resized(), streaming.dirty()};
            if (warm_up_shaders_) {
                // Two frames not shown (GiFrameOptions::warm_up_shaders): without shadow
                // proxies, then with one, since the passes that shade proxies (the sun's, the
                // direct pass's) compile them out when none is in view: a variant each. The
                // last holds a proxy where this frame may hold none, or other proxies, so the
                // direct row's kept light bins do not outlive it (their context hashes the
                // proxies); this frame runs every pass it plans (its cache is empty).
                warm_up_shaders_ = false;
                const gi::FrameInputs warm = gi::warm_up_inputs(f.inputs);
                gi::FrameInputs bare = warm;
                bare.proxies.clear();
                bare.proxy_ids.clear();
                for (const gi::FrameInputs* in : {static_cast<const gi::FrameInputs*>(&bare), &warm}) {
                    const gi::PassPlan plan = gi::plan_passes(*in, w.resource<GiConfig>().lit_image);
                    if (auto warmed = backend_->execute(frame_, *in, plan, plan.run, walls); !warmed) {
                        LANTERN_LOG_WARN("GI shader warm-up: %s", warmed.error().message.c_str());
                        break;
                    }
                }
            }
            auto ok = backend_->execute(frame_, f.inputs, f.plan, f.run, walls);
            const ecs::Entity cam = camera();
            GICache* cache = cam.is_null() ? nullptr : w.try_get<GICache>(cam);
            if (!ok) {
                if (cache) cache->keys = {}; // retry everything next frame
                convergence_.reset();
                report_.error = ok.error();
            } else {
                streaming.clear_dirty();
                report_.ran = f.run;
                if (w.resource<GiConfig>().converge.hold) held_.bits |= f.run.bits;
                else convergence_.advance(f.run);
                if (cache && f.run.bits) {
                    GICache& c = w.patch<GICache>(cam);
                    for (int p = 0; p < gi::registered_pass_count(); ++p)
                        if (f.run.has(gi::Pass(p))) c.keys[std::size_t(p)] = f.keys[std::size_t(p)];
                }
            }
            if (cache) {
                cache->ran = report_.ran;
                ++cache->frames;
            }
        }
        report_.reason = f.reason;
        report_.window = view.window;
        report_.completed = backend_->completed_times();
        for (const gi::FrameTimes& t : report_.completed)
            for (const gi::PassTime& p : t.passes)
                profile::record_gpu(gpu_lane_, t.frame, gi::pass_name(p.pass), p.cpu_begin_ns, p.cpu_end_ns);
    })
        .main_thread()
        .reads_resource<FramePasses, GiView, GiConfig>()
        .reads<Camera>()
        .writes<GICache>()
        .writes_resource<Streaming>() // clears the dirty chunks it uploaded
        .after("streaming");          // which streaming marked this frame
}

void GiFrame::warm_up() {
    const ecs::Entity cam = camera();
    if (cam.is_null()) return;
    const GiConfig& config = world_.resource<GiConfig>();
    auto window = gi::compute_window(world_.get<Camera>(cam).view, config.settings);
    if (window) streaming().load_all(world_, jobs_, window->view);
}

FrameReport GiFrame::step() {
    // The backend's frame ids are profiler frame indices when a profiler frame is open, so
    // GPU timestamps land in the frame that submitted them.
    frame_ = profile::frame_index() ? profile::frame_index() : frame_ + 1;
    report_ = {};
    report_.frame = frame_;
    schedule_.run(world_);
    return report_;
}

} // namespace lantern::systems

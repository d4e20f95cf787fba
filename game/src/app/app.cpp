// The game loop. One frame is one run of the ECS schedule on the job graph:
//
//   input (main) ─► player_move ─► interact (main) ─► camera_view ─► streaming ─┐
//   torch_flicker, day_cycle ─────────────────────────► light/proxy gather ─────┼► cache_keys ─► gpu_submit (main)
//                                                                                └──────────► draw_list ─► render (main)
//
// `input` turns the window's keys and mouse (or the demo script) into Controls; the game
// systems move the player and edit the world; the GI systems submit this frame's GI passes;
// `render` records the raster pass that reads them, the upscale and the HUD, and presents.
//
// This file: start-up (device, renderers, window), sessions (a world, its GI frame and the
// application's systems) and run(). The rest: game.hpp lists the files.
#include "app/game.hpp"

namespace lantern::game::app {

Result<void> Game::init(bool windowed) {
    gpu::DeviceOptions device_options;
    device_options.graphics = true;
    device_options.validation = options_.validation;
    device_options.application_name = "lantern";
    if (windowed) {
        platform::WindowDesc desc;
        desc.title = "Lantern";
        desc.width = std::uint32_t(options_.window_size.x);
        desc.height = std::uint32_t(options_.window_size.y);
        auto window = platform::Window::create(desc);
        if (!window) return Error{"lantern: cannot open a window: " + window.error().message, 1};
        window_.emplace(std::move(*window));
        if (auto ok = render::add_presentation(device_options, *window_); !ok)
            return Error{"lantern: no presentation support: " + ok.error().message, 1};
    }
    auto device = gpu::Device::create(device_options);
    if (!device) return Error{"lantern: no usable Vulkan device: " + device.error().message, 1};
    device_ = std::move(*device);
    if (windowed) {
        auto surface = window_->create_surface(*device_);
        if (!surface) return Error{"lantern: " + surface.error().message, 1};
        render::SwapchainDesc sd;
        sd.vsync = options_.vsync;
        auto swapchain = render::Swapchain::create(*device_, std::move(*surface), window_->framebuffer_size(), sd);
        if (!swapchain) return Error{"lantern: " + swapchain.error().message, 1};
        swapchain_.emplace(std::move(*swapchain));
        render::ImGuiOverlayDesc od;
        od.format = swapchain_->format();
        od.final_layout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
        od.window = &*window_;
        auto overlay = render::ImGuiOverlay::create(*device_, od);
        if (!overlay) return Error{"lantern: " + overlay.error().message, 1};
        overlay_.emplace(std::move(*overlay));
    }
    auto gi = gi::vk::Renderer::create(*device_);
    if (!gi) return Error{"lantern: " + gi.error().message, 1};
    gi_renderer_ = std::move(*gi);
    if (window_) fit_internal_to_window(); // before the first session: its camera's aspect
    auto wr = WorldRenderer::create(*device_, internal_);
    if (!wr) return Error{"lantern: " + wr.error().message, 1};
    world_renderer_ = std::move(*wr);
    if (options_.texel_lighting) {
        auto tw = TexelWorld::create(*device_);
        if (!tw) return Error{"lantern: " + tw.error().message, 1};
        texel_world_ = std::move(*tw);
    }
    if (device_->capabilities().timestamps) {
        auto timer = render::PassTimer::create(*device_);
        if (timer) timer_.emplace(std::move(*timer));
    }
    if (!options_.palette.empty()) {
        const auto palettes = builtin_palettes();
        for (std::size_t i = 1; i < palettes.size(); ++i)
            if (options_.palette == palettes[i].name) art_.palette = int(i);
        if (art_.palette == 0 && options_.palette != "off") {
            std::string names;
            for (const Palette& p : palettes) names += std::string(names.empty() ? "" : ", ") + p.name;
            return Error{"lantern: unknown palette '" + options_.palette + "' (palettes: " + names + ")", 2};
        }
    }
    raster_lane_ = profile::add_gpu_lane("GPU raster");
    hud_.visible = options_.hud;
    if (windowed && options_.sound) {
        // Sound is a pleasure, not a requirement: without an output device the game runs silent.
        if (auto mixer = audio::Mixer::open_device()) {
            LANTERN_LOG_INFO("sound: %s", (*mixer)->device_name().c_str());
            sound_ = std::make_unique<GameSound>(std::move(*mixer));
            sound_->mixer().set_volume(float(settings_.volume) / 100.0f);
        } else {
            LANTERN_LOG_WARN("%s: the game runs silent", mixer.error().message.c_str());
        }
    }
    return {};
}

Result<std::unique_ptr<Session>> Game::make_session(const WorldSpec& spec, const SaveState* save,
                                                    const scene::Scene* scene) {
    auto s = std::make_unique<Session>();
    ecs::World& w = s->world;
    w.set_resource<Controls>();
    w.set_resource<Inventory>();
    w.set_resource<GameClock>();
    DayCycle day;
    day.time_of_day = options_.time_of_day; // 0.85 by default: night, torches and crystals carry the caves
    day.drives_sun = spec.kind != WorldKind::scene;
    w.set_resource<DayCycle>(day);
    CameraRig rig;
    rig.aspect = float(internal_.x) / float(internal_.y);
    w.set_resource<CameraRig>(rig);
    w.set_resource<DrawListResource>();
    w.set_resource<BakedChunks>();
    w.set_resource<BakeStatus>();

    WorldOptions wo;
    wo.gi = options_.gi;
    wo.player_light = options_.player_light;
    wo.scene = scene;
    wo.tables = &tables_;
    auto created = create_world(spec, w, wo);
    if (!created) return created.error();
    s->info = std::move(*created);
    systems::GiConfig config = s->info.config;
    auto gi = session_gi(s->info);
    if (!gi) return gi.error();
    config.settings = *gi;
    config.proxy_fade = 6.0f; // proxies past the cap fade out, not pop (docs/frame.md, "Light gathering")
    w.set_resource<WorldEdits>();
    if (sound_) w.set_resource<SoundCues>();
    for (const GameExtension& e : extensions_)
        if (e.setup) e.setup(w);
    if (save) {
        apply_save(*save, w, s->info.player);
        // Named tables win over the lights the save kept (the defaults leave them as saved).
        if (!options_.tables_file.empty()) apply_tables(w, tables_, false);
        std::vector<std::string> ignored;
        if (auto ok = load_extensions(extensions_, save->extensions, w, save->file, &ignored); !ok) return ok.error();
        for (const std::string& name : ignored)
            LANTERN_LOG_WARN("%s: data for the game extension '%s', which this game does not have: ignored",
                             save->file.c_str(), printable(name, 64).c_str());
    }
    if (options_.bake) {
        // One folder per world (the caves of a seed, a map, a scene): chunk files are named
        // by their coordinates only.
        // Default: beside the save file (the headless demo: in its --out folder).
        const std::filesystem::path root =
            !options_.bake_dir.empty()           ? std::filesystem::path(options_.bake_dir)
            : options_.mode == RunMode::headless ? std::filesystem::path(options_.out_dir) / "lantern-bake"
                                                 : std::filesystem::path(options_.save_file).parent_path() / "lantern-bake";
        const WorldSpec& ws = spec;
        char name[96];
        if (ws.kind == WorldKind::caves)
            std::snprintf(name, sizeof(name), "caves-%u-%.3f", ws.seed, double(ws.cave_threshold));
        else
            std::snprintf(name, sizeof(name), "%s-%s", world_kind_name(ws.kind),
                          std::filesystem::path(ws.path).stem().string().substr(0, 60).c_str());
        BakerOptions bo;
        bo.cache_dir = (root / name).string();
        // The world's own bake settings (a scene's "bake") or the game's, the --bake-* options
        // over them. They are in every chunk's cache key: a change bakes again.
        bo.settings = bake::GivenSettings{options_.bake_values, options_.bake_given}.over(s->info.bake ? *s->info.bake
                                                                                                      : bo.settings);
        const std::string density =
            bo.settings.density.empty() ? "" : " (" + std::to_string(bo.settings.density.size()) + " density regions)";
        const std::string keys = bo.settings.sun_keys >= 2 ? ", the sun at " + std::to_string(bo.settings.sun_keys) + " keys" : "";
        LANTERN_LOG_INFO("baked light: resolution %d%s, margin %d, %d rays (%d on faces), %s%s%s, eps %g, max level %d (%s)",
                         bo.settings.resolution, density.c_str(), bo.settings.margin, bo.settings.rays, bo.settings.face_rays,
                         bake::solver_name(bo.settings.solver), bo.settings.directional ? "" : ", non-directional", keys.c_str(),
                         double(bo.settings.eps), bo.settings.max_level,
                         options_.bake_given.empty() ? (s->info.bake ? "the scene's" : "the game's") : "--bake-* given");
        // The game's sun is mixed while the bake holds its bounce at the day's keys
        // (--bake-sun-keys: seed 004's precomputed GI for the moving sun), realtime otherwise
        // (a mixed sun without keys would be baked again at every step of the day cycle).
        const scene::LightMode sun_mode = bo.settings.sun_keys >= 2 ? scene::LightMode::mixed : scene::LightMode::realtime;
        w.view<Sun, DirectionalLight>().each([&](ecs::Entity e, const Sun&, const DirectionalLight& d) {
            if (d.mode != sun_mode) w.patch<DirectionalLight>(e).mode = sun_mode;
        });
        s->baker = std::make_unique<WorldBaker>(std::move(bo));
    }

    systems::GiFrameOptions fo;
    fo.warm_up_shaders = true; // the sun, the lamp posts and the proxies' shaders before play
    Session* session = s.get();
    fo.add_game_systems = [this, session](ecs::Schedule& schedule) {
        schedule.add("input", [this, session](ecs::SystemContext&) { input_system(*session); })
            .main_thread()
            .reads<Player, Transform, Camera>()
            .reads_resource<systems::Streaming>() // the demo script looks at the walls
            .reads_resource<WorldEdits>()         // a close request asks when something is unsaved
            .writes_resource<Controls, GameClock>();
        add_gameplay_systems(schedule);
        for (const GameExtension& e : extensions_)
            if (e.add_systems) e.add_systems(schedule);
        if (session->baker) add_bake_system(schedule, *session->baker);
    };
    s->frame = std::make_unique<systems::GiFrame>(w, jobs_, s->info.source, gi::make_vulkan_backend(*gi_renderer_),
                                                  config, std::move(fo));
    if (save) s->frame->streaming().restore_edits(save->edits);
    add_systems(s->frame->schedule(), *s);
    s->schedule = s->frame->schedule().describe();
    LANTERN_LOG_INFO("schedule: %zu systems, %zu edges, %zu ambiguities%s", s->schedule.systems.size(),
                     s->schedule.edges.size(), s->schedule.ambiguities.size(),
                     options_.schedule_dot.empty() ? " (--schedule FILE.dot draws it)" : "");
    if (!s->schedule.ambiguities.empty()) { // docs/frame.md explains each of the game's
        std::istringstream report(ecs::ambiguity_report(s->schedule));
        for (std::string line; std::getline(report, line);) LANTERN_LOG_INFO("schedule: %s", line.c_str());
    }
    if (!options_.schedule_dot.empty()) {
        const std::string dot = ecs::schedule_dot(s->schedule, "Lantern game frame: " + s->info.description);
        if (auto ok = write_file_atomic(options_.schedule_dot, dot); !ok)
            return Error{"lantern: --schedule " + ok.error().message, 1};
        LANTERN_LOG_INFO("schedule written to %s (dot -Tsvg %s > schedule.svg)", options_.schedule_dot.c_str(),
                         options_.schedule_dot.c_str());
    }
    s->frame->warm_up();
    if (s->baker) { // the first frame shows the baked light: bake (or read) what the start needs
        const std::int64_t start = now_ns();
        s->baker->finish(w);
        const BakeStatus& b = w.resource<BakeStatus>();
        LANTERN_LOG_INFO("baked light: %d chunks (%llu baked, %llu from %s) in %.1f s", b.chunks,
                         static_cast<unsigned long long>(b.baked), static_cast<unsigned long long>(b.reused),
                         b.cache_dir.c_str(), double(now_ns() - start) * 1e-9);
        if (!b.last_warning.empty()) LANTERN_LOG_WARN("%s", b.last_warning.c_str());
    }
    if (options_.mode == RunMode::headless || !window_) {
        systems::Streaming& streaming = s->frame->streaming();
        const IsWall is_wall = [&streaming](int x, int z) { return streaming.is_wall({x, z}); };
        s->demo.emplace(is_wall, s->info.spawn, options_.frames, config.wall_height);
        w.resource<DayCycle>().day_length = s->demo->day_length();
    }
    LANTERN_LOG_INFO("world: %s, spawn (%.1f, %.1f)", s->info.description.c_str(), s->info.spawn.x, s->info.spawn.y);
    return s;
}

void Game::add_systems(ecs::Schedule& schedule, Session& s) {
    schedule.add("draw_list", [texel_lighting = options_.texel_lighting](ecs::SystemContext& ctx) {
        ecs::World& w = ctx.world;
        DrawListResource& r = w.resource<DrawListResource>();
        r.context = {};
        w.view<Camera>().each([&](const Camera& c) {
            if (auto* p = std::get_if<scene::PerspectiveCamera>(&c.view)) r.context.camera = *p;
        });
        const systems::Streaming& streaming = w.resource<systems::Streaming>();
        r.context.wall_height = w.resource<systems::GiConfig>().wall_height;
        r.context.time = w.resource<GameClock>().time;
        r.context.materials = &w.resource<systems::GiConfig>().materials;
        if (w.resource<BakeStatus>().enabled) r.context.probes = &w.resource<BakedChunks>();
        r.context.live_probes = w.resource<systems::GiConfig>().settings.probe_rays > 0;
        const IsWall is_wall = [&](int x, int z) { return streaming.is_wall({x, z}); };
        w.view<Player, Transform>().each([&](const Player&, const Transform& t) {
            if (auto target = cursor_target(w.resource<Controls>(), r.context.camera, {t.position.x, t.position.z},
                                            r.context.wall_height, is_wall)) {
                r.context.cursor_tile = target->first;
                r.context.cursor_on_wall = target->second;
            }
        });
        r.context.texel_lighting = texel_lighting;
        build_draw_list(w, streaming, r.context, r.list);
        gather_texel_lights(w, r.context, r.texel_lights);
    })
        .reads<Player, Transform, Prop, Torch, PointLight, EmissiveLight, Camera, ProbeAnchor, DroppedItem>()
        .reads_resource<Controls, GameClock, systems::GiConfig, systems::Streaming, BakedChunks, BakeStatus>()
        .reads_resource<GameTables>() // the lights' ambient colours
        .writes_resource<DrawListResource>();
    if (sound_)
        schedule.add("sound", [this](ecs::SystemContext& ctx) { sound_->update(ctx.world); })
            .main_thread() // OpenAL's context is the main thread's
            .reads<Player, Transform, Torch, PointLight>()
            .writes_resource<SoundCues>() // plays and empties them
            .after("interact")            // which adds them
            .after("collect_items");      // and so does this
    schedule.add("render", [this, &s](ecs::SystemContext&) { render_system(s); })
        .main_thread()
        .reads_resource<DrawListResource, systems::FramePasses, systems::GiView, systems::GatheredLights,
                        systems::GatheredProxies, GameClock, systems::Streaming, BakeStatus, Inventory>() // the HUD and hotbar show them
        .reads_resource<WorldEdits>() // the menu's quit question: anything unsaved?
        .reads<Player, Transform>()
        .writes_resource<systems::GiConfig, DayCycle>() // the HUD and the menu edit them live
        .after("day_cycle"); // both write DayCycle: the HUD's time of day takes effect next frame
}


int Game::run() {
    bool windowed = options_.mode == RunMode::window;
    if (options_.mode == RunMode::automatic) {
        const platform::DisplayProbe probe = platform::display_available();
        windowed = bool(probe);
        if (!windowed)
            std::fprintf(stderr, "lantern: no display (%s): running the headless demo (--headless to ask for it)\n",
                         probe.reason.c_str());
    }
    if (windowed) options_.mode = RunMode::window;
    else options_.mode = RunMode::headless;
    profile::set_enabled(true);
    profile::set_history_size(std::uint32_t(std::max(300, windowed ? 600 : options_.frames)));
    if (windowed) {
        // The pause menu's settings (a malformed file: its positioned error, exit 2).
        auto settings = read_settings(settings_path(options_));
        if (!settings) {
            std::fprintf(stderr, "lantern: %s (fix it, or delete it for the defaults)\n",
                         settings.error().message.c_str());
            return 2;
        }
        settings_ = *settings;
        if (!options_.given.vsync) options_.vsync = settings_.vsync;
        apply_settings(nullptr, false);
        auto_quality_ = options_.min_fps > 0 && settings_.gi_preset == GiPreset::world && !options_.given.gi &&
                        options_.world.kind != WorldKind::scene;
    }
    if (auto ok = init(windowed); !ok) {
        std::fprintf(stderr, "%s\n", ok.error().message.c_str());
        return ok.error().exit_code;
    }
    if (!options_.tables_file.empty()) {
        auto tables = read_tables(options_.tables_file);
        if (!tables) {
            std::fprintf(stderr, "lantern: %s\n", tables.error().message.c_str());
            return 2;
        }
        tables_ = std::move(*tables);
        if (options_.watch) tables_watch_.watch({options_.tables_file});
    }
    std::optional<SaveState> save;
    if (!options_.load.empty()) {
        auto state = read_save(options_.load);
        if (!state) {
            std::fprintf(stderr, "lantern: %s\n", state.error().message.c_str());
            return 2;
        }
        save = std::move(*state);
    }
    auto s = make_session(save ? save->world : options_.world, save ? &*save : nullptr);
    if (!s) {
        std::fprintf(stderr, "%s\n", s.error().message.c_str());
        return s.error().exit_code;
    }
    session_ = std::move(*s);
    mark_saved(*session_, false); // the game as it starts has nothing unsaved
    if (options_.watch && options_.world.kind == WorldKind::scene) {
        // The scene file and the files it reads (its world.map): an edit of either reloads.
        std::vector<std::string> files{options_.world.path};
        if (auto scene = scene::load_scene(options_.world.path))
            files.insert(files.end(), scene->inputs.begin(), scene->inputs.end());
        watched_.watch(files);
        std::string also;
        for (std::size_t i = 1; i < files.size(); ++i) also += (i == 1 ? " and " : ", ") + files[i];
        LANTERN_LOG_INFO("watching %s%s: edits reload the scene", options_.world.path.c_str(), also.c_str());
    }
    return windowed ? run_window() : run_headless();
}


void Game::poll_tables() {
    if (options_.tables_file.empty() || !tables_watch_.changed()) return;
    auto tables = read_tables(options_.tables_file);
    if (!tables) {
        ++reload_errors_;
        message_ = "tables not reloaded (the last good tables stay): " + tables.error().message;
        LANTERN_LOG_ERROR("%s", message_.c_str());
        return;
    }
    if (*tables == tables_) return;
    const std::int64_t start = now_ns();
    tables_ = std::move(*tables);
    apply_tables(session_->world, tables_, session_->info.spec.kind != WorldKind::scene);
    ++reloads_;
    message_ = "reloaded " + options_.tables_file;
    LANTERN_LOG_INFO("tables reloaded (%d): %.2f ms to apply them to the world", reloads_, double(now_ns() - start) * 1e-6);
}

void Game::poll_watch() {
    poll_tables();
    if (options_.world.kind != WorldKind::scene) return;
    const std::string& path = options_.world.path;
    if (!watched_.changed()) return;
    const std::int64_t seen = now_ns();
    auto scene = file_stamp(path) ? scene::load_scene(path) : Result<scene::Scene>(make_error(path + ": the file is gone"));
    if (!scene) {
        ++reload_errors_;
        pending_scene_.reset(); // a good edit followed by a bad one before the reload: neither
        message_ = "scene not reloaded (the last good scene stays): " + scene.error().message;
        LANTERN_LOG_ERROR("%s", message_.c_str());
        return;
    }
    // The scene may name another map now: watch the files this one read (a new list is
    // stamped now, after the read).
    std::vector<std::string> files{path};
    files.insert(files.end(), scene->inputs.begin(), scene->inputs.end());
    if (files != watched_.paths()) watched_.watch(std::move(files));
    pending_scene_ = std::move(*scene);
    change_seen_ns_ = seen;
}

Result<void> Game::reload_scene() {
    const scene::Scene scene = std::move(*pending_scene_);
    pending_scene_.reset();
    const bool from_editor = std::exchange(pending_from_editor_, false);
    // The player stays where it stood, and the time of day with it.
    std::optional<glm::vec2> player;
    session_->world.view<Player, Transform>().each(
        [&](const Player&, const Transform& t) { player = glm::vec2(t.position.x, t.position.z); });
    const DayCycle day = session_->world.resource<DayCycle>();
    device_->wait_idle();
    session_.reset();
    auto s = make_session(options_.world, nullptr, &scene);
    if (!s) return s.error(); // the scene was checked: only the device can fail here
    session_ = std::move(*s);
    ecs::World& w = session_->world;
    if (player && !session_->info.player.is_null()) {
        w.get<Transform>(session_->info.player).position = glm::vec3(player->x, 0.0f, player->y);
        if (PointLight* l = w.try_get<PointLight>(session_->info.player)) l->position = *player;
    }
    w.resource<DayCycle>().time_of_day = day.time_of_day;
    w.resource<DayCycle>().running = day.running;
    if (from_editor) {
        ++editor_rebuilds_;
        return {};
    }
    ++reloads_;
    message_ = "reloaded " + options_.world.path;
    LANTERN_LOG_INFO("scene reloaded (%d): %.1f ms from the change noticed to the new world", reloads_,
                     double(now_ns() - change_seen_ns_) * 1e-6);
    // The file changed under the editor: it edits the new file (its unsaved edits are gone
    // with the world they were made in).
    if (editor_.is_open() || editor_.unsaved()) {
        const bool had_edits = editor_.unsaved(), was_open = editor_.is_open();
        if (auto ok = editor_.open(options_.world.path); !ok) {
            editor_.close();
            LANTERN_LOG_ERROR("scene editor: %s", ok.error().message.c_str());
        } else if (!was_open) {
            editor_.close();
        }
        if (had_edits) {
            message_ = "the scene file changed on disk: the editor's unsaved edits were dropped for it";
            LANTERN_LOG_WARN("%s", message_.c_str());
        }
    }
    return {};
}

} // namespace lantern::game::app

namespace lantern::game {

int run_game(const GameOptions& options, std::vector<GameExtension> extensions) {
    if (auto ok = check_extensions(extensions); !ok) {
        std::fprintf(stderr, "lantern: %s\n", ok.error().message.c_str());
        return ok.error().exit_code;
    }
    app::Game game(options, std::move(extensions));
    return game.run();
}

} // namespace lantern::game

// The game loop. One frame is one run of the ECS schedule on the job graph:
//
//   input (main) ─► player_move ─► interact (main) ─► camera_view ─► streaming ─┐
//   torch_flicker, day_cycle ─────────────────────────► light/proxy gather ─────┼► cache_keys ─► gpu_submit (main)
//                                                                                └──────────► draw_list ─► render (main)
//
// `input` turns the window's keys and mouse (or the demo script) into Controls; the game
// systems move the player and edit the world; the GI systems submit this frame's GI passes;
// `render` records the raster pass that reads them, the upscale and the HUD, and presents.
#include "lantern/game/app.hpp"

#include "app/draw_list.hpp"
#include "app/hud.hpp"
#include "lantern/core/clock.hpp"
#include "lantern/core/file.hpp"
#include "lantern/core/json.hpp"
#include "lantern/core/log.hpp"
#include "lantern/core/machine.hpp"
#include "lantern/game/demo.hpp"
#include "lantern/game/gameplay.hpp"
#include "lantern/game/save.hpp"
#include "lantern/game/world_renderer.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/platform/window.hpp"
#include "lantern/profile/profiler.hpp"
#include "lantern/render/render.hpp"
#include "lantern/scene/loader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>

namespace lantern::game {
namespace {

constexpr const char* item_names[] = {"wall", "torch", "crystal", "lamp post", "tree"};
constexpr int warm_up_frames = 30; // left out of the headless percentiles (pipelines, first loads)

// The draw list as a world resource (written by draw_list, read by render).
struct DrawListResource {
    DrawList list;
    DrawContext context;
};

struct Session {
    ecs::World world;
    GameWorld info;
    std::unique_ptr<systems::GiFrame> frame;
    std::optional<DemoScript> demo;
    ~Session() { frame.reset(); } // the GI frame (and its jobs) before the world it uses
};

jobs::JobSystem::Config job_config(const GameOptions& o) {
    jobs::JobSystem::Config c;
    if (o.workers >= 0) c.worker_threads = o.workers;
    return c;
}

std::string json_escape(const std::string& s) {
    std::string out;
    for (char ch : s) {
        if (ch == '"' || ch == '\\') out += '\\';
        if (static_cast<unsigned char>(ch) < 0x20) continue;
        out += ch;
    }
    return out;
}

class Game {
  public:
    explicit Game(const GameOptions& options) : options_(options), jobs_(job_config(options)) {
        art_.posterize = options.posterize;
        art_.dither = options.dither;
    }
    ~Game() {
        if (device_) device_->wait_idle();
        session_.reset();
        overlay_.reset();
        swapchain_.reset();
        timer_.reset();
        world_renderer_.reset();
        gi_renderer_.reset();
        device_.reset();
        window_.reset();
    }

    int run();

  private:
    Result<void> init(bool windowed);
    Result<std::unique_ptr<Session>> make_session(const WorldSpec& spec, const SaveState* save);
    void add_systems(ecs::Schedule& schedule, Session& session);
    void input_system(Session& s);
    void render_system(Session& s);
    void record_world(gpu::CommandList& cmd, Session& s);
    void collect_raster_timings();
    void save(Session& s);
    void export_trace();
    void write_status(Session& s);
    int run_window();
    int run_headless();
    Result<void> write_headless_report(const std::vector<double>& frame_ms, const std::vector<bool>& walking,
                                       const std::vector<std::string>& screenshots, double seconds);

    GameOptions options_;
    jobs::JobSystem jobs_;
    std::optional<platform::Window> window_;
    std::unique_ptr<gpu::Device> device_;
    std::optional<render::Swapchain> swapchain_;
    std::optional<render::ImGuiOverlay> overlay_;
    std::optional<render::PassTimer> timer_;
    std::unique_ptr<gi::vk::Renderer> gi_renderer_;
    std::unique_ptr<WorldRenderer> world_renderer_;
    std::unique_ptr<Session> session_;
    std::uint32_t raster_lane_ = 0;
    ArtSettings art_;
    Hud hud_;
    render::PresentRect present_rect_;
    std::int64_t last_frame_ns_ = 0;
    double last_mine_time_ = -1.0;
    int selected_item_ = 1; // torch
    int headless_frame_ = 0;
    std::uint64_t window_frames_ = 0; // windowed frames stepped (--status-file)
    int saves_done_ = 0;              // successful saves (--status-file)
    bool save_requested_ = false;     // F5 or the HUD: saved between frames, outside the systems
    bool status_failed_ = false;      // the status file could not be written (said once)
    bool quit_ = false;
    std::optional<SaveState> pending_load_;
    std::string message_;
    std::uint64_t raster_serials_[2] = {0, 0};
};

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
    auto wr = WorldRenderer::create(*device_, options_.internal);
    if (!wr) return Error{"lantern: " + wr.error().message, 1};
    world_renderer_ = std::move(*wr);
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
    return {};
}

Result<std::unique_ptr<Session>> Game::make_session(const WorldSpec& spec, const SaveState* save) {
    auto s = std::make_unique<Session>();
    ecs::World& w = s->world;
    w.set_resource<Controls>();
    w.set_resource<GameClock>();
    DayCycle day;
    day.time_of_day = 0.85f; // night: torches and crystals carry the caves
    day.drives_sun = spec.kind != WorldKind::scene;
    w.set_resource<DayCycle>(day);
    CameraRig rig;
    rig.aspect = float(options_.internal.x) / float(options_.internal.y);
    w.set_resource<CameraRig>(rig);
    w.set_resource<DrawListResource>();

    WorldOptions wo;
    wo.gi = options_.gi;
    wo.player_light = options_.player_light;
    auto created = create_world(spec, w, wo);
    if (!created) return created.error();
    s->info = std::move(*created);
    systems::GiConfig config = s->info.config;
    if (spec.kind == WorldKind::scene) {
        // The scene's own settings, with the command line's overrides on top.
        scene::Scene tmp;
        tmp.gi = config.settings;
        for (const std::string& o : options_.gi_overrides)
            if (auto ok = scene::apply_override(tmp, o); !ok) return Error{"lantern: " + ok.error().message, 2};
        config.settings = tmp.gi;
    }
    if (save) apply_save(*save, w, s->info.player);

    systems::GiFrameOptions fo;
    Session* session = s.get();
    fo.add_game_systems = [this, session](ecs::Schedule& schedule) {
        schedule.add("input", [this, session](ecs::SystemContext&) { input_system(*session); })
            .main_thread()
            .reads<Player, Transform, Camera>()
            .reads_resource<systems::Streaming>() // the demo script looks at the walls
            .writes_resource<Controls, GameClock>();
        add_gameplay_systems(schedule);
    };
    s->frame = std::make_unique<systems::GiFrame>(w, jobs_, s->info.source, systems::make_vulkan_backend(*gi_renderer_),
                                                  config, std::move(fo));
    if (save) s->frame->streaming().restore_edits(save->edits);
    add_systems(s->frame->schedule(), *s);
    s->frame->warm_up();
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
    schedule.add("draw_list", [](ecs::SystemContext& ctx) {
        ecs::World& w = ctx.world;
        DrawListResource& r = w.resource<DrawListResource>();
        r.list.boxes.clear();
        r.context = {};
        w.view<Camera>().each([&](const Camera& c) {
            if (auto* p = std::get_if<scene::PerspectiveCamera>(&c.view)) r.context.camera = *p;
        });
        const systems::Streaming& streaming = w.resource<systems::Streaming>();
        r.context.wall_height = w.resource<systems::GiConfig>().wall_height;
        r.context.time = w.resource<GameClock>().time;
        const IsWall is_wall = [&](int x, int z) { return streaming.is_wall({x, z}); };
        w.view<Player, Transform>().each([&](const Player&, const Transform& t) {
            if (auto target = cursor_target(w.resource<Controls>(), r.context.camera, {t.position.x, t.position.z},
                                            r.context.wall_height, is_wall)) {
                r.context.cursor_tile = target->first;
                r.context.cursor_on_wall = target->second;
            }
        });
        build_draw_list(w, streaming, r.context, r.list);
    })
        .reads<Player, Transform, Prop, Torch, PointLight, EmissiveLight, Camera>()
        .reads_resource<Controls, GameClock, systems::GiConfig, systems::Streaming>()
        .writes_resource<DrawListResource>();
    schedule.add("render", [this, &s](ecs::SystemContext&) { render_system(s); })
        .main_thread()
        .reads_resource<DrawListResource, systems::FramePasses, systems::GiView, systems::GatheredLights,
                        systems::GatheredProxies, GameClock>()
        .writes_resource<systems::GiConfig, DayCycle>(); // the HUD edits them live
}

void Game::input_system(Session& s) {
    ecs::World& w = s.world;
    GameClock& clock = w.resource<GameClock>();
    const std::int64_t now = now_ns();
    const bool fixed = options_.fixed_step || s.demo;
    clock.dt = fixed || last_frame_ns_ == 0 ? 1.0f / 60.0f
                                            : float(std::clamp(double(now - last_frame_ns_) * 1e-9, 0.0, 0.1));
    last_frame_ns_ = now;
    clock.time += clock.dt;
    Controls& c = w.resource<Controls>();
    c = {};

    glm::vec2 player(0.0f);
    w.view<Player, Transform>().each([&](const Player&, const Transform& t) { player = {t.position.x, t.position.z}; });
    scene::PerspectiveCamera camera;
    w.view<Camera>().each([&](const Camera& cam) {
        if (auto* p = std::get_if<scene::PerspectiveCamera>(&cam.view)) camera = *p;
    });
    if (s.demo) {
        systems::Streaming& streaming = s.frame->streaming();
        const IsWall is_wall = [&](int x, int z) { return streaming.is_wall({x, z}); };
        c = s.demo->controls(headless_frame_, player, camera, is_wall);
        return;
    }

    window_->poll();
    const platform::InputState& in = window_->input();
    using platform::Key;
    if (window_->should_close() || in.pressed(Key::escape)) quit_ = true;
    const bool keyboard_free = !overlay_ || !overlay_->wants_keyboard();
    const bool mouse_free = !overlay_ || !hud_.visible || !overlay_->wants_mouse();
    if (keyboard_free) {
        if (in.pressed(Key::f1)) hud_.visible = !hud_.visible;
        if (in.pressed(Key::f2)) export_trace();
        if (in.pressed(Key::f5)) save_requested_ = true; // after the frame: a save reads the whole world
        if (in.pressed(Key::f9)) {
            if (auto state = read_save(options_.save_file)) {
                pending_load_ = std::move(*state);
            } else {
                message_ = state.error().message;
                LANTERN_LOG_WARN("%s", message_.c_str());
            }
        }
        for (int i = 0; i < 5; ++i)
            if (in.pressed(Key(int(Key::digit_1) + i))) selected_item_ = i;
        glm::vec2 move(0.0f);
        if (in.down(Key::w) || in.down(Key::up)) move.y -= 1.0f; // screen up is -z
        if (in.down(Key::s) || in.down(Key::down)) move.y += 1.0f;
        if (in.down(Key::a) || in.down(Key::left)) move.x -= 1.0f;
        if (in.down(Key::d) || in.down(Key::right)) move.x += 1.0f;
        c.move = move;
        c.toggle_day_cycle = in.pressed(Key::n);
    }
    if (mouse_free) {
        const platform::Extent source{std::uint32_t(options_.internal.x), std::uint32_t(options_.internal.y)};
        if (auto p = render::destination_to_source(present_rect_, source, in.mouse_position())) {
            c.has_cursor = true;
            c.cursor_ndc = *p / glm::vec2(options_.internal);
        }
        // Holding the left button keeps mining, a wall every 0.2 s.
        const bool mine_held = in.down(platform::MouseButton::left) && clock.time - last_mine_time_ > 0.2;
        if (in.pressed(platform::MouseButton::left) || mine_held) {
            c.mine = true;
            last_mine_time_ = clock.time;
        }
        if (in.pressed(platform::MouseButton::right)) {
            bool Controls::*items[] = {&Controls::place_wall, &Controls::place_torch, &Controls::place_crystal,
                                       &Controls::place_lamp, &Controls::place_tree};
            c.*items[selected_item_] = true;
        }
    }
}

void Game::record_world(gpu::CommandList& cmd, Session& s) {
    ecs::World& w = s.world;
    const DrawListResource& draws = w.resource<DrawListResource>();
    const systems::GiView& gv = w.resource<systems::GiView>();
    WorldView view;
    view.camera = draws.context.camera;
    view.gi = gv.window ? &w.resource<systems::FramePasses>().inputs : nullptr;
    view.renderer = gi_renderer_.get();
    view.art = art_;
    view.time = float(w.resource<GameClock>().time);
    std::uint32_t region = 0;
    if (timer_) {
        timer_->begin_frame(cmd, profile::frame_index());
        region = timer_->begin(cmd, "world raster");
    }
    world_renderer_->record(cmd, view, draws.list);
    if (timer_) timer_->end(cmd, region);
}

void Game::collect_raster_timings() {
    if (!timer_) return;
    for (const render::FrameTimings& t : timer_->take_completed())
        for (const gpu::TimestampRegion& r : t.passes)
            profile::record_gpu(raster_lane_, t.frame, r.name, r.cpu_begin_ns, r.cpu_end_ns);
}

void Game::render_system(Session& s) {
    LANTERN_PROFILE_SCOPE("render");
    ecs::World& w = s.world;
    if (!window_) {
        // Headless: at most two raster frames in flight.
        const int slot = headless_frame_ & 1;
        if (raster_serials_[slot]) device_->wait(raster_serials_[slot]);
        gpu::CommandList cmd = device_->begin("raster frame");
        record_world(cmd, s);
        raster_serials_[slot] = device_->submit(std::move(cmd));
        collect_raster_timings();
        return;
    }
    std::optional<render::SwapchainFrame> frame = swapchain_->acquire(window_->framebuffer_size());
    if (!frame) return; // minimised: nothing to draw
    const bool hud = hud_.visible && overlay_;
    HudActions actions;
    if (hud) {
        overlay_->new_frame();
        systems::FrameReport report;
        const systems::FramePasses& f = w.resource<systems::FramePasses>();
        report.ran = f.run;
        report.reason = f.reason;
        report.window = w.resource<systems::GiView>().window;
        HudInputs in;
        in.report = &report;
        in.config = &w.resource<systems::GiConfig>();
        in.art = &art_;
        in.day = &w.resource<DayCycle>();
        in.lights = &w.resource<systems::GatheredLights>();
        in.proxies = &w.resource<systems::GatheredProxies>();
        in.streaming = s.frame->streaming().stats();
        in.entities = w.alive_count();
        in.world = s.info.description;
        in.message = message_;
        in.item = item_names[selected_item_];
        in.vsync = swapchain_->vsync();
        in.device = device_->name();
        actions = hud_.draw(in);
    }
    gpu::CommandList cmd = device_->begin("raster frame");
    record_world(cmd, s);
    const VkExtent2D size = frame->image().extent();
    const platform::Extent source{std::uint32_t(options_.internal.x), std::uint32_t(options_.internal.y)};
    present_rect_ = render::fit_integer_scale(source, {size.width, size.height});
    render::record_upscale(cmd, world_renderer_->target().color(), frame->image(), present_rect_,
                           hud ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    if (hud) overlay_->record(cmd, frame->image());
    swapchain_->present(std::move(*frame), std::move(cmd));
    collect_raster_timings();
    if (actions.export_trace) export_trace();
    if (actions.save) save_requested_ = true;
    if (actions.load) {
        if (auto state = read_save(options_.save_file)) pending_load_ = std::move(*state);
        else message_ = state.error().message;
    }
    if (actions.toggle_vsync) swapchain_->set_vsync(!swapchain_->vsync());
}

void Game::save(Session& s) {
    const SaveState state = capture_save(s.world, s.frame->streaming(), s.info.spec);
    if (auto ok = write_save(options_.save_file, state); !ok) {
        message_ = "save failed: " + ok.error().message;
        LANTERN_LOG_ERROR("%s", message_.c_str());
        return;
    }
    ++saves_done_;
    message_ = "saved to " + options_.save_file + " (" + std::to_string(state.entities.size()) + " lights and props, " +
               std::to_string(state.edits.size()) + " edited chunks)";
    LANTERN_LOG_INFO("%s", message_.c_str());
}

// One JSON line, replaced atomically after each windowed frame: what a script driving the game
// through real input waits on (the frame that saw its input, where the player is) instead of
// sleeping for a guessed time.
void Game::write_status(Session& s) {
    glm::vec2 player(0.0f);
    s.world.view<Player, Transform>().each([&](const Player&, const Transform& t) { player = {t.position.x, t.position.z}; });
    const platform::InputState& in = window_->input();
    char line[320];
    std::snprintf(line, sizeof line,
                  "{\"frame\": %llu, \"player\": [%.4f, %.4f], \"mouse\": [%.1f, %.1f], \"buttons\": [%d, %d], "
                  "\"item\": %d, \"saves\": %d}\n",
                  static_cast<unsigned long long>(window_frames_), double(player.x), double(player.y),
                  double(in.mouse_position().x), double(in.mouse_position().y), int(in.down(platform::MouseButton::left)),
                  int(in.down(platform::MouseButton::right)), selected_item_ + 1, saves_done_);
    if (auto ok = write_file_atomic(options_.status_file, std::string(line)); !ok && !status_failed_) {
        status_failed_ = true;
        LANTERN_LOG_ERROR("status file: %s", ok.error().message.c_str());
    }
}

void Game::export_trace() {
    const std::string path = (window_ ? std::string("lantern-trace.json") : options_.out_dir + "/trace.json");
    if (auto ok = profile::write_chrome_trace(path, std::uint32_t(hud_.graph_frames)); !ok) {
        message_ = "trace export failed: " + ok.error().message;
        LANTERN_LOG_ERROR("%s", message_.c_str());
        return;
    }
    message_ = "Chrome trace of the last " + std::to_string(hud_.graph_frames) + " frames written to " + path +
               " (open in chrome://tracing or ui.perfetto.dev)";
    LANTERN_LOG_INFO("%s", message_.c_str());
}

int Game::run_window() {
    while (!quit_) {
        profile::begin_frame();
        session_->frame->step();
        profile::end_frame();
        ++window_frames_;
        if (save_requested_) {
            save_requested_ = false;
            save(*session_);
        }
        if (!options_.status_file.empty()) write_status(*session_);
        if (pending_load_) {
            device_->wait_idle();
            const SaveState state = std::move(*pending_load_);
            pending_load_.reset();
            session_.reset();
            auto s = make_session(state.world, &state);
            if (!s) {
                LANTERN_LOG_ERROR("%s", s.error().message.c_str());
                return s.error().exit_code;
            }
            session_ = std::move(*s);
            message_ = "loaded " + options_.save_file;
        }
        if (window_->minimised()) window_->poll_wait(0.1);
    }
    return 0;
}

int Game::run_headless() {
    if (auto ok = ensure_directory(options_.out_dir); !ok) {
        std::fprintf(stderr, "lantern: %s\n", ok.error().message.c_str());
        return 1;
    }
    const int frames = options_.frames;
    std::vector<int> shots;
    for (int k = 1; k <= options_.screenshots; ++k) shots.push_back(std::min(frames - 1, k * frames / options_.screenshots - 1));
    std::vector<double> frame_ms;
    std::vector<bool> walking;
    std::vector<std::string> screenshots;
    const std::int64_t start = now_ns();
    std::fprintf(stderr, "lantern: headless demo, %d frames at %dx%d, %s -> %s/\n", frames, options_.internal.x,
                 options_.internal.y, session_->info.description.c_str(), options_.out_dir.c_str());
    for (headless_frame_ = 0; headless_frame_ < frames; ++headless_frame_) {
        profile::begin_frame();
        const std::int64_t t0 = now_ns();
        session_->frame->step();
        const std::int64_t t1 = now_ns();
        profile::end_frame();
        frame_ms.push_back(double(t1 - t0) * 1e-6);
        walking.push_back(session_->demo->is_walking(headless_frame_));
        if (std::find(shots.begin(), shots.end(), headless_frame_) != shots.end()) {
            char name[64];
            std::snprintf(name, sizeof(name), "frame_%05d.png", headless_frame_);
            const std::string path = options_.out_dir + "/" + name;
            device_->wait_idle();
            if (auto ok = render::write_png(path, world_renderer_->target().read_back()); !ok) {
                std::fprintf(stderr, "lantern: %s\n", ok.error().message.c_str());
                return 1;
            }
            screenshots.push_back(name);
            frame_ms.back() = -1.0; // the next frame starts on an idle GPU: not counted
        }
        if ((headless_frame_ + 1) % std::max(1, frames / 10) == 0 || headless_frame_ + 1 == frames) {
            std::vector<double> recent(frame_ms.end() - std::min<std::ptrdiff_t>(std::ptrdiff_t(frame_ms.size()), 30), frame_ms.end());
            std::erase_if(recent, [](double v) { return v < 0; });
            const auto p = profile::percentiles(recent);
            std::fprintf(stderr, "  frame %d/%d (%d %%): %.1f ms/frame over the last %u\n", headless_frame_ + 1, frames,
                         (headless_frame_ + 1) * 100 / frames, p.mean, p.count);
        }
    }
    device_->wait_idle();
    collect_raster_timings();
    const double seconds = double(now_ns() - start) * 1e-9;
    if (auto ok = write_headless_report(frame_ms, walking, screenshots, seconds); !ok) {
        std::fprintf(stderr, "lantern: %s\n", ok.error().message.c_str());
        return 1;
    }
    return 0;
}

Result<void> Game::write_headless_report(const std::vector<double>& frame_ms, const std::vector<bool>& walking,
                                         const std::vector<std::string>& screenshots, double seconds) {
    std::vector<double> all, walk;
    for (std::size_t i = std::size_t(warm_up_frames); i < frame_ms.size(); ++i) {
        if (frame_ms[i] < 0 || (i > 0 && frame_ms[i - 1] < 0)) continue;
        all.push_back(frame_ms[i]);
        if (walking[i]) walk.push_back(frame_ms[i]);
    }
    const profile::Percentiles pa = profile::percentiles(all), pw = profile::percentiles(walk);
    const auto stats = profile::stats();
    const scene::GiSettings& gi = session_->world.resource<systems::GiConfig>().settings;

    std::ostringstream json;
    auto pct = [](const profile::Percentiles& p) {
        char buf[200];
        std::snprintf(buf, sizeof(buf), "{\"frames\": %u, \"mean\": %.3f, \"p50\": %.3f, \"p95\": %.3f, \"p99\": %.3f, \"max\": %.3f}",
                      p.count, p.mean, p.p50, p.p95, p.p99, p.max);
        return std::string(buf);
    };
    json << "{\n  \"machine\": \"" << json_escape(describe_machine()) << "\",\n";
    json << "  \"device\": \"" << json_escape(device_->name()) << "\",\n";
    json << "  \"world\": \"" << json_escape(session_->info.description) << "\",\n";
    json << "  \"frames\": " << frame_ms.size() << ", \"warm_up_frames\": " << warm_up_frames
         << ", \"seconds\": " << seconds << ",\n";
    json << "  \"internal_resolution\": [" << options_.internal.x << ", " << options_.internal.y << "],\n";
    json << "  \"gi\": {\"resolution\": " << gi.resolution << ", \"heat_rounds\": " << gi.heat_rounds
         << ", \"heat_scale\": " << int(gi.heat_scale) << ", \"padding\": " << gi.padding
         << ", \"max_lights\": " << gi.max_lights << "},\n";
    json << "  \"frame_ms\": " << pct(pa) << ",\n  \"frame_ms_walking\": " << pct(pw) << ",\n";
    json << "  \"scopes\": [";
    bool first = true;
    for (const auto& s : stats) {
        char buf[320];
        std::snprintf(buf, sizeof(buf),
                      "%s\n    {\"name\": \"%s\", \"lane\": \"%s\", \"frames\": %u, \"p50\": %.3f, \"p95\": %.3f, \"p99\": %.3f, \"max\": %.3f}",
                      first ? "" : ",", json_escape(s.name).c_str(), s.kind == profile::LaneKind::gpu ? "gpu" : "cpu",
                      s.frames_seen, s.p50_ms, s.p95_ms, s.p99_ms, s.max_ms);
        json << buf;
        first = false;
    }
    json << "\n  ],\n  \"screenshots\": [";
    for (std::size_t i = 0; i < screenshots.size(); ++i) json << (i ? ", " : "") << "\"" << screenshots[i] << "\"";
    json << "]\n}\n";
    if (auto ok = write_file_atomic(options_.out_dir + "/timings.json", json.str()); !ok) return ok;
    if (auto ok = write_file_atomic(options_.out_dir + "/profile.txt", profile::text_report()); !ok) return ok;
    if (auto ok = profile::write_chrome_trace(options_.out_dir + "/trace.json", 300); !ok) return ok;

    std::printf("lantern headless demo: %zu frames in %.1f s on %s (%s)\n", frame_ms.size(), seconds,
                device_->name().c_str(), describe_machine().c_str());
    std::printf("world: %s; GI resolution %d, %d heat rounds at 1/%d, internal %dx%d\n",
                session_->info.description.c_str(), gi.resolution, gi.heat_rounds, int(gi.heat_scale),
                options_.internal.x, options_.internal.y);
    std::printf("frame ms (after %d warm-up frames):   p50 %6.2f  p95 %6.2f  p99 %6.2f  max %6.2f  (%u frames)\n",
                warm_up_frames, pa.p50, pa.p95, pa.p99, pa.max, pa.count);
    std::printf("frame ms while walking:               p50 %6.2f  p95 %6.2f  p99 %6.2f  max %6.2f  (%u frames) -> %.1f fps at p95\n",
                pw.p50, pw.p95, pw.p99, pw.max, pw.count, pw.p95 > 0 ? 1000.0 / pw.p95 : 0.0);
    if (options_.bench) {
        std::printf("\n%-28s %5s %8s %8s %8s %8s\n", "scope / system / GPU pass", "lane", "p50", "p95", "p99", "max");
        for (const auto& s : stats)
            std::printf("%-28s %5s %8.2f %8.2f %8.2f %8.2f\n", s.name, s.kind == profile::LaneKind::gpu ? "gpu" : "cpu",
                        s.p50_ms, s.p95_ms, s.p99_ms, s.max_ms);
    }
    std::printf("wrote %s/{timings.json, profile.txt, trace.json} and %zu screenshots\n", options_.out_dir.c_str(),
                screenshots.size());
    return {};
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
    if (auto ok = init(windowed); !ok) {
        std::fprintf(stderr, "%s\n", ok.error().message.c_str());
        return ok.error().exit_code;
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
    return windowed ? run_window() : run_headless();
}

} // namespace

int run_game(const GameOptions& options) {
    Game game(options);
    return game.run();
}

} // namespace lantern::game

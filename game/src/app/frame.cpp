// The systems the application adds to each frame: input (keys, mouse or the demo script into
// Controls) and render (the raster pass, the upscale, the HUD, present).
#include "app/game.hpp"

#include <imgui.h>

namespace lantern::game::app {

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
    input_camera_ = camera;
    if (s.demo) {
        systems::Streaming& streaming = s.frame->streaming();
        const IsWall is_wall = [&](int x, int z) { return streaming.is_wall({x, z}); };
        c = s.demo->controls(headless_frame_, player, camera, is_wall);
        return;
    }

    window_->poll();
    const platform::InputState& in = window_->input();
    using platform::Key;
    // A close request (the window's close button, the window manager) asks first when
    // something is unsaved; Escape opens the pause menu, and in it goes back a page.
    if (window_->should_close()) quit_or_ask(s);
    if (in.pressed(Key::escape)) {
        if (menu_.is_open()) menu_.back();
        else menu_.open();
    }
    if (menu_.is_open()) { // paused: no time passes, no input reaches the world
        clock.time -= clock.dt;
        clock.dt = 0.0f;
        return;
    }
    const bool keyboard_free = !overlay_ || !overlay_->wants_keyboard();
    const bool mouse_free = !overlay_ || !(hud_.visible || editor_.is_open()) || !overlay_->wants_mouse();
    const KeyBindings& keys = settings_.keys;
    const auto key_pressed = [&](Action a) { return in.pressed(keys[std::size_t(a)]); };
    const auto key_down = [&](Action a) { return in.down(keys[std::size_t(a)]); };
    if (keyboard_free) {
        if (key_pressed(Action::toggle_hud)) hud_.visible = !hud_.visible;
        if (key_pressed(Action::trace)) export_trace();
        if (key_pressed(Action::quick_save)) save_slot_requested_ = 1; // after the frame: a save reads the whole world
        if (key_pressed(Action::quick_load)) {
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
        if (key_down(Action::walk_up) || in.down(Key::up)) move.y -= 1.0f; // screen up is -z
        if (key_down(Action::walk_down) || in.down(Key::down)) move.y += 1.0f;
        if (key_down(Action::walk_left) || in.down(Key::left)) move.x -= 1.0f;
        if (key_down(Action::walk_right) || in.down(Key::right)) move.x += 1.0f;
        c.move = move;
        c.toggle_day_cycle = key_pressed(Action::day_cycle);
        if (key_pressed(Action::scene_editor)) toggle_editor(s);
        if (editor_.is_open()) {
            if (in.pressed(Key::del)) apply_edit(editor_.remove_selected());
            if (in.pressed_with_control(Key::s)) save_scene_edits(); // Control held when S went down, even if up by now
        }
    }
    cursor_world_.reset();
    if (mouse_free) {
        const platform::Extent source{std::uint32_t(internal_.x), std::uint32_t(internal_.y)};
        if (auto p = render::destination_to_source(present_rect_, source, in.mouse_position())) {
            c.has_cursor = true;
            c.cursor_ndc = *p / glm::vec2(internal_);
            cursor_world_ = ground_point(camera_ray(camera, c.cursor_ndc));
        }
        if (editor_.is_open()) { // the mouse edits the scene instead of the world
            if (cursor_world_ && in.pressed(platform::MouseButton::left)) editor_.select_near(*cursor_world_);
            if (cursor_world_ && in.pressed(platform::MouseButton::right)) apply_edit(editor_.move_selected(*cursor_world_));
            return;
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

void Game::quit_or_ask(Session& s) {
    if (!unsaved(s) && !editor_.unsaved()) {
        quit_ = true;
        return;
    }
    window_->cancel_close();
    menu_.ask_quit();
}

void Game::apply_settings(Session* s, bool gi) {
    if (swapchain_ && !options_.given.vsync && swapchain_->vsync() != settings_.vsync) swapchain_->set_vsync(settings_.vsync);
    if (!options_.given.posterize) art_.posterize = settings_.posterize;
    if (!options_.given.dither) art_.dither = settings_.dither;
    if (options_.palette.empty()) art_.palette = settings_.palette; // --palette wins (init sets it)
    world_bounce_ = {settings_.world_self, settings_.world_bleed};
    character_bounce_ = {settings_.character_self, settings_.character_bleed};
    if (sound_) sound_->mixer().set_volume(float(settings_.volume) / 100.0f);
    if (gi && s) // the HUD's live GI edits are replaced
        if (auto g = session_gi(s->info)) s->world.resource<systems::GiConfig>().settings = *g;
}

Result<scene::GiSettings> Game::session_gi(const GameWorld& info) const {
    scene::Scene tmp;
    tmp.gi = info.config.settings; // a scene's own; elsewhere the game's defaults, --set applied
    if (info.spec.kind == WorldKind::scene) // the command line's overrides on top
        for (const std::string& o : options_.gi_overrides)
            if (auto ok = scene::apply_override(tmp, o); !ok) return Error{"lantern: " + ok.error().message, 2};
    if (window_ && settings_.gi_preset != GiPreset::world) {
        apply_gi_preset(settings_.gi_preset, tmp.gi);
        for (const std::string& o : options_.gi_overrides) (void)scene::apply_override(tmp, o); // still the last word
    }
    return tmp.gi;
}

bool Game::fit_internal_to_window() {
    if (options_.internal_fixed || !window_) return false;
    const platform::Extent design{std::uint32_t(options_.internal.x), std::uint32_t(options_.internal.y)};
    const platform::Extent fill = settings_.pixel_scale > 0
                                      ? render::fill_at_scale(design, window_->framebuffer_size(), std::uint32_t(settings_.pixel_scale))
                                      : render::fill_integer_scale(design, window_->framebuffer_size());
    const glm::ivec2 size(int(fill.width), int(fill.height));
    if (fill.empty() || size == internal_) return false; // minimised, or unchanged
    internal_ = size;
    return true;
}

void Game::follow_window_size() {
    if (!fit_internal_to_window()) return;
    // Between frames: nothing is recording. The old target is retired after the frames in
    // flight; the camera keeps its field of view with the new aspect.
    if (auto ok = world_renderer_->resize(internal_); !ok) LANTERN_LOG_ERROR("%s", ok.error().message.c_str());
    session_->world.resource<CameraRig>().aspect = float(internal_.x) / float(internal_.y);
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
    view.world_bounce = world_bounce_;
    view.character_bounce = character_bounce_;
    view.gi_view = gi_view_;
    view.time = float(w.resource<GameClock>().time);
    std::uint32_t region = 0;
    if (timer_) timer_->begin_frame(cmd, profile::frame_index());
    if (texel_world_ && !draws.list.texel_parts.empty()) {
        // The models' light per texel (docs/texel.md, "In the game"), under the gathered lights
        // and the GI's suns, against the GI's view of the walls.
        std::vector<texel::TexelLight>& lights = texel_lights_;
        lights.assign(draws.texel_lights.begin(), draws.texel_lights.end());
        if (view.gi)
            for (const gi::GpuDirectionalLight& sun : view.gi->directional_lights)
                lights.push_back(texel::make_sun(glm::vec3(sun.direction_base), glm::vec3(sun.color_multiplier), 1.0f,
                                                 texel::ShadowType::hard, 24.0f));
        // Each texel row the plan runs is a region of the pass timer, named by its row.
        struct RowTimer final : texel::vk::TexelRowTimer {
            render::PassTimer& timer;
            explicit RowTimer(render::PassTimer& t) : timer(t) {}
            std::uint32_t begin(gpu::CommandList& c, const char* row) override { return timer.begin(c, row); }
            void end(gpu::CommandList& c, std::uint32_t r) override { timer.end(c, r); }
        };
        std::optional<RowTimer> rows;
        if (timer_) rows.emplace(*timer_);
        texel_world_->record(cmd, draws.list.texel_parts, lights, view.gi ? view.gi->walls : gi::WallView{},
                             draws.context.wall_height, rows ? &*rows : nullptr);
        view.texel_lit = &texel_world_->lit();
        view.texel_surfaces = &texel_world_->surfaces();
        view.texel_albedo = &texel_world_->albedo();
        view.texel_records = texel_world_->records();
    }
    if (timer_) region = timer_->begin(cmd, "world raster");
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
    // No profile scope of its own: the job system records the "render" job's span, and a scope
    // of the same name was added to it in the stats (the HUD showed render's time doubled).
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
    if (overlay_) overlay_->new_frame(); // the hotbar is drawn with the HUD hidden too
    if (hud) {
        systems::FrameReport report;
        const systems::FramePasses& f = w.resource<systems::FramePasses>();
        report.ran = f.run;
        report.reason = f.reason;
        report.window = w.resource<systems::GiView>().window;
        HudInputs in;
        in.report = &report;
        in.config = &w.resource<systems::GiConfig>();
        in.art = &art_;
        in.world_bounce = &world_bounce_;
        in.character_bounce = &character_bounce_;
        in.gi_view = &gi_view_;
        in.gi_view_drawn = world_renderer_->gi_view_drawn();
        const bool gather = f.inputs.settings.method == scene::GiMethod::gather;
        in.converge_history = f.plan.history[int(gather ? gi::Pass::gather : gi::Pass::radiosity)];
        in.day = &w.resource<DayCycle>();
        in.lights = &w.resource<systems::GatheredLights>();
        in.proxies = &w.resource<systems::GatheredProxies>();
        in.streaming = s.frame->streaming().stats();
        if (s.baker) in.bake = &s.world.resource<BakeStatus>();
        in.schedule = &s.schedule;
        in.entities = w.alive_count();
        in.world = s.info.description;
        in.message = message_;
        in.item = item_names[selected_item_];
        in.vsync = swapchain_->vsync();
        in.device = device_->name();
        actions = hud_.draw(in);
    }
    if (overlay_ && w.has_resource<Inventory>()) draw_hotbar(w.resource<Inventory>(), selected_item_);
    EditResult edit;
    if (overlay_ && editor_.is_open() && !menu_.is_open()) {
        draw_editor_markers();
        edit = editor_.draw(player_xz(w), message_);
    }
    MenuActions menu;
    if (overlay_) {
        const MenuPage page_before = menu_.page();
        const PlayerSettings before = settings_;
        MenuInputs mi;
        mi.settings = &settings_;
        mi.input = &window_->input();
        mi.unsaved = unsaved(s) || editor_.unsaved();
        if (editor_.unsaved()) mi.unsaved_scene = editor_.path();
        if (menu_.page() == MenuPage::save) mi.save_slots = slot_views(false);
        if (menu_.page() == MenuPage::load) mi.load_slots = slot_views(true);
        mi.message = message_;
        menu = menu_.draw(mi);
        if (settings_ != before) {
            if (settings_.gi_preset != before.gi_preset) auto_quality_ = false; // the player's choice stands
            apply_settings(&s, settings_.gi_preset != before.gi_preset);
            settings_dirty_ = true;
        }
        // Written when the player leaves the settings pages (not at every slider step).
        const bool on_settings = menu_.page() == MenuPage::settings || menu_.page() == MenuPage::keys;
        if (settings_dirty_ && !on_settings && page_before != menu_.page()) write_settings_file();
        if (settings_dirty_ && !menu_.is_open()) write_settings_file();
    }
    gpu::CommandList cmd = device_->begin("raster frame");
    record_world(cmd, s);
    const VkExtent2D size = frame->image().extent();
    const platform::Extent source{std::uint32_t(internal_.x), std::uint32_t(internal_.y)};
    present_rect_ = render::fit_integer_scale(source, {size.width, size.height});
    render::record_upscale(cmd, world_renderer_->target().color(), frame->image(), present_rect_,
                           overlay_ ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
    if (overlay_) overlay_->record(cmd, frame->image());
    swapchain_->present(std::move(*frame), std::move(cmd));
    collect_raster_timings();
    apply_edit(edit);
    if (edit.save) save_scene_edits();
    if (edit.close) toggle_editor(s);
    if (actions.export_trace) export_trace();
    if (actions.save) save_slot_requested_ = 1;
    if (menu.save_slot) save_slot_requested_ = menu.save_slot;
    if (menu.save_and_quit) {
        // The scene editor's edits first: a failure stays in the game and says why.
        if (!editor_.unsaved() || save_scene_edits()) {
            save_slot_requested_ = 1;
            quit_after_save_ = true;
        }
    }
    if (menu.quit) quit_ = true;
    if (!menu.load_path.empty()) {
        if (auto state = read_save(menu.load_path)) {
            pending_load_ = std::move(*state);
            menu_.close();
        } else {
            message_ = state.error().message;
        }
    }
    if (actions.load) {
        if (auto state = read_save(options_.save_file)) pending_load_ = std::move(*state);
        else message_ = state.error().message;
    }
    if (actions.toggle_vsync) {
        swapchain_->set_vsync(!swapchain_->vsync());
        settings_.vsync = swapchain_->vsync();
        settings_dirty_ = true;
    }
}


void Game::toggle_editor(Session& s) {
    if (editor_.is_open()) {
        editor_.close();
        message_ = editor_.unsaved() ? "scene editor closed; its edits are live but not saved (F3 and Save, or Ctrl+S)"
                                     : "scene editor closed";
        return;
    }
    if (s.info.spec.kind != WorldKind::scene) {
        message_ = "the scene editor edits scene files: start the game with --scene FILE";
        return;
    }
    if (editor_.unsaved() && editor_.path() == s.info.spec.path) {
        editor_.reopen(); // the unsaved edits are still the world's
        return;
    }
    if (auto ok = editor_.open(s.info.spec.path); !ok) {
        message_ = "scene editor: " + ok.error().message;
        LANTERN_LOG_ERROR("%s", message_.c_str());
        return;
    }
    message_ = "editing " + s.info.spec.path;
}

void Game::apply_edit(const EditResult& r) {
    if (r.rebuild || r.changed.valid()) pending_edits_.push_back(r);
}

void Game::apply_pending_edits(Session& s) {
    for (const EditResult& r : std::exchange(pending_edits_, {})) apply_edit_now(s, r);
}

void Game::apply_edit_now(Session& s, const EditResult& r) {
    if (r.rebuild) {
        pending_scene_ = editor_.scene();
        pending_from_editor_ = true;
        change_seen_ns_ = now_ns();
        return;
    }
    const EditTarget t = r.changed;
    if (!t.valid()) return;
    ecs::World& w = s.world;
    const auto entity = [&](const std::vector<ecs::Entity>& list) {
        return std::size_t(t.index) < list.size() ? list[std::size_t(t.index)] : ecs::Entity{};
    };
    const scene::SceneLists& l = editor_.lists();
    switch (t.kind) {
    case EditKind::point_light:
        if (const ecs::Entity e = entity(s.info.scene_point_lights); w.try_get<PointLight>(e)) {
            const scene::PointLight& v = l.point_lights[std::size_t(t.index)].value;
            w.patch<PointLight>(e) = PointLight{v.position, v.height, v.color, v.intensity, v.radius, v.mode};
            return;
        }
        break;
    case EditKind::emissive_light:
        if (const ecs::Entity e = entity(s.info.scene_emissive_lights); w.try_get<EmissiveLight>(e)) {
            const scene::EmissiveLight& v = l.emissive_lights[std::size_t(t.index)].value;
            w.patch<EmissiveLight>(e) = EmissiveLight{v.position, v.color, v.intensity, v.radius, v.mode};
            return;
        }
        break;
    case EditKind::proxy:
        if (const ecs::Entity e = entity(s.info.scene_proxies); w.try_get<ShadowProxy>(e)) {
            w.patch<ShadowProxy>(e).shape = l.shadow_proxies[std::size_t(t.index)].value;
            return;
        }
        break;
    }
    EditResult rebuild;
    rebuild.rebuild = true;
    apply_edit_now(s, rebuild); // no entity for it (yet): build the world again
}

bool Game::save_scene_edits() {
    if (auto ok = editor_.save(); !ok) {
        message_ = "scene not saved: " + ok.error().message;
        LANTERN_LOG_ERROR("%s", message_.c_str());
        return false;
    }
    // Our own write is not an outside edit: --watch takes the new stamps instead of reloading.
    if (options_.watch) watched_.watch(watched_.paths());
    message_ = "scene saved to " + editor_.path();
    LANTERN_LOG_INFO("%s", message_.c_str());
    return true;
}

void Game::draw_editor_markers() {
    if (!input_camera_ || present_rect_.empty()) return;
    const scene::PerspectiveCamera& camera = *input_camera_;
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const scene::SceneLists& l = editor_.lists();
    const auto ring = [&](EditTarget t, glm::vec3 at, ImU32 color) {
        const auto ndc = project_to_ndc(camera, at);
        if (!ndc) return;
        const ImVec2 p(float(present_rect_.x) + ndc->x * float(present_rect_.width),
                       float(present_rect_.y) + ndc->y * float(present_rect_.height));
        const bool chosen = t == editor_.selected();
        const float r = float(std::max(present_rect_.scale, 1u)) * (chosen ? 5.0f : 3.5f);
        draw->AddCircle(p, r, chosen ? IM_COL32(255, 255, 255, 255) : color, 20, chosen ? 3.0f : 1.5f);
    };
    for (std::size_t i = 0; i < l.point_lights.size(); ++i) {
        const auto& v = l.point_lights[i].value;
        ring({EditKind::point_light, int(i)}, {v.position.x, v.height, v.position.y}, IM_COL32(255, 210, 80, 230));
    }
    for (std::size_t i = 0; i < l.emissive_lights.size(); ++i) {
        const auto& v = l.emissive_lights[i].value;
        ring({EditKind::emissive_light, int(i)}, {v.position.x, 0.05f, v.position.y}, IM_COL32(110, 255, 120, 230));
    }
    for (std::size_t i = 0; i < l.shadow_proxies.size(); ++i) {
        const auto& v = l.shadow_proxies[i].value;
        ring({EditKind::proxy, int(i)}, {v.position.x, 0.0f, v.position.y}, IM_COL32(140, 170, 255, 230));
    }
}

} // namespace lantern::game::app

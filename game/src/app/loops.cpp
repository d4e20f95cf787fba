// The window loop, the headless demo and its report (timings.json, profile.txt, trace, the final save).
#include "app/game.hpp"

#include "lantern/core/json_writer.hpp"

#include <utility>

namespace lantern::game::app {
namespace {

// A frame the GI backend refused (the window does not fit the device, too many lights):
// the game goes on (every pass reruns next frame) and says why.
void report_refused(const systems::FrameReport& report) {
    if (report.error)
        LANTERN_LOG_ERROR("GI frame %llu: %s", static_cast<unsigned long long>(report.frame),
                          report.error->message.c_str());
}

} // namespace

// The automatic GI quality (--min-fps, docs/game.md "Performance"). The defaults are the
// seed's look, measured at 30 fps at p95 on a 2-core machine's lavapipe; on a slower one the
// game measures its first frames of play and, when their p95 is clearly over the budget
// (by 15 %: with vsync a frame lasts whole refresh intervals), lowers the preset a step
// (high, then medium, then low), saves it in the settings file, says so, and measures again.
// A measurement within the budget ends it for the run; so does a preset the player picks.
void Game::watch_frame_rate(Session& s) {
    constexpr int skipped = 60;   // after a start or a change: pipelines, streaming, the bake
    constexpr std::size_t measured = 180;
    const std::int64_t now = now_ns();
    const std::int64_t last = std::exchange(rate_last_ns_, now);
    if (!auto_quality_) return;
    if (last == 0 || menu_.is_open() || ++rate_skipped_ <= skipped) return; // paused frames are not play
    rate_frames_.push_back(double(now - last) * 1e-6);
    if (rate_frames_.size() < measured) return;
    const double p95 = profile::percentiles(rate_frames_).p95, budget = 1000.0 / double(options_.min_fps);
    rate_frames_.clear();
    rate_skipped_ = 0;
    const GiPreset now_preset = settings_.gi_preset == GiPreset::world ? GiPreset::high : settings_.gi_preset;
    if (p95 <= budget * 1.15 || now_preset == GiPreset::low) {
        if (p95 > budget * 1.15)
            LANTERN_LOG_INFO("frame %.1f ms at p95 at the lowest GI quality (--min-fps %d asks %.1f)", p95, options_.min_fps, budget);
        auto_quality_ = false;
        return;
    }
    settings_.gi_preset = GiPreset(int(now_preset) - 1);
    apply_settings(&s, true);
    settings_dirty_ = true;
    write_settings_file();
    message_ = std::string("GI quality lowered to ") + gi_preset_names[int(settings_.gi_preset)] + ": the frame took " +
               std::to_string(int(p95 + 0.5)) + " ms at p95 (--min-fps " + std::to_string(options_.min_fps) +
               "); the pause menu's Settings can raise it";
    LANTERN_LOG_INFO("%s", message_.c_str());
}

int Game::run_window() {
    while (!quit_) {
        // Minimised or unmapped, nobody sees a frame: step none (no GI, no raster; the world
        // pauses) and sleep on the window's events instead (frames nobody saw took 30-88 % of
        // a core). The status file still tells scripts and tests that the game waits.
        if (window_->minimised() || !window_->visible()) {
            window_->poll_wait(0.25);
            ++hidden_waits_;
            last_frame_ns_ = 0; // the first frame back steps 1/60 s, not the time away
            rate_last_ns_ = 0;  // and is not measured (watch_frame_rate)
            if (window_->should_close()) quit_or_ask(*session_); // the question shows once it is back
            if (!options_.status_file.empty()) write_status(*session_);
            continue;
        }
        follow_window_size();
        profile::begin_frame();
        report_refused(session_->frame->step());
        profile::end_frame();
        ++window_frames_;
        watch_frame_rate(*session_);
        if (save_slot_requested_) {
            const int slot = save_slot_requested_;
            save_slot_requested_ = 0;
            const bool saved = save(*session_, save_slot_path(options_.save_file, slot), "slot " + std::to_string(slot));
            if (quit_after_save_ && saved) quit_ = true;
            quit_after_save_ = false;
        }
        tick_autosave(*session_);
        apply_pending_edits(*session_);
        if (options_.watch) poll_watch();
        if (pending_scene_) {
            if (auto ok = reload_scene(); !ok) {
                LANTERN_LOG_ERROR("%s", ok.error().message.c_str());
                return ok.error().exit_code;
            }
        }
        if (!options_.status_file.empty()) write_status(*session_);
        if (pending_load_) {
            const SaveState state = std::move(*pending_load_);
            pending_load_.reset();
            if (auto ok = check_extension_data(state); !ok) { // refused: the game goes on
                message_ = ok.error().message;
                LANTERN_LOG_ERROR("%s", message_.c_str());
                continue;
            }
            device_->wait_idle();
            session_.reset();
            auto s = make_session(state.world, &state);
            if (!s) {
                LANTERN_LOG_ERROR("%s", s.error().message.c_str());
                return s.error().exit_code;
            }
            session_ = std::move(*s);
            mark_saved(*session_, false); // what was loaded is what "unsaved" compares with
            message_ = "loaded " + state.file;
        }
    }
    if (settings_dirty_) write_settings_file();
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
    std::vector<MemorySample> memory;
    const int memory_warm_up = std::min(memory_warm_up_frames, frames / 2);
    const int memory_every = std::max(1, frames / 100);
    const std::int64_t start = now_ns();
    std::fprintf(stderr, "lantern: headless demo, %d frames at %dx%d, %s -> %s/\n", frames, options_.internal.x,
                 options_.internal.y, session_->info.description.c_str(), options_.out_dir.c_str());
    for (headless_frame_ = 0; headless_frame_ < frames; ++headless_frame_) {
        profile::begin_frame();
        const std::int64_t t0 = now_ns();
        report_refused(session_->frame->step());
        const std::int64_t t1 = now_ns();
        profile::end_frame();
        frame_ms.push_back(double(t1 - t0) * 1e-6);
        if (options_.watch) poll_watch();
        if (pending_scene_) {
            if (auto ok = reload_scene(); !ok) {
                std::fprintf(stderr, "lantern: %s\n", ok.error().message.c_str());
                return ok.error().exit_code;
            }
        }
        if (!options_.status_file.empty()) write_status(*session_);
        walking.push_back(session_->demo->is_walking(headless_frame_));
        if (headless_frame_ == memory_warm_up || headless_frame_ + 1 == frames ||
            (headless_frame_ > memory_warm_up && (headless_frame_ - memory_warm_up) % memory_every == 0))
            memory.push_back({headless_frame_, resident_set_bytes(), device_->memory_allocated()});
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
    if (auto ok = write_headless_report(frame_ms, walking, screenshots, memory, seconds); !ok) {
        std::fprintf(stderr, "lantern: %s\n", ok.error().message.c_str());
        return 1;
    }
    return 0;
}

Result<void> Game::write_headless_report(const std::vector<double>& frame_ms, const std::vector<bool>& walking,
                                         const std::vector<std::string>& screenshots,
                                         const std::vector<MemorySample>& memory, double seconds) {
    std::vector<double> all, walk;
    std::vector<std::size_t> counted; // frame index of each entry of `all`
    for (std::size_t i = std::size_t(warm_up_frames); i < frame_ms.size(); ++i) {
        if (frame_ms[i] < 0 || (i > 0 && frame_ms[i - 1] < 0)) continue;
        all.push_back(frame_ms[i]);
        counted.push_back(i);
        if (walking[i]) walk.push_back(frame_ms[i]);
    }
    const profile::Percentiles pa = profile::percentiles(all), pw = profile::percentiles(walk);
    // Hitches: counted frames above 3x the p50 (the measure; their scopes are in the
    // trace and profile.txt).
    const double hitch_ms = 3.0 * pa.p50;
    std::vector<std::size_t> hitches;
    for (std::size_t k = 0; k < all.size(); ++k)
        if (all[k] > hitch_ms) hitches.push_back(counted[k]);
    const auto stats = profile::stats();
    const scene::GiSettings& gi = session_->world.resource<systems::GiConfig>().settings;

    // Memory from the warm-up sample to the end (a leak shows as growth; docs/performance.md, "Soak").
    constexpr double mib = 1024.0 * 1024.0;
    const MemorySample from = memory.empty() ? MemorySample{} : memory.front();
    const MemorySample to = memory.empty() ? MemorySample{} : memory.back();
    std::uint64_t peak_resident = 0, peak_device = 0;
    for (const MemorySample& m : memory) {
        peak_resident = std::max(peak_resident, m.resident_bytes);
        peak_device = std::max(peak_device, m.device_bytes);
    }
    const double resident_growth = (double(to.resident_bytes) - double(from.resident_bytes)) / mib;
    const double device_growth = (double(to.device_bytes) - double(from.device_bytes)) / mib;

    json::Writer w;
    auto pct = [&](const char* name, const profile::Percentiles& p) {
        w.key(name).begin_object(json::Layout::one_line).field("frames", p.count).field("mean", p.mean, 3);
        w.field("p50", p.p50, 3).field("p95", p.p95, 3).field("p99", p.p99, 3).field("max", p.max, 3).end();
    };
    w.begin_object();
    w.field("machine", describe_machine()).field("device", device_->name()).field("world", session_->info.description);
    w.field("frames", frame_ms.size()).field("warm_up_frames", warm_up_frames).field("seconds", seconds, 3);
    w.key("internal_resolution").begin_array(json::Layout::one_line).value(options_.internal.x).value(options_.internal.y).end();
    w.key("gi").begin_object(json::Layout::one_line).field("resolution", gi.resolution).field("heat_rounds", gi.heat_rounds);
    w.field("heat_scale", int(gi.heat_scale)).field("padding", gi.padding).field("max_lights", gi.max_lights).end();
    pct("frame_ms", pa);
    pct("frame_ms_walking", pw);
    w.key("hitches").begin_object(json::Layout::one_line).field("above_ms", hitch_ms, 3).field("count", hitches.size());
    w.key("frames").begin_array(json::Layout::one_line);
    for (std::size_t f : hitches) w.value(f);
    w.end().end();
    w.key("memory").begin_object().field("from_frame", from.frame).field("to_frame", to.frame);
    w.key("resident_mib").begin_object(json::Layout::one_line).field("from", double(from.resident_bytes) / mib, 3);
    w.field("to", double(to.resident_bytes) / mib, 3).field("max", double(peak_resident) / mib, 3);
    w.field("growth", resident_growth, 3).end();
    w.key("device_mib").begin_object(json::Layout::one_line).field("from", double(from.device_bytes) / mib, 3);
    w.field("to", double(to.device_bytes) / mib, 3).field("max", double(peak_device) / mib, 3);
    w.field("growth", device_growth, 3).end();
    w.key("samples").begin_array(json::Layout::one_line); // [frame, resident MiB, device MiB]
    for (const MemorySample& m : memory)
        w.begin_array().value(m.frame).value(double(m.resident_bytes) / mib, 3).value(double(m.device_bytes) / mib, 3).end();
    w.end().end();
    w.key("scopes").begin_array();
    for (const auto& st : stats) {
        w.begin_object(json::Layout::one_line).field("name", st.name);
        w.field("lane", st.kind == profile::LaneKind::gpu ? "gpu" : "cpu").field("frames", st.frames_seen);
        w.field("p50", st.p50_ms, 3).field("p95", st.p95_ms, 3).field("p99", st.p99_ms, 3).field("max", st.max_ms, 3).end();
    }
    w.end();
    w.key("screenshots").begin_array(json::Layout::one_line);
    for (const std::string& name : screenshots) w.value(name);
    w.end().end();
    if (auto ok = write_file_atomic(options_.out_dir + "/timings.json", w.take()); !ok) return ok;
    if (auto ok = write_file_atomic(options_.out_dir + "/profile.txt", profile::text_report()); !ok) return ok;
    if (auto ok = profile::write_chrome_trace(options_.out_dir + "/trace.json", 300); !ok) return ok;
    // The world as the demo left it, as a save (continue it with --load; extensions' data too).
    SaveState state = capture_save(session_->world, session_->frame->streaming(), session_->info.spec);
    state.extensions = capture_extensions(extensions_, session_->world);
    if (auto ok = write_save(options_.out_dir + "/save.json", state); !ok) return ok;

    std::printf("lantern headless demo: %zu frames in %.1f s on %s (%s)\n", frame_ms.size(), seconds,
                device_->name().c_str(), describe_machine().c_str());
    std::printf("world: %s; GI resolution %d, %d heat rounds at 1/%d, internal %dx%d\n",
                session_->info.description.c_str(), gi.resolution, gi.heat_rounds, int(gi.heat_scale),
                options_.internal.x, options_.internal.y);
    std::printf("frame ms (after %d warm-up frames):   p50 %6.2f  p95 %6.2f  p99 %6.2f  max %6.2f  (%u frames)\n",
                warm_up_frames, pa.p50, pa.p95, pa.p99, pa.max, pa.count);
    std::printf("frame ms while walking:               p50 %6.2f  p95 %6.2f  p99 %6.2f  max %6.2f  (%u frames) -> %.1f fps at p95\n",
                pw.p50, pw.p95, pw.p99, pw.max, pw.count, pw.p95 > 0 ? 1000.0 / pw.p95 : 0.0);
    std::printf("frames above 3x p50 (%.1f ms): %zu", hitch_ms, hitches.size());
    for (std::size_t k = 0; k < hitches.size() && k < 10; ++k) std::printf("%s%zu", k == 0 ? " (frames " : ", ", hitches[k]);
    std::printf("%s\n", hitches.empty() ? "" : hitches.size() > 10 ? ", ...)" : ")");
    std::printf("memory from frame %d to %d: resident %.1f -> %.1f MiB (%+.2f), device %.1f -> %.1f MiB (%+.2f)\n",
                from.frame, to.frame, double(from.resident_bytes) / mib, double(to.resident_bytes) / mib,
                resident_growth, double(from.device_bytes) / mib, double(to.device_bytes) / mib, device_growth);
    if (options_.bench) {
        std::printf("\n%-28s %5s %8s %8s %8s %8s\n", "scope / system / GPU pass", "lane", "p50", "p95", "p99", "max");
        for (const auto& s : stats)
            std::printf("%-28s %5s %8.2f %8.2f %8.2f %8.2f\n", s.name, s.kind == profile::LaneKind::gpu ? "gpu" : "cpu",
                        s.p50_ms, s.p95_ms, s.p99_ms, s.max_ms);
    }
    std::printf("wrote %s/{timings.json, profile.txt, trace.json, save.json} and %zu screenshots\n", options_.out_dir.c_str(),
                screenshots.size());
    return {};
}


} // namespace lantern::game::app

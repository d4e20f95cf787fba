#include "render_cli.hpp"

#include "lantern/bake/bake.hpp"
#include "lantern/core/cli.hpp"
#include "lantern/core/clock.hpp"
#include "lantern/core/file.hpp"
#include "lantern/core/json_writer.hpp"
#include "lantern/core/text.hpp"
#include "lantern/core/png.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/jobs/job_system.hpp"
#include "lantern/profile/profiler.hpp"
#include "lantern/scene/loader.hpp"
#include "lantern/systems/scene_world.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace lantern::tools {
namespace {

struct Options {
    std::string scene;
    std::string out, dump, timings;
    std::string backend = "vulkan";
    std::vector<std::string> sets;
    std::string bake;
    bake::BakeSettings bake_settings; // --bake-* as parsed
    bake::GivenSettings bake_given;   // ... and which were given: laid over the scene's own "bake"
    int frames = 1;
    bool quiet = false;
    bool watch = false;
};

int fail(const std::string& message, int code) {
    std::fprintf(stderr, "lantern-render: %s\n", message.c_str());
    return code;
}

// Returns the exit code when the program should stop (--help, --version, bad input), nullopt
// when parsing succeeded.
std::optional<int> parse_args(int argc, char** argv, Options& o) {
    cli::Parser p("lantern-render", "SCENE.json [options]",
                  "Renders the GI frame of a scene file (docs/scenes.md) through the whole pipeline: direct\n"
                  "light (point, emissive, directional), heat-diffusion indirect light, blur, wall indirect.");
    p.positionals("SCENE.json", "the scene file", [&](std::string_view a) -> std::optional<std::string> {
        if (!o.scene.empty()) return "more than one scene file given ('" + o.scene + "' and '" + printable(a) + "')";
        o.scene = std::string(a);
        return std::nullopt;
    });
    p.text("--out", "IMAGE.png",
           "the lit image of the GI window seen from above: ground, wall faces\n"
           "and wall tops, tone-mapped, sRGB, one pixel per GI texel",
           o.out);
    p.choice("--backend", "Vulkan (default; LANTERN_VK_DEVICE picks a device) or the C++ reference", o.backend,
             {"vulkan", "cpu"});
    p.text("--dump", "DIR", "every GI texture the frame produced, as little-endian float PFM", o.dump);
    p.text("--timings", "FILE.json", "per-pass times, texture size, GI window, device, passes left out", o.timings);
    p.custom(
        "--set", "gi.KEY=VALUE", "override a gi setting (e.g. --set gi.resolution=16)",
        [&](std::string_view v) -> std::optional<std::string> {
            o.sets.emplace_back(v);
            return std::nullopt;
        },
        true);
    p.integer("--frames", "N",
              "run N frames through the ECS frame (default 1), with a scripted change\n"
              "before frame k >= 1, by k mod 4: 1 moves the first light 0.5 along x,\n"
              "2 changes nothing (every pass a cache hit), 3 toggles the wall at the\n"
              "window's centre, 0 moves the camera one tile along x. --timings then\n"
              "lists, per frame, which passes ran and why the others did not; the\n"
              "outputs are the last frame's",
              o.frames, 1, 100000);
    p.text("--bake", "DIR",
           "light the scene's mixed and baked lights and glowing materials from its bake in DIR\n"
           "(docs/baked.md): chunks missing or stale there are baked first (as lantern-bake does),\n"
           "then the frame adds the baked light and the live passes leave it out",
           o.bake);
    bake::add_settings_options(p, o.bake_settings, "--bake-");
    p.flag("--quiet", "no progress output on stderr", o.quiet);
    p.flag("--watch",
           "after the first render, render again whenever the scene file changes; a\n"
           "malformed edit is reported and the outputs keep the last good render\n"
           "(one stdout line per attempt; Ctrl-C stops)",
           o.watch);
    p.epilog("Exit status: 0 ok, 1 runtime failure (e.g. no Vulkan device), 2 bad input. Nothing is\n"
             "written unless the frame succeeded; every file is written atomically.");
    if (auto exit = p.parse(argc, argv)) return exit;
    o.bake_given = bake::given_settings(p, o.bake_settings, "--bake-");
    if (o.scene.empty()) {
        std::fprintf(stderr, "%s\n", p.message("no scene file given").c_str());
        return 2;
    }
    // Outputs are checked before any work, so a bad one costs nothing and writes nothing.
    for (const std::string* path : {&o.out, &o.timings})
        if (!path->empty())
            if (auto ok = check_output_file(*path); !ok) return fail(ok.error().message, 2);
    if (!o.dump.empty())
        if (auto ok = check_output_folder(o.dump); !ok) return fail(ok.error().message, 2);
    return std::nullopt;
}

namespace fs = std::filesystem;

// --dump writes every GI texture as float PFM: at most 12 bytes per texel each (a camera's
// window keeps its size from frame to frame), so its size is known before any work: refused
// (exit 1) when the file system DIR goes to has less free space than that. (The GI texture
// budget bounds it too: at most about 3 GiB; docs/gi.md, "Memory budget".)
Result<void> check_dump_size(const std::string& dump, const gi::GiWindow& w) {
    const std::uint64_t bytes = std::uint64_t(gi::registered_texture_count()) *
                                (std::uint64_t(w.width) * std::uint64_t(w.height) * 12 + 64);
    std::error_code ec;
    const fs::path parent = fs::absolute(fs::path(dump), ec).parent_path();
    const fs::space_info space = fs::space(parent, ec);
    if (!ec && space.available < bytes) {
        constexpr double mib = 1024.0 * 1024.0;
        char text[512];
        std::snprintf(text, sizeof(text), "--dump %s: needs about %.1f MiB, and its file system has %.1f MiB free",
                      printable(dump, 200).c_str(), double(bytes) / mib, double(space.available) / mib);
        return make_error(text, 1);
    }
    return {};
}

// One frame's record for --timings and the summary.
struct FrameRecord {
    std::uint64_t frame = 0;
    gi::PassSet ran;
    std::array<std::string, gi::pass_count> reason;
    std::array<double, gi::pass_count> ms{};
};

// Every registered pass of frame `f`: ran or why not, GPU ms; returns their sum.
double write_passes(json::Writer& w, const FrameRecord& f) {
    double total = 0.0;
    w.key("passes").begin_array();
    for (int p = 0; p < gi::registered_pass_count(); ++p) {
        const bool ran = f.ran.has(gi::Pass(p));
        w.begin_object(json::Layout::one_line).field("name", gi::pass_name(gi::Pass(p))).field("ran", ran);
        w.field("gpu_ms", f.ms[std::size_t(p)]);
        if (!ran) w.field("reason", f.reason[std::size_t(p)]);
        w.end();
        total += f.ms[std::size_t(p)];
    }
    w.end();
    return total;
}

std::string timings_json(const Options& o, const std::string& device, const gi::GiWindow& win,
                         const systems::GatheredLights& lights, std::size_t proxies,
                         const std::vector<FrameRecord>& frames) {
    json::Writer w;
    w.begin_object().field("scene", o.scene).field("backend", o.backend).field("device", device);
    w.field("timing_source", o.backend == "vulkan" ? "GPU timestamps" : "CPU wall clock of the C++ reference");
    w.key("texture_size").begin_array(json::Layout::one_line).value(win.width).value(win.height).end();
    w.key("camera_view").begin_array(json::Layout::one_line).value(win.view.min_x).value(win.view.min_z);
    w.value(win.view.width).value(win.view.height).end();
    w.field("resolution", win.resolution);
    w.key("lights").begin_object(json::Layout::one_line).field("point", lights.points.size());
    w.field("emissive", lights.emissives.size()).field("directional", lights.suns.size());
    w.field("shadow_proxies", proxies).end();
    // The top level describes the last frame (the one whose outputs were written).
    w.field("total_gpu_ms", write_passes(w, frames.back()));
    w.key("frames").begin_array();
    for (const FrameRecord& f : frames) {
        w.begin_object().field("frame", f.frame);
        w.field("total_gpu_ms", write_passes(w, f)).end();
    }
    w.end().end();
    return w.take();
}

Result<void> write_outputs(const Options& o, gi::Backend& backend, const std::string& timings) {
    if (!o.dump.empty()) {
        // Every texture goes into a staging folder first; only a complete set is moved into
        // place (core/file.hpp: StagedFolder), so a failure leaves no partial dump.
        auto staged = StagedFolder::create(o.dump);
        if (!staged) return staged.error();
        for (const std::string& name : backend.texture_names()) {
            auto texture = backend.read(name);
            if (!texture) continue;
            std::string error;
            if (!gi::write_pfm(*texture, staged->file(name + ".pfm"), &error)) return make_error(error, 1);
        }
        if (auto ok = staged->commit(); !ok) return ok;
    }
    if (!o.out.empty()) {
        auto lit = backend.read_lit();
        if (!lit) return make_error("no lit image was produced", 1);
        // PNG rows run top to bottom; show the window's maximum z at the top (north up).
        const gi::Image& img = *lit;
        std::vector<std::uint8_t> flipped(img.rgb.size());
        const std::size_t row = std::size_t(img.width) * 3;
        for (int y = 0; y < img.height; ++y)
            std::memcpy(&flipped[std::size_t(img.height - 1 - y) * row], &img.rgb[std::size_t(y) * row], row);
        if (auto ok = write_png(o.out, img.width, img.height, 3, flipped); !ok) return ok;
    }
    if (!o.timings.empty())
        if (auto ok = write_file_atomic(o.timings, timings); !ok) return ok;
    return {};
}

// The scripted change before frame k (see --help and docs/frame.md).
void scripted_change(int k, ecs::World& world, const systems::SceneWorld& sw, systems::GiFrame& frame) {
    switch (k % 4) {
    case 1:
        if (!sw.point_lights.empty())
            world.patch<PointLight>(sw.point_lights.front()).position.x += 0.5f;
        else if (!sw.emissive_lights.empty())
            world.patch<EmissiveLight>(sw.emissive_lights.front()).position.x += 0.5f;
        break;
    case 2: break;
    case 3: {
        const auto& view = world.resource<systems::GiView>();
        if (!view.window) break;
        const glm::vec2 c = view.window->center();
        const glm::ivec2 tile(int(std::floor(c.x)), int(std::floor(c.y)));
        frame.streaming().set_wall(world, tile, !frame.streaming().is_wall(tile));
        break;
    }
    default: {
        Camera& cam = world.patch<Camera>(sw.camera);
        if (auto* ortho = std::get_if<scene::OrthoView>(&cam.view)) ortho->center.x += 1.0f;
        if (auto* persp = std::get_if<scene::PerspectiveCamera>(&cam.view)) {
            persp->position.x += 1.0f;
            persp->target.x += 1.0f;
        }
    }
    }
}

void print_frame(const Options& o, const FrameRecord& f) {
    if (o.quiet) return;
    std::string ran, skipped;
    char ms[32];
    for (int p = 0; p < gi::registered_pass_count(); ++p) {
        const std::string name = gi::pass_name(gi::Pass(p));
        if (f.ran.has(gi::Pass(p))) {
            std::snprintf(ms, sizeof(ms), " %.3f ms", f.ms[std::size_t(p)]);
            ran += (ran.empty() ? "" : ", ") + name + ms;
        } else {
            skipped += (skipped.empty() ? "" : "; ") + name + ": " + f.reason[std::size_t(p)];
        }
    }
    std::fprintf(stderr, "  frame %llu ran: %s\n    left out: %s\n", static_cast<unsigned long long>(f.frame),
                 ran.empty() ? "nothing" : ran.c_str(), skipped.empty() ? "nothing" : skipped.c_str());
}

// The Vulkan device and GI renderer, made by the first render and kept for the next ones of
// --watch: making them compiles every pipeline (about 5.8 s of the 5.9 s a watched re-render
// took on lavapipe, benchmarks/reload_latency.py). The game keeps its renderer across
// reloads the same way.
struct KeptDevice {
    std::unique_ptr<gpu::Device> device;
    std::unique_ptr<gi::vk::Renderer> renderer;
};

Result<std::unique_ptr<gi::Backend>> make_backend(const Options& o, jobs::JobSystem& jobs, KeptDevice& kept) {
    if (o.backend == "cpu") return gi::make_reference_backend(&jobs);
    if (!kept.renderer) {
        auto device = gpu::Device::create();
        if (!device) return make_error(device.error().message + " (try --backend cpu)", 1);
        auto renderer = gi::vk::Renderer::create(**device);
        if (!renderer) return renderer.error();
        kept.device = std::move(device.value());
        kept.renderer = std::move(renderer.value());
    }
    return gi::make_vulkan_backend(*kept.renderer);
}

// Renders the scene file once through the frame and writes the outputs (atomically; none on
// failure). The exit status. `inputs`: set to the other files the scene read (its map) once
// it loads.
int render_file(const Options& o, jobs::JobSystem& jobs, KeptDevice& kept,
                std::optional<std::vector<std::string>>* inputs = nullptr) {
    auto scene = scene::load_scene(o.scene);
    if (!scene) return fail(scene.error().message, scene.error().exit_code);
    if (inputs) *inputs = scene->inputs;
    for (const std::string& s : o.sets)
        if (auto ok = scene::apply_override(*scene, s); !ok) return fail(ok.error().message, ok.error().exit_code);
    std::string why;
    const auto window = gi::compute_window(scene->view, scene->gi, &why);
    if (!window) return fail(o.scene + ": no GI for this view: " + why, 1);
    if (!o.dump.empty())
        if (auto ok = check_dump_size(o.dump, *window); !ok) return fail(ok.error().message, ok.error().exit_code);

    auto backend = make_backend(o, jobs, kept);
    if (!backend) return fail(backend.error().message, backend.error().exit_code);
    const std::string device_name = (*backend)->name();
    std::shared_ptr<const gi::BakedLight> baked;
    if (!o.bake.empty()) {
        bake::BakeOptions options;
        options.jobs = &jobs;
        if (!o.quiet)
            options.progress = [](const bake::BakeProgress& p) {
                std::fprintf(stderr, "lantern-render: bake %d/%d chunks (%d reused) %.1f s\n", p.done, p.total, p.reused, p.seconds);
            };
        options.warn = [](const std::string& m) { std::fprintf(stderr, "lantern-render: %s\n", m.c_str()); };
        auto light = bake::load_world_light(*scene, o.bake, o.bake_given.over(scene->bake), options);
        if (!light) return fail(light.error().message, light.error().exit_code);
        baked = std::move(*light);
        *scene = bake::live_scene(*scene); // the bake holds the rest
    }
    ecs::World world;
    systems::SceneWorld sw = systems::populate_world(*scene, world);
    sw.config.lit_image = !o.out.empty();
    systems::GiFrame frame(world, jobs, sw.source, std::move(*backend), sw.config);
    world.resource<systems::BakedGi>().light = baked;
    frame.warm_up();
    profile::set_enabled(true);
    std::vector<FrameRecord> records;
    std::vector<gi::FrameTimes> times;
    for (int k = 0; k < o.frames; ++k) {
        if (k > 0) scripted_change(k, world, sw, frame);
        profile::begin_frame();
        systems::FrameReport report = frame.step();
        profile::end_frame();
        if (report.error) return fail(report.error->message, report.error->exit_code);
        records.push_back({report.frame, report.ran, report.reason, {}});
        times.insert(times.end(), report.completed.begin(), report.completed.end());
    }
    // GPU times arrive after their frames: attach each to the frame that submitted it.
    frame.backend().wait_idle();
    for (const gi::FrameTimes& t : frame.backend().completed_times()) times.push_back(t);
    for (const gi::FrameTimes& t : times)
        for (FrameRecord& r : records)
            if (r.frame == t.frame)
                for (const gi::PassTime& p : t.passes) r.ms[std::size_t(p.pass)] = p.ms;
    const auto& view = world.resource<systems::GiView>();
    if (!view.window) return fail(o.scene + ": no GI for the last frame: " + view.bail_reason, 1);
    if (!o.quiet)
        std::fprintf(stderr, "lantern-render: %s, %d x %d texels, %s, %d frame(s)\n", o.backend.c_str(),
                     view.window->width, view.window->height, device_name.c_str(), o.frames);
    for (const FrameRecord& r : records) print_frame(o, r);
    const std::string timings = timings_json(o, device_name, *view.window, world.resource<systems::GatheredLights>(),
                                                world.resource<systems::GatheredProxies>().proxies.size(), records);
    if (auto ok = write_outputs(o, frame.backend(), timings); !ok) return fail(ok.error().message, 1);
    return 0;
}

} // namespace

int render_main(int argc, char** argv) {
    Options o;
    if (auto code = parse_args(argc, argv, o)) return *code;
    jobs::JobSystem jobs;
    KeptDevice kept;
    if (!o.watch) return render_file(o, jobs, kept);
    // --watch: a render per change of the scene file or a file it reads (its world.map; their
    // FileStamps, looked at ten times a second). A failed render writes nothing, so the
    // outputs keep the last good one; the counts go to stdout, one line per attempt, for
    // scripts (and tests) to wait on.
    FilesWatch watched;
    watched.watch({o.scene});
    int rendered = 0, refused = 0;
    const auto attempt = [&]() {
        const std::int64_t start = now_ns();
        std::optional<std::vector<std::string>> read; // the files the scene read, once it loaded
        const int code = render_file(o, jobs, kept, &read);
        if (read) {
            read->insert(read->begin(), o.scene);
            if (*read != watched.paths()) watched.watch(std::move(*read)); // stamped after the read
        }
        (code == 0 ? rendered : refused) += 1;
        std::printf("lantern-render: watch: %d rendered, %d refused (%s, %.0f ms)\n", rendered, refused,
                    code == 0 ? "rendered" : "refused: the outputs keep the last good render",
                    double(now_ns() - start) * 1e-6);
        std::fflush(stdout);
        return code;
    };
    if (const int code = attempt(); code == 1 && rendered == 0) return code; // no device: nothing to watch with
    if (!o.quiet) std::fprintf(stderr, "lantern-render: watching %s (Ctrl-C stops)\n", o.scene.c_str());
    for (;;) {
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        if (watched.changed()) attempt();
    }
}

} // namespace lantern::tools

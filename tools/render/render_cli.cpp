#include "render_cli.hpp"

#include "lantern/core/file.hpp"
#include "lantern/core/png.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/jobs/job_system.hpp"
#include "lantern/profile/profiler.hpp"
#include "lantern/scene/loader.hpp"
#include "lantern/systems/scene_world.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace lantern::tools {
namespace {

constexpr const char* usage_text =
    "usage: lantern-render SCENE.json [--out IMAGE.png] [--backend vulkan|cpu] [--dump DIR]\n"
    "                      [--timings FILE.json] [--set gi.KEY=VALUE ...] [--frames N] [--quiet]\n"
    "\n"
    "Renders the GI frame of a scene file (docs/scenes.md) through the whole pipeline: direct\n"
    "light (point, emissive, directional), heat-diffusion indirect light, blur, wall indirect.\n"
    "  --out IMAGE.png      the lit image of the GI window seen from above: ground, wall faces\n"
    "                       and wall tops, tone-mapped, sRGB, one pixel per GI texel\n"
    "  --backend vulkan|cpu Vulkan (default; LANTERN_VK_DEVICE picks a device) or the C++ reference\n"
    "  --dump DIR           every GI texture the frame produced, as little-endian float PFM\n"
    "  --timings FILE.json  per-pass times, texture size, GI window, device, passes left out\n"
    "  --set gi.KEY=VALUE   override a gi setting (e.g. --set gi.resolution=16)\n"
    "  --frames N           run N frames through the ECS frame (default 1), with a scripted change\n"
    "                       before frame k >= 1, by k mod 4: 1 moves the first light 0.5 along x,\n"
    "                       2 changes nothing (every pass a cache hit), 3 toggles the wall at the\n"
    "                       window's centre, 0 moves the camera one tile along x. --timings then\n"
    "                       lists, per frame, which passes ran and why the others did not; the\n"
    "                       outputs are the last frame's\n"
    "  --quiet              no progress output on stderr\n"
    "Exit status: 0 ok, 1 runtime failure (e.g. no Vulkan device), 2 bad input. Nothing is\n"
    "written unless the frame succeeded; every file is written atomically.\n";

struct Options {
    std::string scene;
    std::string out, dump, timings;
    std::string backend = "vulkan";
    std::vector<std::string> sets;
    int frames = 1;
    bool quiet = false;
};

int fail(const std::string& message, int code) {
    std::fprintf(stderr, "lantern-render: %s\n", message.c_str());
    return code;
}

// Returns the exit code on error, nullopt when parsing succeeded.
std::optional<int> parse_args(int argc, char** argv, Options& o) {
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&](const char* flag) -> const char* {
            if (i + 1 >= argc) return nullptr;
            (void)flag;
            return argv[++i];
        };
        const char* v = nullptr;
        if (a == "--help" || a == "-h") {
            std::fputs(usage_text, stdout);
            return 0;
        } else if (a == "--quiet") {
            o.quiet = true;
        } else if (a == "--frames") {
            if (!(v = value(a.c_str()))) return fail("--frames needs a value (see --help)", 2);
            char* end = nullptr;
            const long n = std::strtol(v, &end, 10);
            if (*end || n < 1 || n > 100000) return fail("--frames needs an integer from 1 to 100000", 2);
            o.frames = int(n);
        } else if (a == "--out" || a == "--dump" || a == "--timings" || a == "--backend" || a == "--set") {
            if (!(v = value(a.c_str()))) return fail(a + " needs a value (see --help)", 2);
            if (a == "--out") o.out = v;
            else if (a == "--dump") o.dump = v;
            else if (a == "--timings") o.timings = v;
            else if (a == "--backend") o.backend = v;
            else o.sets.push_back(v);
        } else if (!a.empty() && a[0] == '-') {
            return fail("unknown option '" + a + "' (see --help)", 2);
        } else if (o.scene.empty()) {
            o.scene = a;
        } else {
            return fail("more than one scene file given ('" + o.scene + "' and '" + a + "')", 2);
        }
    }
    if (o.scene.empty()) return fail("no scene file given (see --help)", 2);
    if (o.backend != "vulkan" && o.backend != "cpu")
        return fail("--backend must be vulkan or cpu, not '" + o.backend + "'", 2);
    // Outputs are checked before any work, so a bad one costs nothing and writes nothing.
    for (const std::string* path : {&o.out, &o.timings})
        if (!path->empty())
            if (auto ok = check_output_file(*path); !ok) return fail(ok.error().message, 2);
    if (!o.dump.empty())
        if (auto ok = check_output_folder(o.dump); !ok) return fail(ok.error().message, 2);
    return std::nullopt;
}

// One frame's record for --timings and the summary.
struct FrameRecord {
    std::uint64_t frame = 0;
    gi::PassSet ran;
    std::array<std::string, gi::pass_count> reason;
    std::array<double, gi::pass_count> ms{};
};

nlohmann::json passes_json(const FrameRecord& f, double& total) {
    nlohmann::json passes = nlohmann::json::array();
    for (int p = 0; p < gi::registered_pass_count(); ++p) {
        const bool ran = f.ran.has(gi::Pass(p));
        nlohmann::json e{{"name", gi::pass_name(gi::Pass(p))}, {"ran", ran}, {"gpu_ms", f.ms[std::size_t(p)]}};
        if (!ran) e["reason"] = f.reason[std::size_t(p)];
        total += f.ms[std::size_t(p)];
        passes.push_back(e);
    }
    return passes;
}

nlohmann::json timings_json(const Options& o, const std::string& device, const gi::GiWindow& w,
                            const systems::GatheredLights& lights, std::size_t proxies,
                            const std::vector<FrameRecord>& frames) {
    nlohmann::json j;
    j["scene"] = o.scene;
    j["backend"] = o.backend;
    j["device"] = device;
    j["timing_source"] = o.backend == "vulkan" ? "GPU timestamps" : "CPU wall clock of the C++ reference";
    j["texture_size"] = {w.width, w.height};
    j["camera_view"] = {w.view.min_x, w.view.min_z, w.view.width, w.view.height};
    j["resolution"] = w.resolution;
    j["lights"] = {{"point", lights.points.size()},
                   {"emissive", lights.emissives.size()},
                   {"directional", lights.suns.size()},
                   {"shadow_proxies", proxies}};
    // The top level describes the last frame (the one whose outputs were written).
    double total = 0.0;
    j["passes"] = passes_json(frames.back(), total);
    j["total_gpu_ms"] = total;
    nlohmann::json per_frame = nlohmann::json::array();
    for (const FrameRecord& f : frames) {
        double t = 0.0;
        nlohmann::json e{{"frame", f.frame}};
        e["passes"] = passes_json(f, t);
        e["total_gpu_ms"] = t;
        per_frame.push_back(e);
    }
    j["frames"] = per_frame;
    return j;
}

Result<void> write_outputs(const Options& o, gi::Backend& backend, const nlohmann::json& timings) {
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
        if (auto ok = write_file_atomic(o.timings, timings.dump(2) + "\n"); !ok) return ok;
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

struct Backend {
    std::unique_ptr<gpu::Device> device;
    std::unique_ptr<gi::vk::Renderer> renderer;
    std::unique_ptr<gi::Backend> backend;
};

Result<Backend> make_backend(const Options& o, jobs::JobSystem& jobs) {
    Backend b;
    if (o.backend == "cpu") {
        b.backend = gi::make_reference_backend(&jobs);
        return b;
    }
    auto device = gpu::Device::create();
    if (!device) return make_error(device.error().message + " (try --backend cpu)", 1);
    b.device = std::move(device.value());
    auto renderer = gi::vk::Renderer::create(*b.device);
    if (!renderer) return renderer.error();
    b.renderer = std::move(renderer.value());
    b.backend = gi::make_vulkan_backend(*b.renderer);
    return b;
}

} // namespace

int render_main(int argc, char** argv) {
    Options o;
    if (auto code = parse_args(argc, argv, o)) return *code;
    auto scene = scene::load_scene(o.scene);
    if (!scene) return fail(scene.error().message, scene.error().exit_code);
    for (const std::string& s : o.sets)
        if (auto ok = scene::apply_override(*scene, s); !ok) return fail(ok.error().message, ok.error().exit_code);
    std::string why;
    if (!gi::compute_window(scene->view, scene->gi.padding, scene->gi.resolution, &why))
        return fail(o.scene + ": no GI for this view: " + why, 1);

    jobs::JobSystem jobs;
    auto backend = make_backend(o, jobs);
    if (!backend) return fail(backend.error().message, backend.error().exit_code);
    const std::string device_name = backend->backend->name();
    ecs::World world;
    systems::SceneWorld sw = systems::populate_world(*scene, world);
    sw.config.lit_image = !o.out.empty();
    systems::GiFrame frame(world, jobs, sw.source, std::move(backend->backend), sw.config);
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
    const nlohmann::json timings = timings_json(o, device_name, *view.window, world.resource<systems::GatheredLights>(),
                                                world.resource<systems::GatheredProxies>().proxies.size(), records);
    if (auto ok = write_outputs(o, frame.backend(), timings); !ok) return fail(ok.error().message, 1);
    return 0;
}

} // namespace lantern::tools

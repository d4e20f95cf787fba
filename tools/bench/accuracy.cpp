// lantern-bench accuracy: for each scene, the transport reference once, then every setting
// of the sweep timed on the GPU (median of GPU timestamps) and compared with it.
#include "accuracy.hpp"
#include "bench.hpp"

#include "lantern/bake/bake.hpp"
#include "lantern/core/clock.hpp"
#include "lantern/core/file.hpp"
#include "lantern/core/machine.hpp"
#include "lantern/core/png.hpp"
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/vulkan/renderer.hpp"
#include "lantern/jobs/job_system.hpp"
#include "lantern/transport/cache.hpp"
#include "lantern/transport/progress.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

namespace lantern::bench {
namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

// Lantern's frame on the Vulkan device, or on the C++ reference backend (wall time, all
// threads) when asked or when there is no device.
class LanternRunner {
  public:
    LanternRunner(const std::string& backend, jobs::JobSystem& jobs,
                  std::vector<std::string>& notes)
        : jobs_(jobs) {
        if (backend == "vulkan") {
            auto device = gpu::Device::create();
            if (device) {
                auto renderer = gi::vk::Renderer::create(**device);
                if (renderer) {
                    device_ = std::move(device.value());
                    renderer_ = std::move(renderer.value());
                    return;
                }
                notes.push_back("Vulkan renderer unavailable (" + renderer.error().message +
                                "): timings are the C++ reference");
            } else {
                notes.push_back(device.error().message + ": timings are the C++ reference backend");
            }
        }
    }
    bool gpu() const { return renderer_ != nullptr; }
    std::string device_name() const {
        return gpu()
                   ? device_->name()
                   : "C++ reference backend (" + std::to_string(jobs_.thread_count()) + " threads)";
    }

    // The frame's textures and the median pass times of `repeats` frames after a warm-up.
    Result<SweepRun> run(const gi::FrameInputs& in, int repeats, gi::FrameResult& frame) {
        const gi::PassPlan plan = gi::plan_passes(in, false);
        std::map<gi::Pass, std::vector<double>> passes;
        std::vector<double> totals;
        for (int rep = 0; rep <= repeats; ++rep) {
            const bool last = rep == repeats;
            if (gpu()) {
                auto f = gi::run_vulkan_frame(*renderer_, in, plan, last);
                if (!f) return f.error();
                frame = std::move(f.value());
            } else {
                frame = gi::run_reference_frame(in, plan, {&jobs_});
            }
            if (rep == 0) continue; // warm-up: pipeline creation, allocations
            totals.push_back(frame.total_ms);
            for (const gi::PassReport& p : frame.passes) passes[p.pass].push_back(p.gpu_ms);
        }
        SweepRun r;
        r.total_ms = median(totals);
        r.direct_ms = median(passes[gi::Pass::direct]) + median(passes[gi::Pass::directional]);
        r.heat_ms = median(passes[gi::Pass::heat]);
        r.blur_ms = median(passes[gi::Pass::blur]);
        r.distance_ms = median(passes[gi::Pass::distance_field]);
        r.radiosity_ms = median(passes[gi::Pass::radiosity]);
        r.gather_ms = median(passes[gi::Pass::gather]);
        return r;
    }

    // The `frames`-th frame since the scene appeared: `frames` frames of a still scene with
    // the converging rows' history kept (gi::Convergence), as a player sees them. The GPU
    // renderer keeps its textures between frames; the reference keeps them in one store.
    Result<gi::FrameResult> converged(const gi::FrameInputs& in, int frames) {
        gi::Convergence convergence;
        gi::ReferenceStore store;
        const gi::InputKeys keys = gi::input_keys_of(in);
        gi::FrameResult frame;
        for (int f = 0; f < frames; ++f) {
            const bool last = f == frames - 1;
            gi::PassPlan plan = gi::plan_passes(in, false);
            gi::derive_keys(in, plan, keys, &convergence);
            if (gpu()) {
                auto r = gi::run_vulkan_frame(*renderer_, in, plan, last);
                if (!r) return r.error();
                if (last) frame = std::move(r.value());
            } else {
                gi::execute_reference(in, plan, plan.run, {&jobs_}, store);
            }
            convergence.advance(plan.run);
        }
        if (!gpu()) { // the store's contract textures, as run_reference_frame returns them
            for (gi::Tex t :
                 gi::contract_textures([&](gi::Tex held) { return store.find(held) != nullptr; }))
                frame.textures.emplace(gi::tex_name(t), *store.find(t));
            frame.lit = store.lit;
        }
        return frame;
    }

  private:
    jobs::JobSystem& jobs_;
    std::unique_ptr<gpu::Device> device_; // declared first: destroyed after the renderer
    std::unique_ptr<gi::vk::Renderer> renderer_;
};

transport::TransportSettings reference_settings(const AccuracyOptions& o) {
    transport::TransportSettings t;
    t.albedo = o.albedo;
    t.resolution = 16; // the finest giResolution of the sweep
    t.target_relative_error = o.target > 0.0 ? o.target : o.quick ? 0.05 : 0.01;
    return t;
}

Result<transport::TransportResult> solve_reference(const AccuracyScene& s,
                                                   const transport::TransportSettings& t,
                                                   const AccuracyOptions& o,
                                                   jobs::JobSystem& jobs) {
    transport::ProgressBar bar("reference " + s.name);
    transport::SolveOptions so;
    so.jobs = &jobs;
    so.cache_dir =
        o.use_cache ? (o.cache_dir.empty() ? transport::default_cache_dir() : o.cache_dir) : "";
    so.progress = [&](const transport::SolveProgress& p) {
        bar.update(p.fraction, "batch " + std::to_string(p.batch) + ", rel. SE " +
                                   fmt("%.2f%%", 100.0 * p.relative_error) + " (target " +
                                   fmt("%.2f%%", 100.0 * p.target) + ")");
    };
    auto r = transport::solve_transport(s.scene, t, so);
    if (r) {
        const transport::TransportStats& st = r->stats;
        bar.finish(std::to_string(st.batches) + " batches, " +
                   fmt("%.1fM photons", double(st.photons) * 1e-6) + ", rel. SE " +
                   fmt("%.2f%%", 100.0 * st.relative_error) + ", " + fmt("%.0f s", st.seconds) +
                   (st.from_cache ? " (cached)" : ""));
    }
    return r;
}

// The reference's and Lantern's views at Lantern's default settings, for looking at.
Result<void> write_images(const AccuracyOptions& o, const std::string& name,
                          const ViewImages& img) {
    if (auto ok = ensure_directory(o.out_dir); !ok) return ok;
    const std::filesystem::path dir(o.out_dir);
    if (auto ok = write_png((dir / (name + "_reference.png")).string(), img.width, img.height, 3,
                            img.reference);
        !ok)
        return ok;
    return write_png((dir / (name + "_lantern.png")).string(), img.width, img.height, 3,
                     img.lantern);
}

Result<SceneReport> run_scene(const AccuracyScene& s, const AccuracyOptions& o,
                              LanternRunner& lantern, jobs::JobSystem& jobs) {
    auto ref = solve_reference(s, reference_settings(o), o, jobs);
    if (!ref) return ref.error();
    SceneReport report{s.name, s.description, ref->stats, reference_noise(*ref, s.scene), {}};
    std::vector<SweepSetting> settings = sweep(o.quick);
    if (!o.methods.empty())
        std::erase_if(settings, [&](const SweepSetting& set) {
            const char* name = set.is_gather() ? "gather" : set.is_radiosity() ? "radiosity" : "heat";
            return std::find(o.methods.begin(), o.methods.end(), name) == o.methods.end();
        });
    // A radiosity frame costs the same whatever K (accumulate only sets a weight): settings
    // with K > 1 take the timing of their K = 1 twin, so that timer noise does not reorder
    // points that differ only in error.
    std::map<std::string, SweepRun> timed; // by the label without K
    auto twin_key = [](SweepSetting set) {
        set.frames = 1;
        return set.label();
    };
    transport::ProgressBar bar("lantern " + s.name);
    for (std::size_t i = 0; i < settings.size(); ++i) {
        scene::Scene lit = settings[i].apply(s.scene);
        if (settings[i].is_gather()) lit.gi.wall_albedo = o.albedo; // the reference's
        const std::string count =
            " (" + std::to_string(i + 1) + "/" + std::to_string(settings.size()) + ")";
        bar.update(double(i) / double(settings.size()), settings[i].label() + count);
        std::string why;
        auto window = gi::compute_window(lit.view, lit.gi, &why);
        if (!window) return make_error(s.name + ": no GI window: " + why, 1);
        const gi::FrameInputs in = gi::gather_frame_inputs(lit, *window);
        const bool converging = settings[i].converges();
        const auto twin = timed.find(twin_key(settings[i]));
        gi::FrameResult frame;
        SweepRun run;
        if (converging && twin != timed.end()) {
            run = twin->second;
        } else {
            auto r = lantern.run(in, o.repeats, frame); // one frame's passes, history 0
            if (!r) return make_error(s.name + ": " + r.error().message, 1);
            run = *r;
            if (settings[i].is_radiosity() || settings[i].is_gather()) timed[twin_key(settings[i])] = run;
        }
        run.setting = settings[i];
        if (converging) { // scored at its K-th frame
            auto converged = lantern.converged(in, settings[i].frames);
            if (!converged) return make_error(s.name + ": " + converged.error().message, 1);
            frame = std::move(converged.value());
        }
        run.error = compare_to_reference(*ref, lit, in, frame);
        if (o.images && settings[i].is_default()) {
            if (auto ok = write_images(o, s.name, view_images(*ref, lit, in, frame)); !ok)
                return ok.error();
        }
        report.runs.push_back(run);
    }
    bar.finish(std::to_string(settings.size()) + " settings");
    return report;
}

Result<void> write_outputs(const AccuracyOptions& o, const ReportContext& context,
                           const std::vector<SceneReport>& scenes) {
    if (auto ok = ensure_directory(o.out_dir); !ok) return ok;
    const std::filesystem::path dir(o.out_dir);
    if (auto ok =
            write_file_atomic((dir / "accuracy.md").string(), markdown_report(context, scenes));
        !ok)
        return ok;
    if (auto ok = write_file_atomic((dir / "accuracy.csv").string(), csv_report(scenes)); !ok)
        return ok;
    for (const SceneReport& s : scenes)
        if (auto ok = write_plot(s, context.device, (dir / (s.name + ".png")).string()); !ok)
            return ok;
    return {};
}

} // namespace

std::string SweepSetting::taps() const {
    if (!hierarchical) return "8 @ 1 texel";
    const int heat_texels_per_tile = resolution / int(scale); // the diffusion distance is one tile
    return heat_texels_per_tile > 2 ? "rings" : "8 @ 1 tile"; // rings beyond 2.5 heat texels
}

SweepSetting SweepSetting::radiosity(int resolution, scene::HeatScale scale, int rays, int steps,
                                     int frames) {
    SweepSetting s;
    s.method = scene::GiMethod::radiosity;
    s.resolution = resolution;
    s.scale = scale;
    s.rays = rays;
    s.steps = steps;
    s.frames = frames;
    return s;
}

SweepSetting SweepSetting::gather(int resolution, scene::HeatScale scale, int rays, int face_rays, int frames) {
    SweepSetting s = radiosity(resolution, scale, rays, face_rays, frames);
    s.method = scene::GiMethod::gather;
    return s;
}

bool SweepSetting::is_default() const {
    return apply(scene::Scene{}).gi == scene::GiSettings{};
}

std::string SweepSetting::variant() const {
    if (is_radiosity()) return "R";
    if (is_gather()) return "G";
    if (!hierarchical) return "H";
    if (!per_channel) return "P";
    if (!blur) return "B";
    return "";
}

std::string SweepSetting::label() const {
    const char* grid = scale == scene::HeatScale::full   ? "full"
                       : scale == scene::HeatScale::half ? "half"
                                                         : "quarter";
    const std::string base = "giRes " + std::to_string(resolution) + " " + grid;
    if (is_radiosity() || is_gather())
        return variant() + " " + base + " " + std::to_string(rays) + "x" + std::to_string(steps) + " K" +
               std::to_string(frames) + (blur ? "" : " B");
    const std::string v = variant();
    return base + " " + std::to_string(rounds) + "r" + (v.empty() ? "" : " " + v);
}

scene::Scene SweepSetting::apply(const scene::Scene& s) const {
    scene::Scene out = s;
    out.gi.resolution = resolution;
    if (is_radiosity()) { // the heat keys stay the scene's: the method does not read them
        out.gi.method = scene::GiMethod::radiosity;
        out.gi.blur = blur;
        out.gi.radiosity.scale = scale;
        out.gi.radiosity.rays = rays;
        out.gi.radiosity.steps = steps;
        out.gi.radiosity.accumulate = frames;
        return out;
    }
    if (is_gather()) {
        out.gi.method = scene::GiMethod::gather;
        out.gi.blur = blur;
        out.gi.gather.scale = scale;
        out.gi.gather.rays = rays;
        out.gi.gather.face_rays = steps;
        out.gi.gather.frames = frames;
        out.gi.gather.margin = 8; // the reference's domain: the window plus 8 tiles
        return out;
    }
    out.gi.method = scene::GiMethod::heat;
    out.gi.heat_rounds = rounds;
    out.gi.heat_scale = scale;
    out.gi.per_channel = per_channel;
    out.gi.blur = blur;
    // Lantern has no switch for the rings: they engage when the diffusion distance spans more
    // than 2.5 heat texels. "Off" is the seed's texel-scale hop: one heat texel.
    out.gi.diffusion_distance = hierarchical ? 1.0f : float(int(scale)) / float(resolution);
    return out;
}

std::vector<SweepSetting> sweep(bool quick) {
    using scene::HeatScale;
    auto variants = [](int res) {
        return std::vector<SweepSetting>{{res, 20, HeatScale::full, false, true, true},
                                         {res, 20, HeatScale::full, true, false, true},
                                         {res, 20, HeatScale::full, true, true, false}};
    };
    if (quick) {
        std::vector<SweepSetting> out{{4, 20, HeatScale::full}, {8, 20, HeatScale::full}};
        for (const SweepSetting& v : variants(8)) out.push_back(v);
        for (int k : {1, 4, 16})
            out.push_back(SweepSetting::radiosity(8, HeatScale::quarter, 16, 32, k));
        for (int k : {1, 8}) out.push_back(SweepSetting::gather(8, HeatScale::half, 32, 32, k));
        return out;
    }
    std::vector<SweepSetting> out;
    for (int res : {4, 8, 16})
        for (HeatScale scale : {HeatScale::full, HeatScale::half, HeatScale::quarter})
            for (int rounds : {10, 20, 40}) out.push_back({res, rounds, scale});
    for (int res : {4, 8, 16})
        for (const SweepSetting& v : variants(res)) out.push_back(v);
    // Radiosity (seed 003) at Lantern's giRes: its grid at quarter (the default) and half,
    // rays x steps at one frame, then the cheap and the dear ray counts after 4 and 16
    // frames of feedback and accumulation.
    for (HeatScale scale : {HeatScale::quarter, HeatScale::half}) {
        for (int rays : {8, 16, 32, 64})
            for (int steps : {32, 64})
                out.push_back(SweepSetting::radiosity(8, scale, rays, steps, 1));
        for (int k : {4, 16})
            for (int rays : {16, 64}) out.push_back(SweepSetting::radiosity(8, scale, rays, 32, k));
    }
    // Gather (physical) after 8 frames (16 bounces at the default 2 a frame: albedo 0.5 leaves
    // 2^-16 of the light unbounced), over its grid and ray counts; the default after 1 and 4.
    for (HeatScale scale : {HeatScale::half, HeatScale::quarter})
        for (int rays : {16, 32, 64}) out.push_back(SweepSetting::gather(8, scale, rays, rays, 8));
    out.push_back(SweepSetting::gather(8, HeatScale::full, 32, 32, 8));
    for (int rays : {32, 64}) out.push_back(SweepSetting::gather(16, HeatScale::quarter, rays, rays, 8));
    for (int k : {1, 4}) out.push_back(SweepSetting::gather(8, HeatScale::half, 32, 32, k));
    return out;
}

namespace {

// --baked: the bake against the reference (docs/baked.md, "Accuracy against the reference").
// Every point and emissive light is mixed, so the frame is Lantern's live direct light plus
// the baked bounce as the run time reads it (cache file, bricks at the settings' eps, RGBM,
// bilinear); suns stay realtime (their bounce live). The live gather at the scene's own
// settings, all lights realtime, is the row beside it.
int baked_accuracy(const AccuracyOptions& o, std::vector<AccuracyScene>& scenes, LanternRunner& lantern,
                   jobs::JobSystem& jobs, const std::string& machine) {
    std::string md = "# The bake against the transport reference\n\n";
    md += "`" + o.command + "`; " + machine + "; " + lantern.device_name() + ".\n\n";
    md += "Relative RMSE against the reference over the visible view (docs/accuracy.md, \"Metrics\"); "
          "\"fit\": after the least-squares exposure fit.\n\n";
    md += "| scene | bake (s) | bake: total | indirect | indirect, fit | live gather: total | indirect | indirect, fit | "
          "reference noise (indirect) |\n|---|---|---|---|---|---|---|---|---|\n";
    const auto dir = std::filesystem::temp_directory_path() / ("lantern-bench-baked-accuracy-" + std::to_string(now_ns()));
    for (const AccuracyScene& s : scenes) {
        auto ref = solve_reference(s, reference_settings(o), o, jobs);
        if (!ref) {
            std::fprintf(stderr, "lantern-bench: %s\n", ref.error().message.c_str());
            return ref.error().exit_code;
        }
        scene::Scene lit = s.scene;
        lit.gi.method = scene::GiMethod::gather;
        lit.gi.wall_albedo = o.albedo; // the reference's
        const ReferenceNoise noise = reference_noise(*ref, lit);
        std::string why;
        auto window = gi::compute_window(lit.view, lit.gi, &why);
        if (!window) {
            std::fprintf(stderr, "lantern-bench: %s: no GI window: %s\n", s.name.c_str(), why.c_str());
            return 1;
        }
        // The live gather, every light realtime, converged over its frames as a player sees it.
        const gi::FrameInputs live_in = gi::gather_frame_inputs(lit, *window);
        auto live = lantern.converged(live_in, lit.gi.gather.frames);
        if (!live) {
            std::fprintf(stderr, "lantern-bench: %s: %s\n", s.name.c_str(), live.error().message.c_str());
            return 1;
        }
        const ErrorMetrics live_err = compare_to_reference(*ref, lit, live_in, *live);
        // The bake at the frame's resolution, everything else at the bake's defaults.
        scene::Scene mixed = lit;
        for (auto& l : mixed.point_lights) l.mode = scene::LightMode::mixed;
        for (auto& l : mixed.emissive_lights) l.mode = scene::LightMode::mixed;
        bake::BakeSettings settings = mixed.bake;
        settings.resolution = lit.gi.resolution;
        bake::BakeOptions options;
        options.jobs = &jobs;
        transport::ProgressBar bar("bake " + s.name);
        options.progress = [&](const bake::BakeProgress& p) {
            bar.update(p.total ? double(p.done) / double(p.total) : 1.0, std::to_string(p.done) + "/" + std::to_string(p.total) + " chunks");
        };
        const std::int64_t t0 = now_ns();
        auto light = bake::load_world_light(mixed, (dir / s.name).string(), settings, options);
        const double bake_s = double(now_ns() - t0) * 1e-9;
        if (!light) {
            std::fprintf(stderr, "lantern-bench: %s: %s\n", s.name.c_str(), light.error().message.c_str());
            return light.error().exit_code;
        }
        bar.finish(std::to_string(bake::scene_chunks(mixed).size()) + " chunks in " + std::to_string(int(bake_s)) + " s");
        const scene::Scene live_part = bake::live_scene(mixed);
        gi::FrameInputs in = gi::gather_frame_inputs(live_part, *window);
        in.baked = *light;
        gi::split_for_bake(in, live_part);
        auto frame = lantern.converged(in, lit.gi.gather.frames);
        if (!frame) {
            std::fprintf(stderr, "lantern-bench: %s: %s\n", s.name.c_str(), frame.error().message.c_str());
            return 1;
        }
        const ErrorMetrics err = compare_to_reference(*ref, lit, in, *frame);
        char row[512];
        std::snprintf(row, sizeof(row), "| %s | %.1f | %.1f %% | %.1f %% | %.1f %% | %.1f %% | %.1f %% | %.1f %% | %.1f %% |\n",
                      s.name.c_str(), bake_s, 100.0 * err.total_rmse, 100.0 * err.indirect_rmse,
                      100.0 * err.indirect_rmse_fit, 100.0 * live_err.total_rmse, 100.0 * live_err.indirect_rmse,
                      100.0 * live_err.indirect_rmse_fit, 100.0 * noise.indirect);
        md += row;
        std::fputs(row, stderr);
    }
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    if (auto ok = ensure_directory(o.out_dir); !ok) {
        std::fprintf(stderr, "lantern-bench: %s\n", ok.error().message.c_str());
        return 1;
    }
    const std::string path = (std::filesystem::path(o.out_dir) / "baked_accuracy.md").string();
    if (auto ok = write_file_atomic(path, md); !ok) {
        std::fprintf(stderr, "lantern-bench: %s\n", ok.error().message.c_str());
        return 1;
    }
    std::fputs(md.c_str(), stdout);
    std::fprintf(stderr, "lantern-bench: wrote %s\n", path.c_str());
    return 0;
}

} // namespace

int accuracy(const AccuracyOptions& o) {
    jobs::JobSystem jobs;
    ReportContext context;
    context.command = o.command;
    context.machine = describe_machine();
    context.reference = reference_settings(o);
    std::vector<AccuracyScene> scenes = accuracy_scenes(o.maps_dir, o.quick, context.notes);
    if (!o.scenes.empty())
        std::erase_if(scenes, [&](const AccuracyScene& s) {
            return std::find(o.scenes.begin(), o.scenes.end(), s.name) == o.scenes.end();
        });
    if (scenes.empty()) {
        std::fprintf(stderr, "lantern-bench: no scene to run\n");
        return 2;
    }
    LanternRunner lantern(o.backend, jobs, context.notes);
    context.device = lantern.device_name();
    context.timing = lantern.gpu() ? "GPU timestamps, sum of the passes, median of " +
                                         std::to_string(o.repeats) + " frames after a warm-up"
                                   : "C++ reference backend wall time, median of " +
                                         std::to_string(o.repeats) + " frames";
    for (const std::string& note : context.notes)
        std::fprintf(stderr, "lantern-bench: note: %s\n", note.c_str());
    if (o.baked) return baked_accuracy(o, scenes, lantern, jobs, context.machine);
    std::vector<SceneReport> reports;
    for (const AccuracyScene& s : scenes) {
        auto r = run_scene(s, o, lantern, jobs);
        if (!r) {
            std::fprintf(stderr, "lantern-bench: %s\n", r.error().message.c_str());
            return r.error().exit_code;
        }
        reports.push_back(std::move(r.value()));
    }
    mark_fronts(reports);
    if (auto ok = write_outputs(o, context, reports); !ok) {
        std::fprintf(stderr, "lantern-bench: %s\n", ok.error().message.c_str());
        return 1;
    }
    std::fputs(markdown_report(context, reports).c_str(), stdout);
    std::fprintf(stderr, "lantern-bench: wrote %s/accuracy.md, accuracy.csv and %zu plots\n",
                 o.out_dir.c_str(), reports.size());
    return 0;
}

} // namespace lantern::bench

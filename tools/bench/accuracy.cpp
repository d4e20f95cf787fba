// lantern-bench accuracy: for each scene, the transport reference once, then every setting
// of the sweep timed on the GPU (median of GPU timestamps) and compared with it.
#include "accuracy.hpp"
#include "bench.hpp"

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
        return r;
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
    const std::vector<SweepSetting> settings = sweep(o.quick);
    transport::ProgressBar bar("lantern " + s.name);
    for (std::size_t i = 0; i < settings.size(); ++i) {
        const scene::Scene lit = settings[i].apply(s.scene);
        bar.update(double(i) / double(settings.size()),
                   "giRes " + std::to_string(settings[i].resolution) + " (" +
                       std::to_string(i + 1) + "/" + std::to_string(settings.size()) + ")");
        std::string why;
        auto window = gi::compute_window(lit.view, lit.gi.padding, lit.gi.resolution, &why);
        if (!window) return make_error(s.name + ": no GI window: " + why, 1);
        const gi::FrameInputs in = gi::gather_frame_inputs(lit, *window);
        gi::FrameResult frame;
        auto run = lantern.run(in, o.repeats, frame);
        if (!run) return make_error(s.name + ": " + run.error().message, 1);
        run->setting = settings[i];
        run->error = compare_to_reference(*ref, lit, in, frame);
        if (o.images && settings[i].is_default()) {
            if (auto ok = write_images(o, s.name, view_images(*ref, lit, in, frame)); !ok)
                return ok.error();
        }
        report.runs.push_back(*run);
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

bool SweepSetting::is_default() const {
    return apply(scene::Scene{}).gi == scene::GiSettings{};
}

std::string SweepSetting::variant() const {
    if (!hierarchical) return "H";
    if (!per_channel) return "P";
    if (!blur) return "B";
    return "";
}

scene::Scene SweepSetting::apply(const scene::Scene& s) const {
    scene::Scene out = s;
    out.gi.resolution = resolution;
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
        return out;
    }
    std::vector<SweepSetting> out;
    for (int res : {4, 8, 16})
        for (HeatScale scale : {HeatScale::full, HeatScale::half, HeatScale::quarter})
            for (int rounds : {10, 20, 40}) out.push_back({res, rounds, scale});
    for (int res : {4, 8, 16})
        for (const SweepSetting& v : variants(res)) out.push_back(v);
    return out;
}

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

// lantern-bench accuracy: the settings sweep, its results and how they are reported.
#pragma once

#include "accuracy_metrics.hpp"
#include "accuracy_scenes.hpp"

#include "lantern/core/result.hpp"
#include "lantern/transport/solver.hpp"

#include <string>
#include <vector>

namespace lantern::bench {

// One point of the sweep: the GI settings it changes from the scene's defaults.
struct SweepSetting {
    int resolution = 8;
    int rounds = 20;
    scene::HeatScale scale =
        scene::HeatScale::full; // heat's grid, or radiosity's (radiosity.scale)
    bool hierarchical = true;   // false: diffusion distance of one heat texel (8 taps, no rings)
    bool per_channel = true;    // false: physical (scalar) diffusion weights
    bool blur = true;
    // gi.method = radiosity (seed 003): the settings below apply, the heat ones above do not
    // (except resolution, scale and blur).
    scene::GiMethod method = scene::GiMethod::heat;
    int rays = 16, steps = 32;
    // Radiosity: the frames run since the scene appeared (K), with radiosity.accumulate = K:
    // the frame scored is the K-th (K = 1: one frame, history 0, a single bounce).
    int frames = 1;

    // gi.method = gather (physical): scale = gather.scale, rays = gather.rays, steps =
    // gather.face_rays, frames = K (the K-th frame is scored; gather.frames = K).
    static SweepSetting radiosity(int resolution, scene::HeatScale scale, int rays, int steps,
                                  int frames);
    static SweepSetting gather(int resolution, scene::HeatScale scale, int rays, int face_rays, int frames);
    bool is_radiosity() const { return method == scene::GiMethod::radiosity; }
    bool is_gather() const { return method == scene::GiMethod::gather; }
    // A method whose frame K is scored after K frames of history.
    bool converges() const { return (is_radiosity() || is_gather()) && frames > 1; }

    // The taps the heat pass uses: "rings" (three tiers), "8 @ 1 tile" or "8 @ 1 texel".
    std::string taps() const;
    // Whether these are Lantern's default GI settings (a scene file without a "gi" object).
    bool is_default() const;
    // "" for the main grid, "H" hierarchical off, "P" physical, "B" blur off, "R" radiosity.
    std::string variant() const;
    // A unique one-line name: "giRes 8 full 20r", "giRes 8 full 20r H", "R giRes 8 quarter 16x32
    // K4".
    std::string label() const;
    // The scene with these settings applied.
    scene::Scene apply(const scene::Scene& s) const;
};

// The default sweep (heat: giRes 4/8/16 x full/half/quarter x 10/20/40 rounds, plus each
// toggle at 20 rounds, full scale, every resolution; radiosity: giRes 8, quarter and half
// grid, 8/16/32/64 rays x 32/64 steps at K = 1, 16 and 64 rays x 32 steps at K = 4 and 16)
// or the --quick one (five heat settings; radiosity quarter 16 x 32 at K = 1, 4, 16; gather
// half 32 x 32 at K = 1 and 8). Gather: giRes 8 half and quarter x 16 / 32 / 64 rays, full at
// 32, giRes 16 quarter at 32 and 64, all at K = 8, and the default at K = 1 and 4.
std::vector<SweepSetting> sweep(bool quick);

struct SweepRun {
    SweepSetting setting;
    double total_ms = 0.0, direct_ms = 0.0, heat_ms = 0.0, blur_ms = 0.0; // medians
    double distance_ms = 0.0, radiosity_ms = 0.0; // radiosity's passes (medians)
    double gather_ms = 0.0;                       // the gather method's pass (median)
    ErrorMetrics error;                           // radiosity: of the K-th frame
    // On the Pareto front of fitted total relative RMSE against time among the runs of the
    // same method.
    bool front = false;
};

struct SceneReport {
    std::string name, description;
    transport::TransportStats reference;
    ReferenceNoise noise;
    std::vector<SweepRun> runs;
};

struct ReportContext {
    std::string command; // how the report was produced
    std::string device;  // what the timings ran on
    std::string timing;  // "GPU timestamps, median of N frames after a warm-up" or the fallback
    std::string machine;
    transport::TransportSettings reference;
    std::vector<std::string> notes;
};

// snprintf of one number.
std::string fmt(const char* format, double value);

// Marks the Pareto front of every scene's runs, one front per method.
void mark_fronts(std::vector<SceneReport>& scenes);
std::string markdown_report(const ReportContext& context, const std::vector<SceneReport>& scenes);
std::string csv_report(const std::vector<SceneReport>& scenes);
// A PNG of fitted relative RMSE against frame time, Pareto fronts marked (one per method):
// total light, and the ground without direct light (when the scene has some).
Result<void> write_plot(const SceneReport& scene, const std::string& device,
                        const std::string& path);

} // namespace lantern::bench

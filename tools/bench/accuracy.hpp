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
    scene::HeatScale scale = scene::HeatScale::full;
    bool hierarchical = true; // false: diffusion distance of one heat texel (8 taps, no rings)
    bool per_channel = true;  // false: physical (scalar) diffusion weights
    bool blur = true;

    // The taps the heat pass uses: "rings" (three tiers), "8 @ 1 tile" or "8 @ 1 texel".
    std::string taps() const;
    // Whether these are Lantern's default GI settings (a scene file without a "gi" object).
    bool is_default() const;
    // "" for the main grid, "H" hierarchical off, "P" physical, "B" blur off.
    std::string variant() const;
    // The scene with these settings applied.
    scene::Scene apply(const scene::Scene& s) const;
};

// The default sweep (giRes 4/8/16 x full/half/quarter x 10/20/40 rounds, plus each toggle
// at 20 rounds, full scale, every resolution) or the --quick one.
std::vector<SweepSetting> sweep(bool quick);

struct SweepRun {
    SweepSetting setting;
    double total_ms = 0.0, direct_ms = 0.0, heat_ms = 0.0, blur_ms = 0.0; // medians
    ErrorMetrics error;
    bool front = false; // on the Pareto front of fitted total relative RMSE against time
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

// Marks the Pareto front of every scene's runs.
void mark_fronts(std::vector<SceneReport>& scenes);
std::string markdown_report(const ReportContext& context, const std::vector<SceneReport>& scenes);
std::string csv_report(const std::vector<SceneReport>& scenes);
// A PNG of fitted relative RMSE against frame time, Pareto fronts marked: total light, and
// the ground without direct light (when the scene has some).
Result<void> write_plot(const SceneReport& scene, const std::string& device,
                        const std::string& path);

} // namespace lantern::bench

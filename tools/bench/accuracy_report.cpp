// The accuracy benchmark's outputs: Markdown, CSV and plots.
#include "accuracy.hpp"
#include "plot.hpp"

#include <cstdio>

namespace lantern::bench {
namespace {

std::string pct(double v) {
    return fmt("%.1f", 100.0 * v);
}

const char* scale_name(scene::HeatScale s) {
    return s == scene::HeatScale::full ? "full" : s == scene::HeatScale::half ? "half" : "quarter";
}

std::uint32_t resolution_color(int res) {
    return res <= 4 ? 0x1F77B4 : res <= 8 ? 0x2CA02C : 0xD62728;
}

Marker scale_marker(scene::HeatScale s) {
    return s == scene::HeatScale::full   ? Marker::circle
           : s == scene::HeatScale::half ? Marker::square
                                         : Marker::triangle;
}

// Radiosity points: coloured by frames (K), shaped by their grid; their front in its own colour.
std::uint32_t frames_color(int k) {
    return k <= 1 ? 0xFDB863 : k <= 4 ? 0xE66101 : 0x8C2D04;
}

Marker radiosity_marker(scene::HeatScale s) {
    return s == scene::HeatScale::quarter ? Marker::triangle_down : Marker::diamond;
}

constexpr std::uint32_t heat_front_color = 0x303030, radiosity_front_color = 0xC51B7D;

bool has_radiosity(const SceneReport& s) {
    for (const SweepRun& r : s.runs)
        if (r.setting.is_radiosity() || r.setting.is_gather()) return true;
    return false;
}

constexpr scene::GiMethod all_methods[] = {scene::GiMethod::heat, scene::GiMethod::radiosity, scene::GiMethod::gather};
constexpr std::uint32_t gather_front_color = 0x1B9E77;

// The Pareto front of `metric` against time among the runs of one method (indices into runs).
std::vector<std::size_t> front_of(const std::vector<SweepRun>& runs, double ErrorMetrics::*metric,
                                  scene::GiMethod method) {
    std::vector<std::size_t> index;
    std::vector<double> x, y;
    for (std::size_t i = 0; i < runs.size(); ++i)
        if (runs[i].setting.method == method) {
            index.push_back(i);
            x.push_back(runs[i].total_ms), y.push_back(runs[i].error.*metric);
        }
    std::vector<std::size_t> front;
    for (std::size_t i : pareto_front(x, y)) front.push_back(index[i]);
    return front;
}

Panel panel(const SceneReport& s, const char* title, const std::string& x_label,
            double ErrorMetrics::*metric) {
    Panel p{title, x_label, "relative RMSE", true, {}};
    for (const SweepRun& r : s.runs) {
        PlotPoint pt;
        pt.x = r.total_ms;
        pt.y = r.error.*metric;
        if (r.setting.is_radiosity()) {
            pt.color = frames_color(r.setting.frames);
            pt.marker = radiosity_marker(r.setting.scale);
            pt.series = 1;
            pt.front_color = radiosity_front_color;
        } else if (r.setting.is_gather()) {
            pt.color = resolution_color(r.setting.resolution);
            pt.marker = scale_marker(r.setting.scale);
            pt.hollow = true;
            pt.series = 2;
            pt.front_color = gather_front_color;
        } else {
            pt.color = resolution_color(r.setting.resolution);
            pt.marker = scale_marker(r.setting.scale);
            pt.front_color = heat_front_color;
            if (!r.setting.variant().empty()) {
                pt.marker = Marker::diamond;
                pt.hollow = true;
                pt.tag = r.setting.variant();
            }
        }
        p.points.push_back(pt);
    }
    for (scene::GiMethod m : all_methods)
        for (std::size_t i : front_of(s.runs, metric, m)) {
            PlotPoint& pt = p.points[i];
            const SweepSetting& set = s.runs[i].setting;
            pt.front = true;
            pt.tag = set.is_radiosity() || set.is_gather()
                         ? set.variant() + std::to_string(set.rays) + "x" + std::to_string(set.steps) + " K" +
                               std::to_string(set.frames)
                         : (pt.tag.empty() ? "" : pt.tag + " ") + std::to_string(set.rounds) + "r";
        }
    return p;
}

std::vector<LegendEntry> legend(bool radiosity, bool gather) {
    std::vector<LegendEntry> l{
        {"heat: giRes 4", 0x1F77B4},
        {"giRes 8", 0x2CA02C},
        {"giRes 16", 0xD62728},
        {"full", 0x000000, Marker::circle},
        {"half", 0x000000, Marker::square},
        {"quarter", 0x000000, Marker::triangle},
        {"H: no rings, P: physical, B: no blur", 0x000000, Marker::diamond, true},
        {"heat Pareto front (rounds)", heat_front_color, Marker::circle, false, true}};
    if (!radiosity) {
        l.front().label = "giRes 4";
        l.back().label = "Pareto front (rounds)";
        return l;
    }
    for (LegendEntry e :
         std::vector<LegendEntry>{{"radiosity giRes 8: K = 1 frame", frames_color(1)},
                                  {"K = 4", frames_color(4)},
                                  {"K = 16", frames_color(16)},
                                  {"half grid", 0x000000, Marker::diamond},
                                  {"quarter grid", 0x000000, Marker::triangle_down},
                                  {"radiosity Pareto front (rays x steps, K)",
                                   radiosity_front_color, Marker::circle, false, true}})
        l.push_back(e);
    if (gather)
        l.push_back({"gather (hollow; giRes colour, grid shape): Pareto front (G rays, K)", gather_front_color,
                     Marker::circle, false, true});
    return l;
}

std::string table_row(const SweepRun& r) {
    const SweepSetting& s = r.setting;
    const ErrorMetrics& e = r.error;
    return "| " + std::to_string(s.resolution) + " | " + scale_name(s.scale) + " | " +
           std::to_string(s.rounds) + " | " + s.taps() + " | " +
           (s.per_channel ? "per-channel" : "physical") + " | " + (s.blur ? "on" : "off") + " | " +
           fmt("%.1f", r.total_ms) + " | " + pct(e.total_rmse) + " | " + pct(e.total_rmse_fit) +
           " | " + pct(e.indirect_rmse) + " | " + pct(e.indirect_rmse_fit) + " | " +
           fmt("%.2f", e.indirect_scale) + " | " +
           (e.shadow_texels ? pct(e.shadow_rmse_fit) : std::string("-")) + " | " +
           pct(e.max_error) + " | " + fmt("%.3f", e.ssim) + " | " + (r.front ? "yes" : "") + " |\n";
}

std::string radiosity_row(const SweepRun& r) {
    const SweepSetting& s = r.setting;
    const ErrorMetrics& e = r.error;
    return "| " + std::to_string(s.resolution) + " | " + scale_name(s.scale) + " | " +
           std::to_string(s.rays) + " | " + std::to_string(s.steps) + " | " +
           std::to_string(s.frames) + " | " + (s.blur ? "on" : "off") + " | " +
           fmt("%.1f", r.total_ms) + " | " + pct(e.total_rmse) + " | " + pct(e.total_rmse_fit) +
           " | " + pct(e.indirect_rmse) + " | " + pct(e.indirect_rmse_fit) + " | " +
           fmt("%.2f", e.indirect_scale) + " | " +
           (e.shadow_texels ? pct(e.shadow_rmse_fit) : std::string("-")) + " | " +
           pct(e.max_error) + " | " + fmt("%.3f", e.ssim) + " | " + (r.front ? "yes" : "") + " |\n";
}

// "19.4 % (giRes 8 quarter 40r, 61.2 ms, ind. scale 0.66)": the run of `method` with the
// lowest fitted total rRMSE.
std::string best_of(const SceneReport& s, scene::GiMethod method) {
    const SweepRun* best = nullptr;
    for (const SweepRun& r : s.runs)
        if (r.setting.method == method &&
            (!best || r.error.total_rmse_fit < best->error.total_rmse_fit))
            best = &r;
    if (!best) return "-";
    return pct(best->error.total_rmse_fit) + " % (" + best->setting.label() + ", " +
           fmt("%.1f", best->total_ms) + " ms, ind. scale " +
           fmt("%.2f", best->error.indirect_scale) + ")";
}

std::string scene_section(const SceneReport& s) {
    const transport::TransportStats& ref = s.reference;
    std::string md = "\n## " + s.name + "\n\n" + s.description + ".\n\n";
    md += "Reference: " + std::to_string(ref.batches) + " batches, " +
          fmt("%.1fM", double(ref.photons) * 1e-6) + " photons, " + fmt("%.0f s", ref.seconds) +
          (ref.from_cache ? " (read from the cache)" : "") +
          "; its relative standard error over the " + std::to_string(s.noise.texels) +
          " compared texels: indirect " + fmt("%.2f %%", 100.0 * s.noise.indirect) + ", total " +
          fmt("%.2f %%", 100.0 * s.noise.total) + ".\n\n";
    md += "| giRes | heat | rounds | taps | diffusion | blur | ms | total rRMSE % | fit | indirect "
          "rRMSE % | fit | "
          "ind. scale | shadow fit % | max err % | SSIM | Pareto |\n";
    md += "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const SweepRun& r : s.runs)
        if (r.setting.method == scene::GiMethod::heat) md += table_row(r);
    if (!has_radiosity(s)) return md;
    md += "\nRadiosity (gi.method = radiosity, seed 003): grid = radiosity.scale; K = frames run "
          "since the scene appeared, with radiosity.accumulate = K (feedback " +
          fmt("%.2g", double(scene::RadiositySettings{}.feedback)) +
          ", the other radiosity keys at their defaults); ms: one frame's passes at history 0 "
          "(K > 1: the K = 1 twin's); the errors are the K-th frame's. Pareto: among the radiosity "
          "settings.\n\n";
    md +=
        "| giRes | grid | rays | steps | K | blur | ms | total rRMSE % | fit | indirect rRMSE % | "
        "fit | ind. scale | shadow fit % | max err % | SSIM | Pareto |\n";
    md += "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const SweepRun& r : s.runs)
        if (r.setting.is_radiosity()) md += radiosity_row(r);
    bool gather = false;
    for (const SweepRun& r : s.runs) gather = gather || r.setting.is_gather();
    if (gather) {
        md += "\nGather (gi.method = gather, physical; wall albedo " +
              fmt("%.2g", double(scene::GiSettings{}.wall_albedo)) +
              ", margin 8 tiles: the reference's domain): grid = gather.scale, rays = gather.rays, steps = gather.face_rays, K = frames run since "
              "the scene appeared (gather.bounces 2 a frame); ms: one frame at history 0; no exposure fit "
              "is needed (ind. scale near 1 when the level is right).\n\n";
        md += "| giRes | grid | rays | face rays | K | blur | ms | total rRMSE % | fit | indirect rRMSE % | "
              "fit | ind. scale | shadow fit % | max err % | SSIM | Pareto |\n";
        md += "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
        for (const SweepRun& r : s.runs)
            if (r.setting.is_gather()) md += radiosity_row(r);
    }
    md += "\nLowest fitted total rRMSE: heat " + best_of(s, scene::GiMethod::heat) + "; radiosity " +
          best_of(s, scene::GiMethod::radiosity) + (gather ? "; gather " + best_of(s, scene::GiMethod::gather) : "") +
          ".\n";
    return md;
}

} // namespace

std::string fmt(const char* format, double value) {
    char b[64];
    std::snprintf(b, sizeof(b), format, value);
    return b;
}

void mark_fronts(std::vector<SceneReport>& scenes) {
    for (SceneReport& s : scenes)
        for (scene::GiMethod m : all_methods)
            for (std::size_t i : front_of(s.runs, &ErrorMetrics::total_rmse_fit, m))
                s.runs[i].front = true;
}

std::string markdown_report(const ReportContext& c, const std::vector<SceneReport>& scenes) {
    const transport::TransportSettings& t = c.reference;
    std::string md = "# Lantern accuracy: error against run time\n\n";
    md += "Command: `" + c.command + "`\n\nDevice: " + c.device + " (" + c.timing +
          ")\n\nMachine: " + c.machine + "\n\n";
    md += "Reference: 2D light transport, wall albedo " + fmt("%.2f", double(t.albedo)) +
          ", up to " + std::to_string(t.max_bounces) + " bounces, " + std::to_string(t.resolution) +
          " texels per tile, margin " + std::to_string(t.margin) +
          " tiles, target relative standard error " +
          fmt("%.1f %%", 100.0 * t.target_relative_error) + ".\n\n";
    md += "Compared: the visible view's ground texels at the reference resolution. rRMSE: relative "
          "RMSE; fit: after "
          "the least-squares exposure fit; ind. scale: that fit's factor for indirect light; "
          "shadow fit: fitted rRMSE "
          "over the texels without direct light in the reference; max err: largest luminance error "
          "over the largest "
          "reference luminance. Pareto: no other setting is both faster and closer (fitted total "
          "rRMSE)";
    bool radiosity = false;
    for (const SceneReport& s : scenes) radiosity = radiosity || has_radiosity(s);
    md += radiosity ? "; each GI method has its own front.\n" : ".\n";
    for (const std::string& note : c.notes) md += "\nNote: " + note + "\n";
    for (const SceneReport& s : scenes) md += scene_section(s);
    return md;
}

std::string csv_report(const std::vector<SceneReport>& scenes) {
    std::string csv =
        "scene,gi_resolution,heat_scale,heat_rounds,taps,diffusion,blur,total_ms,direct_ms,heat_ms,"
        "blur_ms,"
        "total_rmse,total_rmse_fit,total_scale,indirect_rmse,indirect_rmse_fit,indirect_scale,"
        "shadow_rmse_fit,shadow_texels,max_error,ssim,pareto,texels,reference_rel_se_indirect,"
        "method,radiosity_scale,radiosity_rays,radiosity_steps,frames,distance_ms,radiosity_ms\n";
    for (const SceneReport& s : scenes)
        for (const SweepRun& r : s.runs) {
            const ErrorMetrics& e = r.error;
            const SweepSetting& set = r.setting;
            const bool rad = set.is_radiosity() || set.is_gather(); // the heat columns empty, and the reverse
            const std::string heat = rad ? std::string(",,,")
                                         : std::string(scale_name(set.scale)) + "," +
                                               std::to_string(set.rounds) + "," + set.taps() + "," +
                                               (set.per_channel ? "per-channel" : "physical");
            const std::string radiosity = rad ? std::string(set.is_gather() ? "gather," : "radiosity,") +
                                                    scale_name(set.scale) +
                                                    "," + std::to_string(set.rays) + "," +
                                                    std::to_string(set.steps) + "," +
                                                    std::to_string(set.frames)
                                              : std::string("heat,,,,1");
            csv += s.name + "," + std::to_string(set.resolution) + "," + heat + "," +
                   (set.blur ? "on" : "off") + "," + fmt("%.4f", r.total_ms) + "," +
                   fmt("%.4f", r.direct_ms) + "," + fmt("%.4f", r.heat_ms) + "," +
                   fmt("%.4f", r.blur_ms) + "," + fmt("%.6f", e.total_rmse) + "," +
                   fmt("%.6f", e.total_rmse_fit) + "," + fmt("%.6f", e.total_scale) + "," +
                   fmt("%.6f", e.indirect_rmse) + "," + fmt("%.6f", e.indirect_rmse_fit) + "," +
                   fmt("%.6f", e.indirect_scale) + "," + fmt("%.6f", e.shadow_rmse_fit) + "," +
                   std::to_string(e.shadow_texels) + "," + fmt("%.6f", e.max_error) + "," +
                   fmt("%.6f", e.ssim) + "," + (r.front ? "1" : "0") + "," +
                   std::to_string(e.texels) + "," + fmt("%.6f", s.noise.indirect) + "," +
                   radiosity + "," + fmt("%.4f", r.distance_ms) + "," +
                   fmt("%.4f", r.radiosity_ms) + "\n";
        }
    return csv;
}

Result<void> write_plot(const SceneReport& s, const std::string& device, const std::string& path) {
    Figure f;
    f.title = s.name + ": error against frame time on " + device;
    const std::string x_label = "frame time (ms, log scale)";
    f.panels.push_back(
        panel(s, "total light, exposure fitted", x_label, &ErrorMetrics::total_rmse_fit));
    if (!s.runs.empty() && s.runs.front().error.shadow_texels > 0)
        f.panels.push_back(panel(s, "ground without direct light, fitted", x_label,
                                 &ErrorMetrics::shadow_rmse_fit));
    bool gather = false;
    for (const SweepRun& r : s.runs) gather = gather || r.setting.is_gather();
    f.legend = legend(has_radiosity(s), gather);
    return write_figure_png(f, path);
}

} // namespace lantern::bench

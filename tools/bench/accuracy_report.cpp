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

std::vector<std::size_t> front_of(const std::vector<SweepRun>& runs, double ErrorMetrics::*metric) {
    std::vector<double> x, y;
    for (const SweepRun& r : runs) x.push_back(r.total_ms), y.push_back(r.error.*metric);
    return pareto_front(x, y);
}

Panel panel(const SceneReport& s, const char* title, const std::string& x_label,
            double ErrorMetrics::*metric) {
    Panel p{title, x_label, "relative RMSE", true, {}};
    for (const SweepRun& r : s.runs) {
        PlotPoint pt;
        pt.x = r.total_ms;
        pt.y = r.error.*metric;
        pt.color = resolution_color(r.setting.resolution);
        pt.marker = scale_marker(r.setting.scale);
        if (!r.setting.variant().empty()) {
            pt.marker = Marker::diamond;
            pt.hollow = true;
            pt.tag = r.setting.variant();
        }
        p.points.push_back(pt);
    }
    for (std::size_t i : front_of(s.runs, metric)) {
        PlotPoint& pt = p.points[i];
        pt.front = true;
        pt.tag =
            (pt.tag.empty() ? "" : pt.tag + " ") + std::to_string(s.runs[i].setting.rounds) + "r";
    }
    return p;
}

std::vector<LegendEntry> legend() {
    return {{"giRes 4", 0x1F77B4},
            {"giRes 8", 0x2CA02C},
            {"giRes 16", 0xD62728},
            {"full", 0x000000, Marker::circle},
            {"half", 0x000000, Marker::square},
            {"quarter", 0x000000, Marker::triangle},
            {"H: no rings, P: physical, B: no blur", 0x000000, Marker::diamond, true},
            {"Pareto front (rounds)", 0x303030, Marker::circle, false, true}};
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
    for (const SweepRun& r : s.runs) md += table_row(r);
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
        for (std::size_t i : front_of(s.runs, &ErrorMetrics::total_rmse_fit))
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
          "rRMSE).\n";
    for (const std::string& note : c.notes) md += "\nNote: " + note + "\n";
    for (const SceneReport& s : scenes) md += scene_section(s);
    return md;
}

std::string csv_report(const std::vector<SceneReport>& scenes) {
    std::string csv =
        "scene,gi_resolution,heat_scale,heat_rounds,taps,diffusion,blur,total_ms,direct_ms,heat_ms,"
        "blur_ms,"
        "total_rmse,total_rmse_fit,total_scale,indirect_rmse,indirect_rmse_fit,indirect_scale,"
        "shadow_rmse_fit,shadow_texels,max_error,ssim,pareto,texels,reference_rel_se_indirect\n";
    for (const SceneReport& s : scenes)
        for (const SweepRun& r : s.runs) {
            const ErrorMetrics& e = r.error;
            csv += s.name + "," + std::to_string(r.setting.resolution) + "," +
                   scale_name(r.setting.scale) + "," + std::to_string(r.setting.rounds) + "," +
                   r.setting.taps() + "," + (r.setting.per_channel ? "per-channel" : "physical") +
                   "," + (r.setting.blur ? "on" : "off") + "," + fmt("%.4f", r.total_ms) + "," +
                   fmt("%.4f", r.direct_ms) + "," + fmt("%.4f", r.heat_ms) + "," +
                   fmt("%.4f", r.blur_ms) + "," + fmt("%.6f", e.total_rmse) + "," +
                   fmt("%.6f", e.total_rmse_fit) + "," + fmt("%.6f", e.total_scale) + "," +
                   fmt("%.6f", e.indirect_rmse) + "," + fmt("%.6f", e.indirect_rmse_fit) + "," +
                   fmt("%.6f", e.indirect_scale) + "," + fmt("%.6f", e.shadow_rmse_fit) + "," +
                   std::to_string(e.shadow_texels) + "," + fmt("%.6f", e.max_error) + "," +
                   fmt("%.6f", e.ssim) + "," + (r.front ? "1" : "0") + "," +
                   std::to_string(e.texels) + "," + fmt("%.6f", s.noise.indirect) + "\n";
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
    f.legend = legend();
    return write_figure_png(f, path);
}

} // namespace lantern::bench

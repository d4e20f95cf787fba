// lantern-bench seed-table: seed 000's performance table on the current device, each pass
// next to a copy kernel writing the same bytes in the same dispatches, and next to the
// scalar C++ reference (single thread).
#include "bench.hpp"
#include "seed_scene.hpp"

#include "lantern/core/clock.hpp"
#include "lantern/core/file.hpp"
#include "lantern/core/machine.hpp"
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/vulkan/renderer.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace lantern::bench {
namespace {

struct PassNumbers {
    double gpu_ms = 0.0, copy_ms = 0.0, cpp_ms = 0.0;
    bool ran = false;
};

struct RowResult {
    SeedRow row;
    int width = 0, height = 0;
    std::map<gi::Pass, PassNumbers> passes;  // with gi.shadow_method = shadow_map (the default)
    std::map<gi::Pass, std::vector<std::pair<std::string, double>>> parts; // timed parts, median ms
    PassNumbers direct_by_dda;               // the direct pass with gi.shadow_method = dda
    double total_gpu = 0.0, total_copy = 0.0, total_cpp = 0.0;
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

Result<RowResult> run_row(gi::vk::Renderer& renderer, const SeedRow& row, const SeedTableOptions& o) {
    const scene::Scene s = seed_scene(row);
    std::string why;
    auto window = gi::compute_window(s.view, s.gi, &why);
    if (!window) return make_error("seed scene has no GI window: " + why, 1);
    gi::FrameInputs in = gi::gather_frame_inputs(s, *window);
    in.settings.shadow_method = scene::ShadowMethod::shadow_map;
    gi::FrameInputs by_dda = in;
    by_dda.settings.shadow_method = scene::ShadowMethod::dda;
    const gi::PassPlan plan = gi::plan_passes(in, false);
    RowResult r{row, window->width, window->height, {}, {}, {}, 0, 0, 0};
    std::map<gi::Pass, std::vector<double>> samples;
    std::map<std::pair<gi::Pass, std::string>, std::vector<double>> part_samples;
    std::vector<double> dda_samples;
    // The two shadow methods alternate frame by frame, so that both see the same machine.
    for (int rep = 0; rep <= o.repeats; ++rep) { // rep 0 warms up (pipeline creation)
        auto frame = gi::run_vulkan_frame(renderer, in, plan, false);
        if (!frame) return frame.error();
        auto dda = gi::run_vulkan_frame(renderer, by_dda, plan, false);
        if (!dda) return dda.error();
        if (rep == 0) continue;
        for (const gi::PassReport& p : frame->passes) {
            if (p.ran) samples[p.pass].push_back(p.gpu_ms);
            for (const gi::PartReport& part : p.parts) part_samples[{p.pass, part.name}].push_back(part.gpu_ms);
        }
        for (const gi::PassReport& p : dda->passes)
            if (p.ran && p.pass == gi::Pass::direct) dda_samples.push_back(p.gpu_ms);
    }
    for (auto& [key, v] : part_samples) r.parts[key.first].push_back({key.second, median(v)});
    r.direct_by_dda.ran = !dda_samples.empty();
    r.direct_by_dda.gpu_ms = median(dda_samples);
    for (auto& [pass, v] : samples) {
        PassNumbers& n = r.passes[pass];
        n.ran = true;
        n.gpu_ms = median(v);
        n.copy_ms = renderer.time_copy_dispatches(gi::vk::Renderer::pass_bytes_written(pass, in), o.repeats);
        r.total_gpu += n.gpu_ms;
        r.total_copy += n.copy_ms;
    }
    if (o.reference) {
        const gi::FrameResult ref = gi::run_reference_frame(in, plan); // single-threaded
        for (const gi::PassReport& p : ref.passes)
            if (p.ran) {
                r.passes[p.pass].cpp_ms = p.gpu_ms;
                r.total_cpp += p.gpu_ms;
            }
        const gi::PassPlan direct_only = gi::plan_passes(by_dda, false, gi::Pass::direct);
        for (const gi::PassReport& p : gi::run_reference_frame(by_dda, direct_only).passes)
            if (p.ran && p.pass == gi::Pass::direct) r.direct_by_dda.cpp_ms = p.gpu_ms;
    }
    return r;
}

std::string fmt(const char* f, double v) {
    char b[64];
    std::snprintf(b, sizeof(b), f, v);
    return b;
}

void print_row(const RowResult& r, bool reference) {
    std::printf("\n%s: %d x %d texels\n", r.row.label().c_str(), r.width, r.height);
    std::printf("  %-14s %10s %10s %8s%s\n", "pass", "gpu ms", "copy ms", "x copy", reference ? "     C++ ms  C++/gpu" : "");
    for (const auto& [pass, n] : r.passes) {
        if (!n.ran) continue;
        std::printf("  %-14s %10.3f %10.3f %8.2f", gi::pass_name(pass), n.gpu_ms, n.copy_ms,
                    n.copy_ms > 0 ? n.gpu_ms / n.copy_ms : 0.0);
        if (reference) std::printf(" %10.2f %8.1f", n.cpp_ms, n.gpu_ms > 0 ? n.cpp_ms / n.gpu_ms : 0.0);
        std::printf("\n");
        if (auto parts = r.parts.find(pass); parts != r.parts.end())
            for (const auto& [name, ms] : parts->second) // within the pass's time above
                std::printf("    %-12s %10.3f\n", ("- " + name).c_str(), ms);
    }
    if (r.direct_by_dda.ran) {
        const PassNumbers& d = r.direct_by_dda;
        const double map_ms = r.passes.at(gi::Pass::direct).gpu_ms, map_cpp = r.passes.at(gi::Pass::direct).cpp_ms;
        std::printf("  %-14s %10.3f %10s %8s", "direct by DDA", d.gpu_ms, "", "");
        if (reference) std::printf(" %10.2f %8.1f", d.cpp_ms, d.gpu_ms > 0 ? d.cpp_ms / d.gpu_ms : 0.0);
        std::printf("\n  map speed-up: %.1fx on the device", map_ms > 0 ? d.gpu_ms / map_ms : 0.0);
        if (reference) std::printf(", %.1fx in C++", map_cpp > 0 ? d.cpp_ms / map_cpp : 0.0);
        std::printf("\n");
    }
    std::printf("  %-14s %10.3f %10.3f %8.2f", "total", r.total_gpu, r.total_copy,
                r.total_copy > 0 ? r.total_gpu / r.total_copy : 0.0);
    if (reference) std::printf(" %10.2f %8.1f", r.total_cpp, r.total_gpu > 0 ? r.total_cpp / r.total_gpu : 0.0);
    std::printf("\n");
    std::fflush(stdout);
}

std::string markdown(const std::vector<RowResult>& rows, const std::string& device, bool reference) {
    std::string md = "Device: " + device + "\nMachine: " + describe_machine() + "\n\n";
    md += "| giRes | Heat Spread Res | Point | Emissive | Directional | DDA | DDA by DDA | map speed-up | DDA_Directional | HeatSpread | Blur | "
          "Total (ms) | DDA x copy | Dir x copy | Heat x copy | Blur x copy | Cond x copy | AO x copy | "
          "Emission x copy | WallInd x copy |";
    md += reference ? " C++ total (ms) | C++ DDA | C++ DDA by DDA |\n" : "\n";
    md += "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|";
    md += reference ? "---|---|---|\n" : "\n";
    auto get = [](const RowResult& r, gi::Pass p) {
        auto it = r.passes.find(p);
        return it == r.passes.end() ? PassNumbers{} : it->second;
    };
    for (const RowResult& r : rows) {
        auto ratio = [&](gi::Pass p) {
            PassNumbers n = get(r, p);
            return n.ran && n.copy_ms > 0 ? fmt("%.2f", n.gpu_ms / n.copy_ms) : std::string("-");
        };
        auto ms = [&](gi::Pass p) {
            PassNumbers n = get(r, p);
            return n.ran ? fmt("%.2f", n.gpu_ms) : std::string("-");
        };
        const char* scale = r.row.scale == scene::HeatScale::full ? "full" : r.row.scale == scene::HeatScale::half ? "half" : "quarter";
        md += "| " + std::to_string(r.row.resolution) + " | " + scale + " | " + std::to_string(r.row.points) + " | " +
              std::to_string(r.row.emissives) + " | " + std::to_string(r.row.directionals) + " | " + ms(gi::Pass::direct) +
              " | " + (r.direct_by_dda.ran ? fmt("%.2f", r.direct_by_dda.gpu_ms) : std::string("-")) + " | " +
              (r.direct_by_dda.ran && get(r, gi::Pass::direct).gpu_ms > 0
                   ? fmt("%.1fx", r.direct_by_dda.gpu_ms / get(r, gi::Pass::direct).gpu_ms)
                   : std::string("-")) +
              " | " + ms(gi::Pass::directional) + " | " + ms(gi::Pass::heat) + " | " + ms(gi::Pass::blur) + " | " +
              fmt("%.2f", r.total_gpu) + " | " + ratio(gi::Pass::direct) + " | " + ratio(gi::Pass::directional) + " | " +
              ratio(gi::Pass::heat) + " | " + ratio(gi::Pass::blur) + " | " + ratio(gi::Pass::conduction) + " | " +
              ratio(gi::Pass::ao) + " | " + ratio(gi::Pass::emission) + " | " + ratio(gi::Pass::wall_indirect) + " |";
        md += reference ? " " + fmt("%.1f", r.total_cpp) + " | " + fmt("%.1f", get(r, gi::Pass::direct).cpp_ms) + " | " +
                              fmt("%.1f", r.direct_by_dda.cpp_ms) + " |\n"
                        : "\n";
    }
    return md;
}

// The cost of one more point light: the slope between rows that differ only in their count
// of point lights (the many-light rows), for each method.
std::string light_slopes(const std::vector<RowResult>& rows) {
    // b has more point lights than a and is otherwise the same row.
    auto more_lights = [](const SeedRow& a, const SeedRow& b) {
        return a.resolution == b.resolution && a.scale == b.scale && a.emissives == b.emissives &&
               a.directionals == b.directionals && a.method == b.method && b.points > a.points;
    };
    std::string out;
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t j = i + 1; j < rows.size(); ++j) {
            const SeedRow &a = rows[i].row, &b = rows[j].row;
            if (!more_lights(a, b)) continue;
            // Only the nearest larger count, so each step is reported once.
            bool nearer = false;
            for (std::size_t k = i + 1; k < j; ++k) nearer |= more_lights(a, rows[k].row) && more_lights(rows[k].row, b);
            if (nearer) continue;
            const double n = double(b.points - a.points);
            auto slope = [&](double x, double y) { return fmt("%.3f", (y - x) / n); };
            const auto &da = rows[i].passes.at(gi::Pass::direct), &db = rows[j].passes.at(gi::Pass::direct);
            // The machine's speed drifts between rows (the copy kernel with it): the slope of
            // "x copy" is the steadier figure.
            auto per_copy = [](const PassNumbers& x) { return x.copy_ms > 0 ? x.gpu_ms / x.copy_ms : 0.0; };
            out += "| " + std::to_string(a.resolution) + " | " + std::to_string(a.points) + " -> " +
                   std::to_string(b.points) + " | " + slope(da.gpu_ms, db.gpu_ms) + " | " +
                   slope(per_copy(da), per_copy(db)) + " | " +
                   slope(rows[i].direct_by_dda.gpu_ms, rows[j].direct_by_dda.gpu_ms) + " | " +
                   slope(rows[i].total_gpu, rows[j].total_gpu) + " |";
            out += da.cpp_ms > 0 ? " " + slope(da.cpp_ms, db.cpp_ms) + " |\n" : " - |\n";
        }
    if (out.empty()) return out;
    return "\nCost of one more point light in view (ms per light, slope between rows):\n\n"
           "| giRes | point lights | direct | direct x copy | direct by DDA | total | C++ direct |\n"
           "|---|---|---|---|---|---|---|\n" +
           out;
}

// A row's numbers for `p` (zeros when the pass did not run), and "ms (x copy)" or "-".
PassNumbers get(const RowResult& r, gi::Pass p) {
    auto it = r.passes.find(p);
    return it == r.passes.end() ? PassNumbers{} : it->second;
}
std::string cell(const RowResult& r, gi::Pass p) {
    const PassNumbers n = get(r, p);
    return n.ran ? fmt("%.2f", n.gpu_ms) + " (" + (n.copy_ms > 0 ? fmt("%.1f", n.gpu_ms / n.copy_ms) : "-") + ")"
                 : std::string("-");
}

// Seed 003's radiosity beside seed 000's heat on the same row (resolution, scale, lights):
// the indirect passes each method runs instead of the other's, in ms and x copy.
std::string methods_table(const std::vector<RowResult>& rows) {
    std::string out;
    for (const RowResult& rad : rows) {
        if (rad.row.method != scene::GiMethod::radiosity) continue;
        for (const RowResult& heat : rows) {
            const SeedRow &a = heat.row, &b = rad.row;
            if (a.method != scene::GiMethod::heat || a.resolution != b.resolution || a.scale != b.scale ||
                a.points != b.points || a.emissives != b.emissives || a.directionals != b.directionals)
                continue;
            const char* scale = b.scale == scene::HeatScale::full ? "full" : b.scale == scene::HeatScale::half ? "half" : "quarter";
            const double heat_ms = get(heat, gi::Pass::heat).gpu_ms;
            const double rad_ms = get(rad, gi::Pass::distance_field).gpu_ms + get(rad, gi::Pass::radiosity).gpu_ms;
            out += "| " + std::to_string(b.resolution) + " | " + scale + " | " + cell(heat, gi::Pass::heat) + " | " +
                   cell(rad, gi::Pass::distance_field) + " | " + cell(rad, gi::Pass::radiosity) + " | " +
                   (heat_ms > 0 ? fmt("%.2f", rad_ms / heat_ms) : std::string("-")) + " | " +
                   fmt("%.2f", heat.total_gpu) + " | " + fmt("%.2f", rad.total_gpu) + " | " +
                   (get(rad, gi::Pass::radiosity).cpp_ms > 0 ? fmt("%.1f", get(rad, gi::Pass::radiosity).cpp_ms)
                                                              : std::string("-")) +
                   " |\n";
        }
    }
    if (out.empty()) return out;
    return "\nSeed 003's radiosity beside seed 000's heat (ms, x copy in brackets; radiosity: 16 rays, 32 steps, its "
           "grid at the row's scale; the distance field reruns only when walls or the window change):\n\n"
           "| giRes | scale | heat | distance field | radiosity | (field + radiosity) / heat | total, heat | "
           "total, radiosity | C++ radiosity |\n"
           "|---|---|---|---|---|---|---|---|---|\n" +
           out;
}

// The gather method (physical) on the same scene and lights: its pass, the direct pass it
// runs over a window `gather.margin` tiles wider, heat at the same resolution and scale for
// scale, and the cost of one more face bounce (rows differing only in gather.bounces).
std::string gather_table(const std::vector<RowResult>& rows) {
    std::string out;
    const RowResult* previous = nullptr;
    for (const RowResult& g : rows) {
        if (g.row.method != scene::GiMethod::gather) continue;
        const char* scale = g.row.scale == scene::HeatScale::full ? "full" : g.row.scale == scene::HeatScale::half ? "half" : "quarter";
        const RowResult* heat = nullptr;
        for (const RowResult& h : rows)
            if (h.row.method == scene::GiMethod::heat && h.row.resolution == g.row.resolution &&
                h.row.scale == g.row.scale && h.row.points == g.row.points && h.row.emissives == g.row.emissives &&
                h.row.directionals == g.row.directionals)
                heat = &h;
        std::string per_bounce = "-";
        if (previous && previous->row.scale == g.row.scale && previous->row.resolution == g.row.resolution &&
            previous->row.bounces + 1 == g.row.bounces)
            per_bounce = fmt("%.2f", get(g, gi::Pass::gather).gpu_ms - get(*previous, gi::Pass::gather).gpu_ms);
        out += "| " + std::to_string(g.row.resolution) + " | " + scale + " | " + std::to_string(g.row.bounces) + " | " +
               cell(g, gi::Pass::gather) + " | " + per_bounce + " | " + cell(g, gi::Pass::direct) + " | " +
               (heat ? cell(*heat, gi::Pass::heat) : std::string("-")) + " | " + fmt("%.2f", g.total_gpu) + " | " +
               (get(g, gi::Pass::gather).cpp_ms > 0 ? fmt("%.1f", get(g, gi::Pass::gather).cpp_ms) : std::string("-")) +
               " |\n";
        previous = &g;
    }
    if (out.empty()) return out;
    return "\nThe gather method (physical) beside heat (ms, x copy in brackets; 32 ground and 32 face rays, its "
           "grid at the row's scale, margin 4 tiles: every pass runs over the wider window; + bounce: the "
           "gather's ms over the row above, one face bounce less):\n\n"
           "| giRes | scale | bounces | gather | + bounce | direct | heat (same row) | total, gather | C++ gather |\n"
           "|---|---|---|---|---|---|---|---|---|\n" +
           out;
}

} // namespace

int seed_table(const SeedTableOptions& o) {
    auto device = gpu::Device::create();
    if (!device) {
        std::fprintf(stderr, "lantern-bench: %s\n", device.error().message.c_str());
        return 1;
    }
    gi::vk::RendererOptions ro;
    ro.block_h = o.block_h;
    ro.group_x = o.group_x;
    ro.group_y = o.group_y;
    if (o.proxy_list_kib >= 0) ro.proxy_list_bytes = std::uint64_t(o.proxy_list_kib) * 1024u;
    auto renderer = gi::vk::Renderer::create(**device, ro);
    if (!renderer) {
        std::fprintf(stderr, "lantern-bench: %s\n", renderer.error().message.c_str());
        return 1;
    }
    std::printf("lantern-bench seed-table\ndevice: %s\nmachine: %s\nmedian of %d frames per pass after a warm-up; "
                "copy = the copy kernel writing the same bytes in the same dispatches%s\n",
                (*device)->name().c_str(), describe_machine().c_str(), o.repeats,
                o.reference ? "; C++ = the scalar reference, one thread" : "");
    std::printf("block: 4 x %u texels per invocation, workgroup %u x %u blocks; proxy lists within %llu KiB\n",
                (*renderer)->block_h(), (*renderer)->group_x(), (*renderer)->group_y(),
                static_cast<unsigned long long>(ro.proxy_list_bytes / 1024u));
    std::vector<RowResult> rows;
    const auto all = seed_rows();
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (!o.rows.empty() && std::find(o.rows.begin(), o.rows.end(), int(i)) == o.rows.end()) continue;
        std::fprintf(stderr, "lantern-bench: row %zu/%zu: %s ...\n", i + 1, all.size(), all[i].label().c_str());
        auto r = run_row(**renderer, all[i], o);
        if (!r) {
            std::fprintf(stderr, "lantern-bench: %s\n", r.error().message.c_str());
            return 1;
        }
        print_row(*r, o.reference);
        rows.push_back(std::move(r.value()));
    }
    const std::string md = markdown(rows, (*device)->name(), o.reference) + light_slopes(rows) + methods_table(rows) + gather_table(rows);
    std::printf("\n%s", md.c_str());
    if (!o.markdown_out.empty()) {
        if (auto ok = write_file_atomic(o.markdown_out, md); !ok) {
            std::fprintf(stderr, "lantern-bench: %s\n", ok.error().message.c_str());
            return 1;
        }
    }
    return 0;
}

} // namespace lantern::bench

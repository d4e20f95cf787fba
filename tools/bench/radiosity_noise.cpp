// lantern-bench radiosity-noise: how the radiosity method's noise behaves over frames, for
// each of the seed's remedies (issue 16): more rays, the denoiser (the blur row), smarter
// noise (the blue-noise shift: rotate, golden, off) and temporal accumulation.
//
// A still scene runs `frames` frames per configuration on the Vulkan device (history
// counting as in the game, so feedback adds a bounce per frame and accumulation averages).
// Over the last half of the frames, per air texel of the indirect light (luminance):
//   temporal noise  the mean over texels of the standard deviation over frames, over the
//                   mean indirect luminance (what a player sees as flicker)
//   error           the RMSE of the last frame against the truth (64 rays, no blur, the mean
//                   of its frames 32 to 63, when the bounces have converged), over its mean:
//                   noise, banding and the denoiser's blurring together
//   flat steps      among neighbouring texel pairs whose truth differs by at least one
//                   8-bit step of the tone-mapped indirect light, the share the image shows
//                   equal: the plateaus (colour banding) a denoiser adds
#include "bench.hpp"
#include "seed_scene.hpp"

#include "lantern/core/machine.hpp"
#include "lantern/gi/frame_runner.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/vulkan/renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace lantern::bench {
namespace {

struct Config {
    scene::NoiseShift noise = scene::NoiseShift::rotate;
    int rays = 16;
    int accumulate = 1;
    bool blur = false;
    std::string label() const {
        const char* n = noise == scene::NoiseShift::rotate ? "rotate" : noise == scene::NoiseShift::golden ? "golden" : "off";
        return std::string(n) + ", " + std::to_string(rays) + " rays, accumulate " + std::to_string(accumulate) +
               (blur ? ", blur" : "");
    }
};

struct Series {
    std::vector<std::vector<float>> frames; // luminance of the indirect light per texel, per frame kept
    std::vector<bool> air;
    int width = 0, height = 0;
};

float luminance(const float* v) { return 0.2126f * v[0] + 0.7152f * v[1] + 0.0722f * v[2]; }

Result<Series> run(gi::vk::Renderer& renderer, const scene::Scene& base, const Config& c, int frames) {
    scene::Scene s = base;
    s.gi.radiosity.noise = c.noise;
    s.gi.radiosity.rays = c.rays;
    s.gi.radiosity.accumulate = c.accumulate;
    s.gi.radiosity.frames = 4096; // never settles within the run
    s.gi.blur = c.blur;
    std::string why;
    auto window = gi::compute_window(s.view, s.gi, &why);
    if (!window) return make_error("no GI window: " + why, 1);
    const gi::FrameInputs in = gi::gather_frame_inputs(s, *window);
    gi::Convergence convergence;
    Series out;
    for (int f = 0; f < frames; ++f) {
        gi::PassPlan plan = gi::plan_passes(in, false);
        gi::derive_keys(in, plan, gi::input_keys_of(in), &convergence);
        const bool keep = f >= frames / 2;
        auto frame = gi::run_vulkan_frame(renderer, in, plan, keep);
        if (!frame) return frame.error();
        convergence.advance(plan.run);
        if (!keep) continue;
        const gi::Texture& t = frame->textures.at("indirect");
        out.width = t.width, out.height = t.height;
        if (out.air.empty()) {
            out.air.resize(std::size_t(t.width) * std::size_t(t.height));
            for (int y = 0; y < t.height; ++y)
                for (int x = 0; x < t.width; ++x) {
                    const glm::vec2 p = in.window.texel_center(x, y);
                    out.air[std::size_t(y * t.width + x)] = !in.walls.is_wall(int(std::floor(p.x)), int(std::floor(p.y)));
                }
        }
        std::vector<float> lum(out.air.size());
        for (int y = 0; y < t.height; ++y)
            for (int x = 0; x < t.width; ++x) lum[std::size_t(y * t.width + x)] = luminance(t.at(x, y));
        out.frames.push_back(std::move(lum));
    }
    return out;
}

std::vector<float> mean_image(const Series& s) {
    std::vector<float> m(s.air.size(), 0.0f);
    for (const auto& f : s.frames)
        for (std::size_t i = 0; i < m.size(); ++i) m[i] += f[i] / float(s.frames.size());
    return m;
}

// The 8-bit level of a luminance after a Reinhard curve (what the eye compares).
int level(float v) { return int(std::floor(255.0f * v / (1.0f + v) + 0.5f)); }

struct Numbers {
    double temporal = 0, error = 0, flat = 0;
};

Numbers measure(const Series& s, const std::vector<float>& truth) {
    const std::vector<float> mean = mean_image(s);
    double sum_sd = 0, sum_mean = 0, sum_err2 = 0, sum_truth = 0;
    std::size_t n = 0, steps = 0, flat = 0;
    const std::vector<float>& last = s.frames.back();
    for (std::size_t i = 0; i < s.air.size(); ++i) {
        if (!s.air[i]) continue;
        double var = 0;
        for (const auto& f : s.frames) var += (f[i] - mean[i]) * (f[i] - mean[i]);
        sum_sd += std::sqrt(var / double(s.frames.size()));
        sum_mean += mean[i];
        sum_err2 += (last[i] - truth[i]) * (last[i] - truth[i]);
        sum_truth += truth[i];
        ++n;
    }
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x + 1 < s.width; ++x) {
            const std::size_t a = std::size_t(y * s.width + x), b = a + 1;
            if (!s.air[a] || !s.air[b] || level(truth[a]) == level(truth[b])) continue;
            ++steps;
            flat += level(last[a]) == level(last[b]);
        }
    Numbers out;
    const double mean_lum = n ? sum_mean / double(n) : 0.0, truth_lum = n ? sum_truth / double(n) : 0.0;
    out.temporal = mean_lum > 0 ? sum_sd / double(n) / mean_lum : 0.0;
    out.error = truth_lum > 0 ? std::sqrt(sum_err2 / double(n)) / truth_lum : 0.0;
    out.flat = steps ? double(flat) / double(steps) : 0.0;
    return out;
}

} // namespace

int radiosity_noise(const RadiosityNoiseOptions& o) {
    auto device = gpu::Device::create();
    if (!device) {
        std::fprintf(stderr, "lantern-bench: %s\n", device.error().message.c_str());
        return 1;
    }
    auto renderer = gi::vk::Renderer::create(**device);
    if (!renderer) {
        std::fprintf(stderr, "lantern-bench: %s\n", renderer.error().message.c_str());
        return 1;
    }
    const SeedRow row{o.resolution, scene::HeatScale::quarter, o.lights, 0, 0, scene::GiMethod::radiosity};
    const scene::Scene scene = seed_scene(row);
    std::printf("lantern-bench radiosity-noise\ndevice: %s\nmachine: %s\nscene: %s, radiosity grid quarter, "
                "feedback %.2f, %d frames per configuration (the last %d measured)\n",
                (*device)->name().c_str(), describe_machine().c_str(), row.label().c_str(),
                double(scene.gi.radiosity.feedback), o.frames, o.frames - o.frames / 2);
    std::fprintf(stderr, "lantern-bench: the truth (64 rays, the mean of 32 frames after 32) ...\n");
    auto truth_series = run(**renderer, scene, {scene::NoiseShift::rotate, 64, 1, false}, std::max(o.frames, 64));
    if (!truth_series) {
        std::fprintf(stderr, "lantern-bench: %s\n", truth_series.error().message.c_str());
        return 1;
    }
    const std::vector<float> truth = mean_image(*truth_series);
    std::vector<Config> configs;
    for (scene::NoiseShift noise : {scene::NoiseShift::rotate, scene::NoiseShift::golden, scene::NoiseShift::off})
        for (int accumulate : {1, 8})
            for (bool blur : {false, true}) configs.push_back({noise, 16, accumulate, blur});
    for (int rays : {4, 64}) configs.push_back({scene::NoiseShift::rotate, rays, 1, false});
    std::string md = "| noise | rays | accumulate | blur | temporal noise | error against the truth | flat steps |\n"
                     "|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < configs.size(); ++i) {
        const Config& c = configs[i];
        std::fprintf(stderr, "lantern-bench: %zu/%zu: %s ...\n", i + 1, configs.size(), c.label().c_str());
        auto s = run(**renderer, scene, c, o.frames);
        if (!s) {
            std::fprintf(stderr, "lantern-bench: %s\n", s.error().message.c_str());
            return 1;
        }
        const Numbers n = measure(*s, truth);
        const char* noise = c.noise == scene::NoiseShift::rotate ? "rotate" : c.noise == scene::NoiseShift::golden ? "golden" : "off";
        char line[256];
        std::snprintf(line, sizeof(line), "| %s | %d | %d | %s | %.1f %% | %.1f %% | %.1f %% |\n", noise, c.rays,
                      c.accumulate, c.blur ? "on" : "off", 100.0 * n.temporal, 100.0 * n.error, 100.0 * n.flat);
        md += line;
    }
    std::printf("\n%s", md.c_str());
    return 0;
}

} // namespace lantern::bench

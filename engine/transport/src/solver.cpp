// The reference solve: exact direct terms, then batches of light tracing until the
// indirect fluence's relative standard error reaches the target.
#include "lantern/transport/solver.hpp"

#include "emitters.hpp"
#include "problem.hpp"
#include "tracer.hpp"

#include "lantern/core/clock.hpp"
#include "lantern/core/hash.hpp"
#include "lantern/core/log.hpp"
#include "lantern/jobs/job_system.hpp"
#include "lantern/transport/cache.hpp"
#include "lantern/transport/model.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

namespace lantern::transport {
namespace {

// Photons per chunk: the unit of parallel work and of random streams. Part of the results'
// definition (changing it changes them: bump transport_code_version).
constexpr std::uint32_t chunk_photons = 1024;

template <typename F>
void for_each_row(jobs::JobSystem* jobs, int rows, F&& row) {
    if (!jobs) {
        for (int y = 0; y < rows; ++y) row(y);
        return;
    }
    jobs->parallel_for("transport.rows", 0, std::uint32_t(rows), 4,
                       [&](std::uint32_t b, std::uint32_t e, std::uint32_t) {
                           for (std::uint32_t y = b; y < e; ++y) row(int(y));
                       });
}

glm::ivec2 window_min_tile(const gi::GiWindow& w) {
    return {int(std::floor(w.view.min_x)), int(std::floor(w.view.min_z))};
}

RgbField solve_direct(const Problem& p, jobs::JobSystem* jobs) {
    const gi::GiWindow& w = p.window;
    RgbField out(w.width, w.height);
    for_each_row(jobs, w.height, [&](int y) {
        for (int x = 0; x < w.width; ++x)
            if (!p.domain.is_wall(glm::ivec2(x, y) + p.domain.offset))
                out.set(x, y, direct_fluence(p.inputs, w.texel_center(x, y)));
    });
    return out;
}

// Direct irradiance at the midpoint of every exposed face segment of the window.
FaceField solve_face_direct(const Problem& p, const FaceLayout& layout, jobs::JobSystem* jobs) {
    FaceField out(layout);
    const glm::ivec2 origin = window_min_tile(p.window);
    const int res = layout.resolution;
    auto segment = [&](FaceRef f, int i, int j, int along) {
        if (face_exposed(p.inputs.walls, f))
            out.set(f.face, i, j,
                    direct_face_irradiance(p.inputs, f,
                                           face_point(f, (float(along) + 0.5f) / float(res))));
    };
    // +-X faces: one segment per tile column and texel row; +-Z: per tile row and texel column.
    for_each_row(jobs, layout.height, [&](int j) {
        for (int tx = 0; tx < layout.tiles_x(); ++tx)
            for (int face : {gi::face_pos_x, gi::face_neg_x})
                segment({origin + glm::ivec2(tx, j / res), face}, tx * res, j, j % res);
    });
    for_each_row(jobs, layout.tiles_z(), [&](int tz) {
        for (int i = 0; i < layout.width; ++i)
            for (int face : {gi::face_pos_z, gi::face_neg_z})
                segment({origin + glm::ivec2(i / res, tz), face}, i, tz * res, i % res);
    });
    return out;
}

// Running mean and sum of squared deviations (Welford) of the batch means, per value.
struct BatchMoments {
    int batches = 0;
    std::vector<double> mean, m2;

    explicit BatchMoments(std::size_t n) : mean(n, 0.0), m2(n, 0.0) {}
    void add(const std::vector<double>& x) {
        ++batches;
        for (std::size_t i = 0; i < x.size(); ++i) {
            const double delta = x[i] - mean[i];
            mean[i] += delta / double(batches);
            m2[i] += delta * (x[i] - mean[i]);
        }
    }
    double variance_of_mean(std::size_t i) const {
        return batches > 1 ? m2[i] / (double(batches) * double(batches - 1)) : 0.0;
    }
};

// sqrt(sum SE^2) / sqrt(sum mean^2) over the window's air texels (the first values).
double relative_error(const BatchMoments& m, const Domain& d) {
    double se2 = 0.0, sq = 0.0;
    for (int y = 0; y < d.window_height; ++y)
        for (int x = 0; x < d.window_width; ++x) {
            if (d.is_wall(glm::ivec2(x, y) + d.offset)) continue;
            const std::size_t i =
                (std::size_t(y) * std::size_t(d.window_width) + std::size_t(x)) * 3;
            for (std::size_t c = i; c < i + 3; ++c) {
                se2 += m.variance_of_mean(c);
                sq += m.mean[c] * m.mean[c];
            }
        }
    return sq > 0.0 ? std::sqrt(se2 / sq) : 0.0;
}

std::uint64_t chunk_stream(std::uint64_t seed, int batch, std::uint32_t chunk) {
    return Hasher(seed).add(batch).add(chunk).value();
}

// Runs one batch over every worker's tally and returns the merged batch means (ground
// values first, then faces), in light units.
std::vector<double> run_batch(const Problem& p, const EmitterTable& emitters,
                              const FaceLayout& layout, const TraceParams& params,
                              const TransportSettings& s, int batch, jobs::JobSystem* jobs,
                              std::vector<Tally>& tallies) {
    const std::size_t ground = std::size_t(p.window.width) * std::size_t(p.window.height) * 3;
    const std::size_t faces = layout.segments() * 3;
    for (Tally& t : tallies) t.reset(ground, faces);
    const std::uint32_t chunks = s.photons_per_batch / chunk_photons;
    auto run = [&](std::uint32_t chunk, std::uint32_t worker) {
        trace_photons(p, emitters, layout, params, chunk_stream(s.seed, batch, chunk),
                      chunk_photons, tallies[worker]);
    };
    if (jobs)
        jobs->parallel_for("transport.batch", 0, chunks, 1,
                           [&](std::uint32_t b, std::uint32_t e, std::uint32_t w) {
                               for (std::uint32_t c = b; c < e; ++c) run(c, w);
                           });
    else
        for (std::uint32_t c = 0; c < chunks; ++c) run(c, 0);
    std::vector<double> means(ground + faces);
    const double to_light = 1.0 / (params.fixed_point * double(s.photons_per_batch));
    for (std::size_t i = 0; i < means.size(); ++i) {
        std::int64_t sum = 0; // exact, whatever the order
        for (const Tally& t : tallies) sum += i < ground ? t.ground[i] : t.faces[i - ground];
        means[i] = double(sum) * to_light;
    }
    return means;
}

SolveProgress progress_of(const BatchMoments& m, double error, const TransportSettings& s,
                          std::int64_t start) {
    SolveProgress pr;
    pr.batch = m.batches;
    pr.max_batches = s.max_batches;
    pr.relative_error = error;
    pr.target = s.target_relative_error;
    pr.photons = std::uint64_t(m.batches) * s.photons_per_batch;
    pr.seconds = double(now_ns() - start) * 1e-9;
    const double needed = m.batches > 1 ? double(m.batches) * (error / s.target_relative_error) *
                                              (error / s.target_relative_error)
                                        : double(s.max_batches);
    pr.fraction = double(m.batches) / std::clamp(needed, double(std::max(s.min_batches, m.batches)),
                                                 double(s.max_batches));
    return pr;
}

void store_indirect(const BatchMoments& m, TransportResult& r) {
    const std::size_t ground = r.indirect.rgb.size();
    for (std::size_t i = 0; i < m.mean.size(); ++i) {
        const float value = float(m.mean[i]), error = float(std::sqrt(m.variance_of_mean(i)));
        if (i < ground) {
            r.indirect.rgb[i] = value;
            r.indirect_error.rgb[i] = error;
        } else {
            r.face_indirect.rgb[i - ground] = value;
            r.face_indirect_error.rgb[i - ground] = error;
        }
    }
}

void solve_indirect(const Problem& p, const TransportSettings& s, const SolveOptions& o,
                    TransportResult& r, std::int64_t start) {
    const EmitterTable emitters = EmitterTable::build(p);
    if (emitters.empty()) { // no light leaves a wall: the indirect is exactly 0
        r.stats.converged = true;
        return;
    }
    const double weight_bound = emitters.total_bound() / double(p.domain.resolution);
    TraceParams params;
    params.max_bounces = s.max_bounces;
    params.roulette_weight = 0.25 * weight_bound;
    params.fixed_point =
        fixed_point_scale(weight_bound, p.domain.resolution, s.max_bounces, s.photons_per_batch);
    std::vector<Tally> tallies(o.jobs ? o.jobs->thread_count() : 1);
    BatchMoments moments(r.indirect.rgb.size() + r.face_indirect.rgb.size());
    double error = 0.0;
    while (moments.batches < s.max_batches) {
        moments.add(run_batch(p, emitters, r.face_indirect.layout, params, s, moments.batches,
                              o.jobs, tallies));
        error = relative_error(moments, p.domain);
        if (o.progress) o.progress(progress_of(moments, error, s, start));
        if (moments.batches >= s.min_batches && error <= s.target_relative_error) break;
    }
    store_indirect(moments, r);
    r.stats.batches = moments.batches;
    r.stats.photons = std::uint64_t(moments.batches) * s.photons_per_batch;
    r.stats.relative_error = error;
    r.stats.converged = error <= s.target_relative_error;
}

// The exact part of a result: the window and the direct terms (no noise, no cache).
TransportResult solve_direct_terms(const Problem& p, jobs::JobSystem* jobs) {
    TransportResult r;
    r.window = p.window;
    const FaceLayout layout{p.window.resolution, p.window.width, p.window.height};
    r.direct = solve_direct(p, jobs);
    r.indirect = r.indirect_error = RgbField(p.window.width, p.window.height);
    r.face_direct = solve_face_direct(p, layout, jobs);
    r.face_indirect = r.face_indirect_error = FaceField(layout);
    return r;
}

// A cached result for this problem, or nothing (missing, unreadable, or stale). The cache
// key cannot see Lantern's direct-light code, which the model reuses, so a cached result
// is only taken when its direct terms equal the ones just computed, bit for bit.
std::optional<TransportResult> load_from_cache(const std::string& path, std::uint64_t key,
                                               const TransportResult& direct) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return std::nullopt;
    auto cached = read_cached(path, key);
    if (!cached) {
        LANTERN_LOG_WARN("ignoring the cached transport result: %s",
                         cached.error().message.c_str());
        return std::nullopt;
    }
    if (cached->window != direct.window || cached->direct != direct.direct ||
        cached->face_direct != direct.face_direct) {
        LANTERN_LOG_WARN("ignoring the cached transport result: %s: its direct light differs "
                         "from the current model's (Lantern's direct term changed?)",
                         path.c_str());
        return std::nullopt;
    }
    cached->stats.from_cache = true;
    return std::move(cached.value());
}

} // namespace

Result<void> validate_settings(const TransportSettings& s) {
    auto bad = [](const char* field, const std::string& what) {
        return make_error(std::string("transport.") + field + ": " + what);
    };
    if (!(s.albedo >= 0.0f && s.albedo <= 1.0f)) return bad("albedo", "must be in [0, 1]");
    if (s.max_bounces < 1 || s.max_bounces > 1024)
        return bad("max_bounces", "must be in [1, 1024]");
    if (s.resolution < 1 || s.resolution > 32) return bad("resolution", "must be in [1, 32]");
    if (s.margin < 0 || s.margin > 256) return bad("margin", "must be in [0, 256]");
    if (!(s.target_relative_error > 0.0 && s.target_relative_error < 1.0))
        return bad("target_relative_error", "must be in (0, 1)");
    if (s.photons_per_batch < chunk_photons || s.photons_per_batch > (1u << 24) ||
        s.photons_per_batch % chunk_photons)
        return bad("photons_per_batch", "must be a multiple of 1024 in [1024, 2^24]");
    if (s.min_batches < 2) return bad("min_batches", "must be at least 2");
    if (s.max_batches < s.min_batches || s.max_batches > 1000000)
        return bad("max_batches", "must be in [min_batches, 10^6]");
    return {};
}

Result<TransportResult> solve_transport(const scene::Scene& scene,
                                        const TransportSettings& settings,
                                        const SolveOptions& options) {
    if (auto ok = validate_settings(settings); !ok) return ok.error();
    auto problem = make_problem(scene, settings);
    if (!problem) return problem.error();
    const std::int64_t start = now_ns();
    TransportResult result = solve_direct_terms(*problem, options.jobs);
    std::string path;
    std::uint64_t key = 0;
    if (!options.cache_dir.empty()) {
        auto k = cache_key(scene, settings);
        if (!k) return k.error();
        key = *k;
        path = cache_path(options.cache_dir, key);
        if (auto cached = load_from_cache(path, key, result)) return std::move(*cached);
    }
    solve_indirect(*problem, settings, options, result, start);
    result.stats.seconds = double(now_ns() - start) * 1e-9;
    if (!path.empty())
        if (auto ok = write_cached(path, key, result); !ok)
            LANTERN_LOG_WARN("transport result not cached: %s", ok.error().message.c_str());
    return result;
}

} // namespace lantern::transport

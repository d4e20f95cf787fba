// Lantern's light-transport reference: a Monte Carlo solution of the physical model of
// model.hpp on a scene's GI window, for measuring how far the real-time GI is from it
// (lantern-bench accuracy, docs/accuracy.md).
//
// What it computes, on the texel grid of Lantern's GI window for the scene's view and
// padding at `settings.resolution` texels per world unit:
// - direct fluence at every air texel centre, exactly (no noise; model.hpp);
// - indirect fluence averaged over every air texel, by light tracing: photons leave the
//   directly lit (or glowing) wall faces (importance-sampled per face segment and source), reflect
//   diffusely off walls until absorbed (albedo, Russian roulette) or `max_bounces`
//   reflections, and deposit power x track length / texel area in every texel they cross
//   (the track-length estimator, unbiased for the texel average);
// - direct and indirect irradiance on every exposed wall face segment in the window.
// Light is traced in a transport domain: the window plus `margin` tiles on each side;
// walls outside it do not reflect and light leaving it is lost. Every source of the scene
// that reaches the domain takes part (Lantern's max_lights and max_shadow_proxies caps do
// not apply to the reference).
//
// Convergence: photons are traced in batches; per-texel standard errors come from the
// spread of the batch means. The solve stops once at least `min_batches` ran and the
// relative standard error of the indirect fluence, sqrt(sum SE^2) / sqrt(sum mean^2) over
// the window's air texels and channels, is at most `target_relative_error` (the noise it
// adds to a relative RMSE measured against it), or after `max_batches`.
//
// Determinism: the result depends only on the scene, the settings (seed included) and the
// code version, never on the number of threads: batches are split into fixed chunks with
// their own random streams and deposits are summed in 64-bit fixed point, which is exact
// and order-independent.
//
// Cache: with a cache folder, results are stored as <folder>/<key>.ltr (cache.hpp) and
// reused by later solves of the same problem. The direct terms are always computed (they
// are exact and cheap); a cached result is used only when its direct terms equal them bit
// for bit, so a change to Lantern's direct-light code, which the model reuses and the key
// cannot see, invalidates it. Unreadable, mismatching or stale files are ignored with a
// warning on stderr and replaced.
//
// Threads: call from a JobSystem's main thread (or without one: then single-threaded).
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gi/window.hpp"
#include "lantern/scene/scene.hpp"
#include "lantern/transport/field.hpp"

#include <cstdint>
#include <functional>
#include <string>

namespace lantern::jobs {
class JobSystem;
}

namespace lantern::transport {

struct TransportSettings {
    float albedo = 0.5f;                 // the default wall's grey reflectance, [0, 1] (materials have their own)
    int max_bounces = 64;                // wall reflections per path, 1..1024 (1: single bounce)
    int resolution = 16;                 // output texels per world unit, 1..32 (as gi.resolution)
    int margin = 8;                      // tiles of transport domain around the window, 0..256
    double target_relative_error = 0.01; // (0, 1)
    // Photons per batch, a multiple of 1024 in [1024, 2^24]. Larger batches give steadier
    // per-texel errors; smaller ones finer stopping. 2^18 suits windows of ~10^5 texels.
    std::uint32_t photons_per_batch = 1u << 18;
    int min_batches = 8;   // >= 2: the spread of fewer batch means says little
    int max_batches = 512; // >= min_batches
    std::uint64_t seed = 1;

    friend bool operator==(const TransportSettings&, const TransportSettings&) = default;
};

// Checks the ranges above; errors read "transport.<field>: <what is wrong>" (exit code 2).
Result<void> validate_settings(const TransportSettings& settings);

struct TransportStats {
    std::uint64_t photons = 0; // traced, including those that carried no light
    int batches = 0;
    double relative_error = 0.0; // of the indirect fluence, as defined above
    bool converged = false;      // relative_error <= target (always, without indirect light)
    double seconds = 0.0;        // time of the solve that computed it (also when cached)
    bool from_cache = false;     // this result was read from the cache

    friend bool operator==(const TransportStats&, const TransportStats&) = default;
};

struct TransportResult {
    gi::GiWindow window;           // compute_window(scene.view, scene.gi.padding, resolution)
    RgbField direct;               // direct fluence at air texel centres; 0 in walls
    RgbField indirect;             // indirect fluence, texel averages; 0 in walls
    RgbField indirect_error;       // standard error of `indirect`, per texel and channel
    FaceField face_direct;         // direct irradiance at face segment midpoints
    FaceField face_indirect;       // indirect irradiance, segment averages
    FaceField face_indirect_error; // standard error of `face_indirect`
    TransportStats stats;
};

struct SolveProgress {
    int batch = 0; // batches done
    int max_batches = 0;
    double relative_error = 0.0; // after `batch` batches (0 before the second)
    double target = 0.0;
    std::uint64_t photons = 0;
    double seconds = 0.0;
    // Estimated share of the work done, in [0, 1]: the batches so far over the batches the
    // current error predicts (error falls as 1 / sqrt(batches)).
    double fraction = 0.0;
};

struct SolveOptions {
    jobs::JobSystem* jobs = nullptr; // chunks of each batch in parallel when set
    std::string cache_dir;           // "" = no cache
    // Called on the calling thread after every batch (progress bars, logs).
    std::function<void(const SolveProgress&)> progress;
};

// Solves the scene's transport. Errors (exit code 2): invalid settings, a view with no GI
// window. A cache that cannot be written is a warning, not an error.
Result<TransportResult> solve_transport(const scene::Scene& scene,
                                        const TransportSettings& settings,
                                        const SolveOptions& options = {});

} // namespace lantern::transport

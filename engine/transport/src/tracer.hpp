// Light tracing of one chunk of photons into fixed-point tallies.
#pragma once

#include "emitters.hpp"
#include "problem.hpp"

#include "lantern/transport/field.hpp"

#include <cstdint>
#include <vector>

namespace lantern::transport {

// One worker's sums for one batch, in fixed-point units (TraceParams::fixed_point per light
// unit). Integer sums are exact and order-independent: the merged batch is the same for any
// split of its chunks over workers.
struct Tally {
    std::vector<std::int64_t> ground; // window texels * 3: fluence x photons
    std::vector<std::int64_t> faces;  // face segments * 3: irradiance x photons

    void reset(std::size_t ground_values, std::size_t face_values);
};

struct TraceParams {
    int max_bounces = 64;
    // Photons whose brightest channel falls below this play Russian roulette. Photon
    // weights (light power per channel) never exceed EmitterTable::total_bound() /
    // resolution: emission weights are bounded so (emitters.hpp), reflection (albedo <= 1)
    // only lowers them, and roulette survivors are raised to roulette_weight, which must not
    // exceed it either.
    double roulette_weight = 0.25;
    double fixed_point = 1.0; // tally units per light unit of one deposit
};

// The fixed-point scale for batches of `photons` whose weights never exceed weight_bound:
// the largest that cannot overflow a tally (each of a photon's max_bounces + 1 straight
// segments crosses a texel at most once and ends on at most one face).
double fixed_point_scale(double weight_bound, int resolution, int max_bounces,
                         std::uint32_t photons);

// Traces `photons` photons drawn from the random stream `stream` and adds them to `tally`.
void trace_photons(const Problem& problem, const EmitterTable& emitters, const FaceLayout& faces,
                   const TraceParams& params, std::uint64_t stream, std::uint32_t photons,
                   Tally& tally);

} // namespace lantern::transport

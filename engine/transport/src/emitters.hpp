// Where indirect light starts: every (face segment, source) pair of the domain that can
// receive direct light, with an upper bound of that light, for importance sampling.
#pragma once

#include "problem.hpp"

#include "lantern/transport/model.hpp"

#include <cstdint>
#include <vector>

namespace lantern::transport {

// A face segment that sends light out: reflecting one source's direct light (weighted by
// its material's albedo), or its material's own emission.
struct Emitter {
    FaceRef face;
    int segment = 0; // 0..resolution-1 along the face
    SourceRef source;
    bool emission = false; // the material's emission (source unused)
    // An upper bound of the brightest channel the segment sends out per unit length:
    // max(albedo) x source_face_bound over the segment, or max(emission).
    float bound = 0.0f;
};

class EmitterTable {
  public:
    // Exposed faces of the domain's wall tiles whose air side is inside the domain, split
    // into `domain.resolution` segments, paired with every source that can light them (when
    // their material reflects) and with their material's emission (when it emits).
    static EmitterTable build(const Problem& problem);

    bool empty() const { return emitters_.empty(); }
    double total_bound() const { return total_; }
    // The emitter whose share of the bound total contains u in [0, 1). Not on an empty table.
    const Emitter& pick(double u) const;

  private:
    std::vector<Emitter> emitters_;
    std::vector<double> cumulative_; // inclusive prefix sums of the bounds
    double total_ = 0.0;
};

} // namespace lantern::transport

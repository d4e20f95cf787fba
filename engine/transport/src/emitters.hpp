// Where indirect light starts: every (face segment, source) pair of the domain that can
// receive direct light, with an upper bound of that light, for importance sampling.
#pragma once

#include "problem.hpp"

#include "lantern/transport/model.hpp"

#include <cstdint>
#include <vector>

namespace lantern::transport {

struct Emitter {
    FaceRef face;
    int segment = 0; // 0..resolution-1 along the face
    SourceRef source;
    float bound = 0.0f; // source_face_bound over the segment
};

class EmitterTable {
  public:
    // Exposed faces of the domain's wall tiles whose air side is inside the domain, split
    // into `domain.resolution` segments, paired with every source that can light them.
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

// The GI passes by name, and which ones a frame needs. The passes are rows of the pass
// table (pass_table.hpp): Pass is a row's id; the order they run in is their method's.
#pragma once

#include "lantern/gi/frame_inputs.hpp"

#include <cstdint>
#include <string>

namespace lantern::gi {

enum class Pass : std::uint8_t {
    conduction,
    ao,
    direct,      // point + emissive lights (the seed's "DDA")
    directional, // the seed's "DDA_Directional"
    emission,
    heat,        // heat transfer x rounds, with down/upsample at half and quarter scale
    blur,
    wall_indirect,
    lit,         // the lit image (tools; the game shades in its raster pass instead)
    count
};
inline constexpr int pass_count = int(Pass::count);
const char* pass_name(Pass pass);

struct PassSet {
    std::uint32_t bits = 0;
    bool has(Pass p) const { return (bits >> int(p)) & 1u; }
    PassSet& add(Pass p) {
        bits |= 1u << int(p);
        return *this;
    }
    PassSet& remove(Pass p) {
        bits &= ~(1u << int(p));
        return *this;
    }
    friend bool operator==(PassSet, PassSet) = default;
};

// What the scene and settings need: the rows of gi.method whose `not_needed` says nothing,
// and for each pass left out, why ("no directional lights", "AO disabled", ...). `through`
// limits the pipeline to the rows up to it (e.g. Pass::directional for direct light only).
struct PassPlan {
    PassSet run;
    std::string reason[pass_count]; // empty for passes that run
    bool has_walls_in_window = false;
};
PassPlan plan_passes(const FrameInputs& in, bool lit_image, Pass through = Pass::lit);

// Whether any wall tile lies in the window (wall-face work can be left out otherwise).
bool walls_in_window(const FrameInputs& in);

} // namespace lantern::gi

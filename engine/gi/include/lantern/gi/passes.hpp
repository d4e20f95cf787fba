// The GI passes by name, and which ones a frame needs. The passes are rows of the pass
// table (pass_table.hpp): Pass is a row's id; the order they run in is their method's.
#pragma once

#include "lantern/gi/frame_inputs.hpp"

#include <cstdint>
#include <string>
#include <string_view>

namespace lantern::gi {

enum class Pass : std::uint8_t {
    conduction,
    ao,
    direct,      // point + emissive lights (the seed's "DDA"), plus the realtime suns' own textures
    directional, // the seed's "DDA_Directional": the realtime suns into their own textures (runs before direct)
    emission,
    heat,        // heat transfer x rounds, with down/upsample at half and quarter scale
    blur,
    wall_indirect,
    lit,         // the lit image (tools; the game shades in its raster pass instead)
    distance_field, // radiosity: jump flood from the walls to a distance field (seed 003)
    radiosity,      // radiosity: light image, raymarch, accumulation, upsample (seed 003)
    gather,         // gather: face bounces, wall fill, ground gather, upsample (physical)
    mixed,          // mixed lights' direct light, after the indirect passes (their bounce is baked)
    baked_sample,   // the bake's atlas read into the window (cached while the bake and window stand)
    baked,          // the bake's light (FrameInputs::baked) added to the indirect textures, mixed lights' to direct
    probes,         // live light probes: the walls' light as circular harmonics every other tile (gi.probe_rays)
    builtin_count
};
// Pass ids: the built-in rows above, then rows registered at run time (add_row in
// pass_table.hpp) up to this capacity. Arrays indexed by Pass have pass_count entries.
inline constexpr int pass_count = 32;
inline constexpr int builtin_pass_count = int(Pass::builtin_count);
// The row's name ("heat"); "?" for an id no row has.
const char* pass_name(Pass pass);
// Pass ids in use: 0 .. registered_pass_count() - 1 (the built-ins and the rows added).
int registered_pass_count();

struct PassSet {
    std::uint32_t bits = 0;
    static_assert(pass_count <= 32, "PassSet holds 32 passes");
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
// limits the pipeline to the rows up to it (e.g. Pass::direct for direct light only: the suns come before it).
struct PassPlan {
    PassSet run;
    std::string_view reason[pass_count] = {}; // static text; empty for passes that run
    bool has_walls_in_window = false;
    // Converging rows (PassRow::converge_frames): how many frames of history the row has
    // accumulated before this one (0: start afresh). Set by derive_keys from a Convergence.
    std::uint16_t history[pass_count] = {};
};
PassPlan plan_passes(const FrameInputs& in, bool lit_image, Pass through = Pass::lit);

// Whether any wall tile lies in the window (wall-face work can be left out otherwise).
bool walls_in_window(const FrameInputs& in);

} // namespace lantern::gi

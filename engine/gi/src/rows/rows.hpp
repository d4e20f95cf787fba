// The rows of the built-in GI methods (pass_table.hpp), defined beside their recorders:
// direct_light.cpp (conduction, ao, direct, directional), indirect_light.cpp (emission,
// heat, blur, wall_indirect), radiosity.cpp (distance_field, radiosity) and lit_image.cpp (lit). Constant-initialised, so the method
// lists in pass_table.cpp can point at them from any translation unit.
#pragma once

#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/reference_indirect.hpp"

namespace lantern::gi::rows {

extern const PassRow conduction;
extern const PassRow ao;
extern const PassRow direct;
extern const PassRow directional;
extern const PassRow emission;
extern const PassRow heat;
extern const PassRow blur;
extern const PassRow wall_indirect;
extern const PassRow lit;
extern const PassRow distance_field;
extern const PassRow radiosity;

// Records the upsample of a grid texture (heat, radiosity) into Tex::indirect (gi_upsample).
void record_upsample(vk::PassRecorder& r, Tex src, const HeatGrid& grid);

} // namespace lantern::gi::rows

// The fog pass (a row added to Lantern's pass table from outside the engine).
#pragma once

#include "lantern/gi/pass_table.hpp"

#include <glm/vec3.hpp>

namespace fog {

// The fog's colour and its blend at the window's edge.
inline constexpr glm::vec3 colour{0.35f, 0.4f, 0.55f};
inline constexpr float density = 0.6f;

// Adds the "fogged" texture and the "fog" row (after the blur) to the heat method; call once,
// before the first frame. Returns the texture's id.
lantern::gi::Tex register_fog();

} // namespace fog

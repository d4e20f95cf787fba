// The physical model of Lantern's light-transport reference (docs/accuracy.md, "Model").
//
// Transport is two-dimensional ("flatland"): light travels in the ground plane over the
// wall grid. The ground is not a surface of the transport: it neither reflects nor absorbs,
// it is where fluence is read. Wall tiles are opaque Lambertian reflectors, each with its
// material's RGB albedo and emission (scene::Material; the default wall is grey
// TransportSettings::albedo and does not glow); tiles outside the wall grid are air.
//
// Quantities, in Lantern's light units:
// - fluence: radiance integrated over all directions of the plane. Lantern's ground
//   textures (direct, indirect) hold it.
// - irradiance on a wall face: radiance times the cosine to the face normal, integrated over
//   the half-plane in front of the face. Lantern's wall-face textures hold it.
//
// Sources are defined by their direct term, which is Lantern's own, so the direct parts of
// the two agree by construction and the comparison isolates the indirect modelling:
// - point light: fluence c (1 - d/r)^s V within the radius, where c = colour x intensity,
//   s = gi.light_softness and V = min(grid visibility by Lantern's traversal, proxy shadow);
// - emissive: the same without V (emissives pass through walls, as in Lantern);
// - directional: c x angle x V_sun, with Lantern's wall-height traversal and directional
//   proxies (a sun below the horizon gives nothing).
// Every source arrives from a single direction l at a point (a point or a parallel source),
// so a face with normal n receives E = fluence x max(0, n . l): Lantern's face weighting,
// evaluated at the point on the face instead of at the wall texel's centre.
//
// Reflection: a face with irradiance E leaves with radiosity B = albedo x E + emission, as radiance
// B / 2 in every direction of its half-plane (in 2D the cosine integrates to 2 over the
// half circle).
//
// Threads: every function is reentrant; FrameInputs are read only.
#pragma once

#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/reference.hpp" // gi::Face

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace lantern::transport {

// Exposed wall faces: the face `face` (gi::Face order +X, -X, +Z, -Z) of the wall tile `tile`.
struct FaceRef {
    glm::ivec2 tile{0};
    int face = 0;
};

// Outward unit normal of a face, pointing into the air in front of it.
glm::vec2 face_normal(int face);
// The point at parameter s in [0, 1] along the face, s increasing with world x (for +-Z
// faces) or world z (for +-X faces).
glm::vec2 face_point(FaceRef face, float s);
// Whether the face is exposed: a wall tile with air across the face.
bool face_exposed(const gi::WallView& walls, FaceRef face);

// One source of a frame: an index into FrameInputs::point_lights, emissive_lights or
// directional_lights.
enum class SourceKind : std::uint8_t { point, emissive, directional };
struct SourceRef {
    SourceKind kind = SourceKind::point;
    std::uint32_t index = 0;
};

// Direct fluence at a ground point p in air: every source of `in` (caps and culling as the
// caller gathered them). What Lantern's direct pass computes at a texel centre, in float.
glm::vec3 direct_fluence(const gi::FrameInputs& in, glm::vec2 p);

// Direct irradiance on an exposed face at the point p on it, from one source or from all.
// Shadow rays end (or, for suns, start) 1e-3 in front of the face, as Lantern's face rays.
glm::vec3 source_face_irradiance(const gi::FrameInputs& in, SourceRef source, FaceRef face,
                                 glm::vec2 p);
glm::vec3 direct_face_irradiance(const gi::FrameInputs& in, FaceRef face, glm::vec2 p);

// An upper bound of the brightest channel of source_face_irradiance over the face points
// with parameters [s0, s1], ignoring visibility; 0 when no light of the source can arrive
// there (behind the face, out of reach, a sun below the horizon or overhead). Exact for
// the unshadowed maximum: falloff and cosine both peak at the point closest to the source.
float source_face_bound(const gi::FrameInputs& in, SourceRef source, FaceRef face, float s0,
                        float s1);

} // namespace lantern::transport

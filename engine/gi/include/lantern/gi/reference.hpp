// The scalar C++ reference of every GI pass: the specification the Vulkan passes are
// compared with texel by texel. Written for clarity, one texel at a time, in the order of
// operations the shaders use, compiled with -ffp-contract=off. The passes follow seed 000
// (../shared/seeds/000_8b759f34ccb2f1d7.txt); docs/gi.md lists where Lantern had to decide
// something the seed leaves open (proxy width and penumbra curves, directional proxies).
//
// Outputs are quantised to their storage formats as the GPU stores them (texture.hpp).
// Rows may run in parallel on a JobSystem (pass one in RefOptions); the result is the same.
#pragma once

#include "lantern/gi/frame_inputs.hpp"
#include "lantern/gi/texture.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace lantern::jobs {
class JobSystem;
}

namespace lantern::gi {

enum Face : int { face_pos_x = 0, face_neg_x = 1, face_pos_z = 2, face_neg_z = 3 };
inline constexpr const char* face_suffix[4] = {"px", "nx", "pz", "nz"};

struct DirectTextures {
    Texture direct; // rgba16f: ground direct light (point + emissive + directional)
    Texture shadow; // rg8: R = max point-light visibility, G = max directional visibility
    std::array<Texture, 4> wall_direct; // rgba16f per face (+X, -X, +Z, -Z), wall texels only;
                                        // empty for faces not computed (computed_faces)
    // gi.proxy_wall_shadows = unfold with proxies (unfolds_proxy_shadows): per face the light
    // at the face's top (rgb) and the height where the proxies' shadows end (a); else empty.
    std::array<Texture, 4> wall_upper;
};

struct RefOptions {
    jobs::JobSystem* jobs = nullptr; // rows in parallel when set
};

Texture reference_conduction(const FrameInputs& in, const RefOptions& options = {});
Texture reference_ao(const FrameInputs& in, const RefOptions& options = {});
// Point and emissive lights (the seed's "DDA" pass); with `suns` (the realtime suns' own
// textures: reference_directional onto zero textures), their light added texel by texel as
// the direct shader adds it: colours and faces summed, the suns' shadow as G, the upper
// faces' edges merged weighted by the light their shadows take.
DirectTextures reference_direct(const FrameInputs& in, const RefOptions& options = {},
                                const DirectTextures* suns = nullptr);
// Adds the directional lights into `textures` (the seed's "DDA_Directional" pass).
void reference_directional(const FrameInputs& in, DirectTextures& textures, const RefOptions& options = {});

// ---- building blocks, exposed for the edge-case tests

// Amanatides-Woo traversal from the light to the pixel against the wall grid: 0 when a
// wall cell (or a diagonal step between two wall cells) blocks the segment, else 1.
float shadow_dda(const WallView& walls, glm::vec2 light, glm::vec2 pixel, float radius);
// Traversal from the pixel towards the sun with the wall-height test: 0 when blocked.
float directional_shadow_dda(const WallView& walls, glm::vec2 pixel, glm::vec3 light_dir, float max_distance,
                             float wall_height);
float penumbra_factor(float distance, float edge, float width, float power, int mode);
float proxy_width(const GpuShadowProxy& proxy, glm::vec2 perp);
float point_proxy_shadow(std::span<const GpuShadowProxy> proxies, glm::vec2 light, glm::vec2 pixel);
float directional_proxy_shadow(std::span<const GpuShadowProxy> proxies, glm::vec2 pixel, glm::vec3 light_dir);
float light_falloff(float distance, float radius, float softness);

// gi.proxy_wall_shadows = unfold: the wall folded flat onto the ground behind it, so a face
// point at height y is shaded by the proxies as the ground point y beyond it along the
// light's direction of travel. `low`: the proxies' visibility at the face's foot (the
// seed's value), `high`: at its top (height), `edge`: the height where their shadows end
// (where the length penumbra is half way), in [0, height]; 0 when none falls on it.
struct FaceProxyShadow {
    float low = 1.0f, high = 1.0f, edge = 0.0f;
};
FaceProxyShadow point_proxy_face_shadow(std::span<const GpuShadowProxy> proxies, glm::vec2 light, glm::vec2 target,
                                        float height);
FaceProxyShadow directional_proxy_face_shadow(std::span<const GpuShadowProxy> proxies, glm::vec2 target,
                                              glm::vec3 light_dir, float height);
// True when the frame stores unfolded proxy shadows on wall faces: the setting, proxies,
// computed faces and walls with a height.
bool unfolds_proxy_shadows(const FrameInputs& in);
glm::vec4 wall_face_mask(const WallView& walls, glm::ivec2 cell);
// The wall faces the GI computes and stores, bit f for face f (+x, -x, +z, -z): the faces
// gi.wall_faces keeps, none when gi.wall_lighting is off. Faces left out are neither
// traced nor allocated; they read as no light.
std::uint32_t computed_faces(const scene::GiSettings& gi);
inline bool computes_face(std::uint32_t faces, int face) { return (faces >> face) & 1u; }
// 1 for the faces in `faces`, 0 for the others (multiplies wall_face_mask).
glm::vec4 face_bits_mask(std::uint32_t faces);
// The weight of each wall face (+x, -x, +z, -z) for light from unit direction `dir_to_light`:
// saturate(dot(n, d)) raised to `exponent` (gi.wall_face_exponent; 1 leaves it as it is).
glm::vec4 wall_facing(glm::vec2 dir_to_light, float exponent);
float bayer4(int x, int y); // (M[y%4][x%4] + 0.5) / 16

// AO weights. A texel's weight for the tile (dx, dy) tiles away from its own depends only on
// the texel's position inside its tile, so the weights are computed once per resolution in
// tile-local coordinates: weights[(sy * res + sx) * n + (dy + range) * (2 range + 1) + dx + range]
// = pow(1 - saturate(dist / radius), power) (0 beyond the radius), totals[sy * res + sx] =
// their sum. Both the reference and the GPU pass use this table.
struct AoKernel {
    int resolution = 1;
    int range = 0; // ceil(radius)
    std::vector<float> weights;
    std::vector<float> totals;
    int taps() const { return (2 * range + 1) * (2 * range + 1); }
};
AoKernel ao_kernel(int resolution, const scene::AoSettings& ao);

} // namespace lantern::gi

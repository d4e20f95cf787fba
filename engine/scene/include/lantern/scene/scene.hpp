// A lit grid world as a scene file describes it (../shared/SCENES.md, docs/scenes.md):
// the wall grid, the GI window (orthographic view or perspective camera), the GI settings,
// and the lights and shadow proxies. Plain data; loading and validation live in loader.hpp.
// Every type compares member-wise with == (floats exactly).
//
// Conventions (identical in every GI pass): world positions are (x, z); one grid cell is
// one world unit; the tile of a position is floor(pos); grid cell (col, row) of WallGrid
// is the world tile (origin.x + col, origin.z + row); tiles outside the grid are air.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace lantern::scene {

enum class HeatScale : std::uint8_t { full = 1, half = 2, quarter = 4 };
enum class ToneMap : std::uint8_t { none, reinhard, reinhard_white, aces };
// What the GI window's origin locks to as the camera moves (seed 000's phase lock): whole
// tiles, or texel boundaries (smoother tracking: the window steps 1/resolution of a tile,
// times the heat scale, so heat texels stay whole; more cache invalidations while walking).
enum class WindowSnap : std::uint8_t { tile, texel };
// How the sun's grid shadows are found: the seed's DDA per texel, or a 1D shadow map across
// the sun direction (exact against the DDA; docs/gi.md, "The sun's shadow map").
enum class SunShadowMethod : std::uint8_t { dda, shadow_map };
enum class ShadowMethod : std::uint8_t { dda, shadow_map }; // point lights' grid shadows
// How a shadow proxy's shadow falls on a wall face: the whole face top to bottom (the seed's),
// or unfolded: the wall is folded flat onto the ground behind it, so a face at height y is
// shaded as the ground y beyond the face along the ray, and the shadow keeps its shape,
// reaching up the wall as far as its remaining length (docs/gi.md, "Proxy shadows on walls").
enum class ProxyWallShadows : std::uint8_t { full, unfold };

struct AoSettings {
    bool enabled = true;
    float radius = 1.5f;   // world units
    float power = 1.0f;    // distance-weight exponent
    float strength = 0.6f; // 0 = no darkening, 1 = full
    bool dither = false;   // 4x4 Bayer dither before 8-bit quantisation
    bool walls = false;    // also darken wall faces (by the ground texel just outside the face)

    friend bool operator==(const AoSettings&, const AoSettings&) = default;
};

// Which wall faces the GI computes and stores (gi.wall_faces.px ... nz). A camera with a
// fixed direction never sees some faces (the game's never sees -z): leave those out.
struct WallFaces {
    bool px = true, nx = true, pz = true, nz = true; // +x, -x, +z, -z

    friend bool operator==(const WallFaces&, const WallFaces&) = default;
};

// Every key of a scene's "gi" object; the defaults are the documented defaults.
// The GI method: which rows of the pass table a frame runs (engine/gi pass_table.hpp).
enum class GiMethod : std::uint8_t {
    heat = 0,      // seed 000's heat diffusion
    radiosity = 1, // seed 003's jump-flood distance field and raymarched radiosity
    gather = 2,    // physical: wall-face radiosity bounced and gathered by rays (engine/transport's model)
};

// How the radiosity method's rays turn from frame to frame (seed 003, "Noise & Hacks"):
// the seed's rotation of the blue noise by t / 2pi radians per frame, the golden-ratio
// shift fract(noise + PHI * t), or no noise at all (every texel casts the same directions:
// the banding the seed warns of).
enum class NoiseShift : std::uint8_t { rotate, golden, off };

// gi.radiosity.* (docs/gi.md, "The radiosity method").
struct RadiositySettings {
    HeatScale scale = HeatScale::quarter; // the radiosity grid: the GI window at 1/scale
    int rays = 16;                        // rays per texel, equally spaced
    int steps = 32;                       // distance-field steps per ray
    float epsilon = 0.5f;                 // hit when the distance to a wall texel's centre < epsilon (grid texels)
    float feedback = 0.5f;                // weight of last frame's light as this frame's emitter (a bounce per frame)
    int accumulate = 1;                   // temporal accumulation: running mean over up to this many frames (1: off)
    NoiseShift noise = NoiseShift::rotate;
    int frames = 16;                      // frames a still scene refines before it stops submitting

    friend bool operator==(const RadiositySettings&, const RadiositySettings&) = default;
};

// gi.gather.* (docs/gi.md, "The gather method").
struct GatherSettings {
    HeatScale scale = HeatScale::half; // the ground gather's grid: the GI window at 1/scale
    int rays = 32;                     // ground rays per grid texel, equally spaced over the circle
    int face_rays = 32;                // rays per wall-face texel, equally spaced over the half circle
    int bounces = 2;                   // face bounces per frame (light reflected on from face to face)
    int frames = 8;                    // frames a still scene refines before it stops submitting
    int margin = 4;                    // tiles added to the GI window on every side: walls there reflect light in

    friend bool operator==(const GatherSettings&, const GatherSettings&) = default;
};

struct GiSettings {
    GiMethod method = GiMethod::heat;
    int resolution = 8; // GI texels per world unit, 1..32
    float padding = 1.4f;
    WindowSnap window_snap = WindowSnap::tile;
    int heat_rounds = 20;
    HeatScale heat_scale = HeatScale::full;
    float diffusion_rate = 1.0f;
    float diffusion_distance = 1.0f; // world units
    float emission_strength = 1.0f;
    float range_boost = 0.0f;
    float intensity_multiplier = 1.0f;
    bool per_channel = true;
    bool segment_check = true;
    float light_softness = 1.0f; // falloff exponent
    float wall_face_exponent = 1.0f; // k in a wall face's weight saturate(dot(n, to_light))^k (seed 000)
    bool wall_lighting = true;       // false: no wall-face light, passes or textures (seed 000's switch)
    WallFaces wall_faces;            // the faces computed and stored (culling for fixed cameras)
    AoSettings ao;
    bool blur = true;
    ToneMap tone_map = ToneMap::aces;
    float white_point = 4.0f;              // reinhard_white
    float directional_angle_scale = 0.0f;  // 0 = full sun-angle modulation, 1 = none
    ShadowMethod shadow_method = ShadowMethod::shadow_map; // point lights: angular maps (exact) or the DDA
    SunShadowMethod sun_shadow_method = SunShadowMethod::dda;
    int max_lights = 256;                  // point lights kept per frame (emissives bypass it)
    int max_shadow_proxies = 64;
    ProxyWallShadows proxy_wall_shadows = ProxyWallShadows::full;
    RadiositySettings radiosity; // gi.method = radiosity
    GatherSettings gather;       // gi.method = gather
    float wall_albedo = 0.5f;    // walls' grey albedo where bounce light is physical (gi.method = gather)
    // Seed 004's meta pass: every wall albedo a (materials' and the default's) becomes
    // clamp(a^(1 / albedo_boost), 0, 1) in the physical bounce (gather, transport, bake).
    float albedo_boost = 1.0f;
    // Seed 002's runtime intensity: the baked light (docs/baked.md) the frame adds, scaled
    // (the light probes too). 1 is the bake as solved.
    float baked_intensity = 1.0f;
    // Live light probes (seed 004's realtime light probes; docs/baked.md, "Live probes"): rays
    // per probe that capture the frame's wall light as circular harmonics every other tile, for
    // the things that move. 0: none (nothing in a scene file or lantern-render reads them).
    int probe_rays = 0;

    friend bool operator==(const GiSettings&, const GiSettings&) = default;
};

// How a light reaches the GI (seed 004's light modes): live every frame, direct light live
// and its bounce light baked (mixed), or both baked (lantern-bake; docs/baked.md). The bake
// holds mixed and baked lights; until a world's bake is loaded at run time every light
// is lit live, whatever its mode.
enum class LightMode : std::uint8_t { realtime, mixed, baked };

struct PointLight {
    glm::vec2 position{0.0f}; // world x, z
    float height = 1.0f;      // above the ground (used by later height-aware passes)
    glm::vec3 color{1.0f};    // linear RGB
    float intensity = 1.0f;   // multiplies color
    float radius = 8.0f;      // world units, > 0
    LightMode mode = LightMode::realtime;
    // Seed 004's indirect multiplier: scales the light's baked bounce (0: no GI). Mixed and
    // baked lights only: a realtime light's bounce is the live method's (the loader refuses it).
    float indirect = 1.0f;

    friend bool operator==(const PointLight&, const PointLight&) = default;
};

struct EmissiveLight {
    glm::vec2 position{0.0f};
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float radius = 4.0f;
    LightMode mode = LightMode::realtime;
    float indirect = 1.0f; // as PointLight::indirect

    friend bool operator==(const EmissiveLight&, const EmissiveLight&) = default;
};

struct DirectionalLight {
    glm::vec3 direction{0.0f, -1.0f, 0.0f}; // direction the light travels, normalised on load
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float base_shadow_distance = 4.0f; // world units, scaled by 1 / max(|direction.y|, 0.02)
    float bounce_intensity = 0.5f;
    LightMode mode = LightMode::realtime;
    float indirect = 1.0f; // as PointLight::indirect

    friend bool operator==(const DirectionalLight&, const DirectionalLight&) = default;
};

enum class ProxyShape : std::uint8_t { box = 0, circle = 1 };
enum class WidthMode : std::uint8_t { projected = 0, max_axis = 1 };
enum class PenumbraMode : std::uint8_t { inward = 0, outward = 1, both = 2 };

struct ShadowProxy {
    glm::vec2 position{0.0f};
    ProxyShape shape = ProxyShape::circle;
    glm::vec2 size{0.5f}; // half extents (box) or radius in x (circle)
    float max_length = 3.0f;
    float end_cap_blend = 0.5f;
    float penumbra_width = 0.3f;
    float penumbra_length = 1.0f;
    float penumbra_power = 1.0f;
    WidthMode width_mode = WidthMode::projected;
    PenumbraMode penumbra_mode = PenumbraMode::both;
    // Seed 004's static flag: a static proxy (a placed tree or lamp post) shadows the baked
    // light too; a moving one only the live light.
    bool is_static = true;

    friend bool operator==(const ShadowProxy&, const ShadowProxy&) = default;
};

// A wall material (seed 004's meta pass; docs/scenes.md, "materials"): what a wall tile
// reflects and emits where bounce light is physical (gi.method = gather, the transport
// reference, the bake). A lit face leaves with radiosity B = albedo x E + emission.
// Seed 004's emission GI mode: how a glowing material's light reaches the GI.
//   baked     (default) held by the bake once a world's bake is used; live until then
//   realtime  always live: the bake leaves it out (glow that changes at run time)
//   none      lights nothing: the tile is drawn glowing, the GI never sees its emission
enum class EmissionGi : std::uint8_t { baked, realtime, none };

struct Material {
    std::string name;
    glm::vec3 albedo{0.5f};   // linear RGB reflectance, each in [0, 1]
    glm::vec3 emission{0.0f}; // linear RGB radiosity the faces leave with unlit (light units)
    EmissionGi emission_gi = EmissionGi::baked;
    // Seed 004's meta-pass opacity, [0, 1]: multiplies albedo and emission in the GI (the
    // bounce and glow of see-through tiles: glass, ice, water). The tile still blocks light.
    float opacity = 1.0f;
    // Seed 004's pulsing emission, in Hz (0: steady): the glow scales by
    // 0.5 + 0.5 cos(2 pi pulse t). A baked glow's light is baked apart from the steady light
    // and scaled at run time (a colour-only update, not a re-bake: docs/baked.md, "Pulsing
    // emission"); every pulsing material of a scene pulses at one frequency.
    float pulse = 0.0f;

    friend bool operator==(const Material&, const Material&) = default;
};

// The glow factor of a material pulsing at `hz` at time `t` seconds: 0.5 + 0.5 cos(2 pi hz t)
// (1 when steady).
inline float pulse_factor(float hz, double t) {
    if (hz <= 0.0f) return 1.0f;
    const double cycles = double(hz) * t;
    return float(0.5 + 0.5 * std::cos(6.283185307179586 * (cycles - std::floor(cycles))));
}
// The frequency the scene's pulsing materials share (0: none pulses).
inline float pulse_frequency(const std::vector<Material>& materials) {
    for (const Material& m : materials)
        if (m.pulse > 0.0f) return m.pulse;
    return 0.0f;
}

// Wall cell values: 0 air, 1 the default wall (grey gi.wall_albedo, no emission), and
// 2 + k the scene's material k. Every wall test is `cell != 0`.
inline constexpr std::uint8_t default_wall_cell = 1;
inline constexpr int first_material_cell = 2;
inline constexpr int max_materials = 256 - first_material_cell; // 254
inline constexpr std::uint8_t material_cell(int material) { return std::uint8_t(first_material_cell + material); }

struct WallGrid {
    int width = 0;
    int height = 0;
    glm::ivec2 origin{0};            // world tile of cell (0, 0)
    std::vector<std::uint8_t> cells; // row-major, cells[col + row * width]: 0 air, else a wall (its material, above)

    bool is_wall_tile(int x, int z) const { return cell(x, z) != 0; }
    // The tile's cell value: 0 air (also out of bounds), else its wall material.
    std::uint8_t cell(int x, int z) const {
        int c = x - origin.x, r = z - origin.y;
        if (c < 0 || r < 0 || c >= width || r >= height) return 0;
        return cells[std::size_t(c) + std::size_t(r) * std::size_t(width)];
    }

    friend bool operator==(const WallGrid&, const WallGrid&) = default;
};

// Top-down orthographic GI window: centre and size in world units, before padding.
struct OrthoView {
    glm::vec2 center{0.0f};
    glm::vec2 size{30.0f, 16.875f};

    friend bool operator==(const OrthoView&, const OrthoView&) = default;
};

// Perspective camera whose viewport is projected on the ground plane y = 0.
struct PerspectiveCamera {
    glm::vec3 position{0.0f, 20.0f, 0.0f};
    glm::vec3 target{0.0f};
    float fov_deg = 40.0f; // vertical field of view
    float aspect = 16.0f / 9.0f;

    friend bool operator==(const PerspectiveCamera&, const PerspectiveCamera&) = default;
};

using ViewSpec = std::variant<OrthoView, PerspectiveCamera>;

// The rectangle of ground (y = 0) a perspective camera sees: its four viewport corners
// projected on the ground (the seed's CalculateCameraVisibleArea), in double precision.
// nullopt when a corner ray is parallel to the ground (|dir.y| < 1e-4) or hits it behind
// the camera, or a value is not finite; `reason` then says which. The scene loader refuses
// such a camera; the GI window (gi::visible_area) is built on this rectangle.
struct GroundArea {
    glm::vec2 min{0.0f};
    glm::vec2 size{0.0f};
};
std::optional<GroundArea> ground_footprint(const PerspectiveCamera& camera, std::string* reason = nullptr);

// How the bake solves the bounce light (lantern/bake/bake.hpp says more).
//   gather   the converged physical method (gi.method = gather)
//   seed002  seed 002's own one-bounce bake with its falloff and ambient fill
enum class BakeSolver : std::uint8_t { gather, seed002 };

// A world's bake settings (seed 002's "saved with the world"; the scene file's "bake",
// docs/scenes.md): lantern-bake and lantern-render --bake start from them, and their
// command-line options win. Checked by bake::validate_settings.
// Seed 004's texel density, per chunk: the chunks (x, z) with min <= (x, z) <= max (chunk
// (x, z) covers the tiles [32 x, 32 x + 32) x [32 z, 32 z + 32)) bake at `resolution` texels
// a tile instead of the world's (BakeSettings::density: the last region holding a chunk wins).
struct BakeDensity {
    glm::ivec2 min{0}, max{0};
    int resolution = 4; // 1..16
    friend bool operator==(const BakeDensity&, const BakeDensity&) = default;
};
inline constexpr int max_bake_density_regions = 4096;

struct BakeSettings {
    int resolution = 4; // texels per tile, 1..16 (seed 002's finest probe spacing: 1 / resolution tiles)
    int margin = 32;    // tiles around the chunk whose walls reflect or send light into it, 0..64
    int rays = 256;      // gather rays per ground texel and light probe, 1..1024 (the live default is 32)
    int face_rays = 128; // gather rays per face texel, 1..1024
    BakeSolver solver = BakeSolver::gather;
    float falloff = 4.0f; // seed002: the falloff's half distance, tiles, [1/64, 4096]
    float ambient = 0.0f; // seed002: the ambient fill every hit face receives, [0, 1000]
    // Seed 004's directional bake: probes keep the light's direction (circular harmonics of
    // order 2); non-directional keeps the fluence alone (a0), lighting every side alike.
    bool directional = true;
    // Seed 004's precomputed GI for the moving sun (docs/baked.md, "The moving sun"): 0 bakes
    // a mixed sun's bounce at its own direction; 2..32 bakes it at that many times of the
    // day's path (scene::sun_key_time, day.hpp), at unit colour, and the run time blends the
    // two keys around the sun's direction and scales them by its colour. Takes one mixed sun.
    int sun_keys = 0;
    // At run time (not in the cache key): seed 002's brick coarsening tolerance (colour range
    // per channel, light units, [0, 1000]) and the largest brick level (0..3: a brick spans
    // up to 2^max_level x 4 probes a side).
    float eps = 0.01f;
    int max_level = 3;
    // Texel density per chunk (regions of chunks at their own resolution; empty: every chunk
    // at `resolution`). Sparse caves can bake coarse and a detailed room fine.
    std::vector<BakeDensity> density{};

    // The resolution chunk (x, z) bakes at: the last density region holding it, else
    // `resolution`.
    int resolution_at(int x, int z) const {
        for (auto r = density.rbegin(); r != density.rend(); ++r)
            if (x >= r->min.x && x <= r->max.x && z >= r->min.y && z <= r->max.y) return r->resolution;
        return resolution;
    }

    friend bool operator==(const BakeSettings&, const BakeSettings&) = default;
};

struct Scene {
    std::string source; // file the scene came from (for messages); empty if built in code
    WallGrid walls;
    float wall_height = 2.0f;
    ViewSpec view = OrthoView{};
    GiSettings gi;
    std::vector<PointLight> point_lights;
    std::vector<EmissiveLight> emissive_lights;
    std::vector<DirectionalLight> directional_lights;
    std::vector<ShadowProxy> shadow_proxies;
    std::vector<Material> materials; // cell value 2 + k is materials[k]
    BakeSettings bake;               // its bake's settings ("bake")
    bool bake_given = false;         // the file has a "bake" block (else `bake` holds the defaults)
    // The other files the scene was read from (its world.map), as opened: what --watch looks
    // at besides the scene file. Empty for a scene built in code.
    std::vector<std::string> inputs;

    friend bool operator==(const Scene&, const Scene&) = default;
};

} // namespace lantern::scene

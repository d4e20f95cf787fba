// The game's world renderer: the world as boxes (walls, the ground, props, torches, the
// player, the cursor highlight), drawn face group by face group into the low-resolution
// pixel-art target (render::RenderTarget, 480x270 RGBA8 sRGB + D32 by default) and lit by the
// GI textures that gi::vk::Renderer computed this frame. docs/game.md, "World rendering".
//
//   auto world = WorldRenderer::create(device);                 // an error without raster support
//   gpu::CommandList cmd = device.begin("frame");
//   gi.record_plan(cmd, inputs, plan);                           // this frame's GI passes
//   world->record(cmd, {camera, &inputs, &gi, art, time}, list); // barrier, clear, boxes, art
//   device.submit(std::move(cmd));                               // or record_upscale + present
//
// Shading: the shared shading library (shaders/include/lantern/shading.glsl, the twin of
// engine/gi/src/shading.cpp) routes every lit fragment (ground, wall face, wall top) exactly
// as the GI's lit image and the C++ reference do; the colour is
//   tone_map(albedo * pattern * surface_light(pos, n) + color * emissive)   (ground, wall, prop)
//   tone_map(color * emissive)                                                (glow: unlit)
// then the art controls (dither, posterize, palette) in sRGB-encoded space.
//
// Ownership: move-only GPU handles (destroy before the Device). Threads: the submission
// thread of the Device. Frames in flight: every per-frame buffer is rewritten inside the
// frame's command list (render::StreamBuffer), so any number of frames may be in flight.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/game/gameplay.hpp"
#include "lantern/game/gi_view.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/render/render_target.hpp"
#include "lantern/scene/scene.hpp"

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace lantern::gpu {
class Buffer;
class CommandList;
class Device;
} // namespace lantern::gpu

namespace lantern::gi::vk {
class Renderer;
}

namespace lantern::game {

enum class Material : int {
    ground = 0, // lit; speckled floor pattern
    wall = 1,   // lit; brick pattern on faces, slabs on the top
    prop = 2,   // lit; plain hashed variation
    glow = 3,   // unlit: color * emissive only (flames, crystals' cores, the cursor)
    // lit as prop, and by the baked light from the direction it comes from: `emissive` is
    // the index of its record in DrawList::probes (the player, trees, lamp posts)
    lit_probes = 4,
    // lit per texel (docs/texel.md): each face takes the per-texel light of the texel under the
    // pixel (WorldView::texel_lit) plus the GI's indirect light at that texel's centre, times
    // the texel's albedo (WorldView::texel_albedo) and `color`; `emissive` is the index of its
    // record in WorldView::texel_records. Drawn as prop when the view has no texel light.
    texel_lit = 5,
};

// One box of the world (48 bytes: three vec4s, which game_world.vert.glsl reads as three
// RGBA32F texels of a uniform texel buffer).
// The ground is a box of zero height with only its top face. Boxes are axis-aligned.
struct BoxInstance {
    glm::vec3 center{0.0f};
    float material = 0.0f;  // float(Material)
    glm::vec3 half{0.5f};   // half extents (>= 0)
    float face_mask = 31.0f; // bits: 1 +x, 2 -x, 4 +z, 8 -z, 16 top (+y); faces not in it are not drawn
    glm::vec3 color{1.0f};  // linear albedo (lit materials) or emission colour (glow)
    float emissive = 0.0f;  // adds color * emissive, unlit
};
static_assert(sizeof(BoxInstance) == 48, "game_world.vert.glsl reads 48-byte instances");

inline constexpr int face_pos_x = 1, face_neg_x = 2, face_pos_z = 4, face_neg_z = 8, face_top = 16, face_all = 31;

// The baked light around a lit_probes box: circular harmonics (bake/probes.hpp) a0, a1, b1,
// a2, b2 in rgb. A side face whose normal has angle phi adds
// max(pi E(phi), 0) - a0 to the light the GI textures give it (their baked part is a0, the
// ground's fluence), so a face turned towards the baked light gets more of it and one turned
// away less: E(phi) = a0 / pi + (a1 cos phi + b1 sin phi) / 2 + 2 (a2 cos 2phi + b2 sin 2phi) / (3 pi).
// Tops add nothing (the baked light is in the ground plane). 96 bytes: two BoxInstances.
// With `live.z` 1 the vertex stage first adds the GI's live probes (gi::Tex::probes, the
// walls' light this frame) interpolated at (live.x, live.y), the object's anchor on the ground,
// between the four around it that stand in open ground (docs/baked.md, "Live probes").
struct ProbeRecord {
    glm::vec4 c[5]{};
    glm::vec4 live{0.0f};
};
static_assert(sizeof(ProbeRecord) == 2 * sizeof(BoxInstance), "probe records ride in the box buffer");

// The light the probes add to a side face of a lit_probes box whose outward normal has angle
// phi = atan2(n.z, n.x) (the vertex stage's formula, for tests and the CPU; the record's own
// harmonics: the live probes are the GPU's).
glm::vec3 probe_face_light(const ProbeRecord& r, float phi);

// Where a texel_lit box's texture lies in the per-texel atlas (96 bytes: two BoxInstances):
// `texture` x the atlas index of its texel (0, 0), y its size (texels per side), z 1 + the
// index of its baked-light ProbeRecord in the DrawList (0: none; the side faces then take
// the baked light's direction as lit_probes boxes do), w its glow (TexelPart::glow); face f's
// rectangle of texels (x, y, width, height) as texel::box_model lays the box's faces out
// (texel::Model::faces: +x, -x, +z, -z, top).
struct TexelRecord {
    glm::vec4 texture{0.0f};
    glm::vec4 faces[5]{};
};
static_assert(sizeof(TexelRecord) == 2 * sizeof(BoxInstance), "texel records ride in the box buffer");

// A texel_lit box's model: which one (the application's table) and where it stands.
struct TexelPart {
    std::uint64_t key = 0; // the same while the part exists (entity and part), for caching
    int model = 0;
    glm::vec3 center{0.0f}; // the box's centre (its half extents are the model's)
    int lod = 0;            // level of detail: the model's art at 8 >> lod texels per unit
    int probe = -1;         // its baked-light ProbeRecord in the DrawList (-1: none)
    // Light of its own (a crystal): the raster adds albedo x tint x glow to what the texel
    // passes lit (the box's colour is the tint), as a glowing box adds colour x emissive.
    float glow = 0.0f;
    // It moves between frames (the player): baked lights reach it in the realtime texel
    // pass, and it neither receives nor casts anything in the bake (TexelWorld).
    bool moves = false;
};

struct DrawList {
    std::vector<BoxInstance> boxes;
    std::vector<ProbeRecord> probes; // lit_probes boxes' records
    // texel_lit boxes' models, indexed by the boxes' `emissive` (the application lights them
    // and hands their records to WorldView::texel_records in the same order).
    std::vector<TexelPart> texel_parts;
    // Drawn again after the boxes, only where something nearer hides them, as a checkerboard
    // of their colour (the player's silhouette behind walls). Material and emission unused.
    std::vector<BoxInstance> xray;
    // Boxes drawn after the x-ray pass, as `boxes` are (records alike): the player's own
    // parts, so that its backpack in front of its body does not make the silhouette show.
    std::vector<BoxInstance> late;
};

// Building blocks for a DrawList.
// The ground over [min, max] (world x, z): a box of zero height at y = 0, top face only.
BoxInstance ground_box(glm::vec2 min, glm::vec2 max, glm::vec3 color);
// One wall box per wall tile in [min_tile, max_tile) from the ground up to `height`, each with
// only the faces that border air (interior faces are never seen; a tile walled in on all
// four sides keeps its top).
void append_wall_boxes(DrawList& list, const IsWall& is_wall, glm::ivec2 min_tile, glm::ivec2 max_tile,
                       float height, glm::vec3 color);

// A named palette of 2..16 colours, sRGB-encoded in [0, 1] (hex / 255: how palettes are
// authored), applied by nearest colour.
struct Palette {
    const char* name = "";
    std::vector<glm::vec3> colors;
};
inline constexpr int max_palette_colors = 16;

// The built-in palettes, indexed by ArtSettings::palette: 0 "off" (no colours: no palette
// swap; a HUD can list the names as they are), 1 "cave" (12 warm browns and ambers with a
// little cold blue), 2 "gameboy" (the four greens), 3 "pico" (PICO-8's 16), 4 "dusk" (8
// purples, blues and oranges).
std::span<const Palette> builtin_palettes();

// The pixel-art controls, applied after tone mapping in this order: dither, posterize,
// palette. All of them work on the sRGB-encoded colour (what the player sees: posterize N
// gives N evenly spaced encoded levels), which is converted back to linear for the sRGB
// target to re-encode.
struct ArtSettings {
    int posterize = 0;          // 0 off, else levels per channel (clamped to 2..64)
    bool dither = false;        // 4x4 ordered (Bayer) dither before posterize/palette, by one
                                // quantisation step (posterize), 1/8 (palette only) or
                                // 1/255 (neither: de-banding the 8-bit target)
    int palette = 0;            // index into builtin_palettes() (0: off; out of range: off):
                                // nearest colour by weighted (2, 4, 3) distance in
                                // sRGB-encoded space
    bool texture_pattern = true; // the procedural per-texel pixel-art pattern (tests turn it off)
};

// Seed 002's runtime knobs on the bounce light a surface reflects (live sliders: no re-bake,
// nothing recomputed but the raster). The GI's indirect light (live and baked) reaches a
// surface of albedo a as
//   b = indirect, less (1 - self) x its part along the chroma of a (a - mean(a), unit
//       length) where that part is positive, kept non-negative;
//   reflected = b x mix(a, 1, bleed).
// self = 1, bleed = 0 (the defaults) is the physical albedo x indirect. Lower `self`: an
// orange wall no longer piles its own orange onto itself, while cross-colour bounce and the
// light's brightness (the chroma has mean 0) stay; higher `bleed`: dark surfaces pick up
// their neighbours' colour. One set for the world (ground, walls) and one for characters
// and decorations (everything else that is lit), as the seed splits them.
struct BounceStyle {
    float self = 1.0f;  // [0, 1]
    float bleed = 0.0f; // [0, 1]
    friend bool operator==(const BounceStyle&, const BounceStyle&) = default;
};
// The bounce light `bounce` as a surface of albedo `albedo` reflects it under `style` (the C++
// twin of game_world.frag's reflected_bounce). A lit face shows
// max(albedo x direct + reflected_bounce(...), 0) + emission when the style is not the default.
glm::vec3 reflected_bounce(const BounceStyle& style, glm::vec3 bounce, glm::vec3 albedo);

struct WorldView {
    scene::PerspectiveCamera camera;           // the tilted top-down camera (game::follow_camera)
    const gi::FrameInputs* gi = nullptr;       // this frame's GI inputs; nullptr: no GI (lit
                                               // surfaces black, emission still shows)
    const gi::vk::Renderer* renderer = nullptr; // the GI textures, prepared and recorded for `gi`
                                               // earlier in the same command list (or an earlier
                                               // submission); nullptr: no GI
    ArtSettings art;
    BounceStyle world_bounce;     // ground and walls
    BounceStyle character_bounce; // props, the player, trees, texel-lit models
    GiDebugView gi_view = GiDebugView::lit; // a texture this frame lacks (the method has no such
                                            // pass) draws the lit scene
    float time = 0.0f; // seconds; unused for now (no animated glow: output is a function of the view)
    // The per-texel light (texel::vk::TexelPasses, recorded earlier in the same command list):
    // its lit() and surfaces() buffers, the albedo of every atlas texel (vec4 each) and the
    // texel_lit boxes' records (DrawList::texel_parts' order). Any missing: texel_lit boxes
    // are drawn as props.
    const gpu::Buffer* texel_lit = nullptr;
    const gpu::Buffer* texel_surfaces = nullptr;
    const gpu::Buffer* texel_albedo = nullptr;
    std::span<const TexelRecord> texel_records;
};

class WorldRenderer {
  public:
    // Pipelines and buffers for a target of `size` pixels. An error when the device was
    // created without DeviceOptions::graphics.
    static Result<std::unique_ptr<WorldRenderer>> create(gpu::Device& device, glm::ivec2 size = {480, 270});
    ~WorldRenderer();
    WorldRenderer(const WorldRenderer&) = delete;
    WorldRenderer& operator=(const WorldRenderer&) = delete;

    // Records the world into target(): a barrier after the GI compute (and transfer) writes,
    // the box and frame-constant uploads, then one rendering scope: clear, the visible faces
    // in one draw per face group (one pipeline each; the descriptors pushed once; ground
    // last so walls reject the floor behind them early), the art controls in the fragment
    // shader. Outside any rendering scope; the caller submits.
    // The target's colour image is left in TRANSFER_SRC_OPTIMAL (render::RenderTarget).
    void record(gpu::CommandList& cmd, const WorldView& view, const DrawList& list);

    render::RenderTarget& target();
    // A new target of `size` pixels (the pipelines are kept: they depend on its formats only);
    // the old one is destroyed once the frames in flight that use it have finished. Nothing
    // happens when the size is unchanged; an empty size is refused.
    Result<void> resize(glm::ivec2 size);
    // Box faces the last record() drew: in the view, in their box's mask and turned towards
    // the camera (the HUD shows it; the rest never reach the GPU).
    std::size_t faces_drawn() const;
    // The GI view the last record() drew (lit when the view asked for was not in the frame).
    GiDebugView gi_view_drawn() const;

    // The view-projection the raster uses: right-handed look-at with world +y as the up hint
    // (the basis of game::camera_ray and gi::visible_area), vertical fov_deg, aspect =
    // width / height, depth 0..1 from near_plane to far_plane, and y flipped for Vulkan clip
    // space (y down in the framebuffer). A world point projected with it lands on the pixel
    // whose camera_ray (ndc = pixel / size, y down) passes through the point.
    static glm::mat4 view_projection(const scene::PerspectiveCamera& camera);
    static constexpr float near_plane = 0.1f;
    static constexpr float far_plane = 1000.0f;

  private:
    struct Impl;
    explicit WorldRenderer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

} // namespace lantern::game

// The GI window: the world rectangle the GI textures cover, phase-locked to whole tiles
// (gi.window_snap "tile", the default) or to texel boundaries ("texel").
//
// Conventions (every pass, C++ and GLSL): CameraView = (min_x, min_z, width, height) in
// world units; texel (i, j) covers [min_x + i/res, min_x + (i+1)/res) x [min_z + j/res, ...);
// its centre is (floor(p * res) + 0.5) / res for any p inside it; row 0 is at min_z.
// min_x and min_z are whole texels (whole tiles when snapping to tiles), and width/height
// are the texture size divided by res (whole tiles), so the texel grid lines up with tile
// boundaries exactly either way; a pass that needs a texel's tile takes it from the global
// texel index round(min_x * res) + i (window_texel_origin).
#pragma once

#include "lantern/scene/scene.hpp"

#include <glm/vec2.hpp>
#include <glm/ext/vector_int2.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace lantern::gi {

struct CameraView {
    float min_x = 0.0f, min_z = 0.0f, width = 0.0f, height = 0.0f;
    friend bool operator==(const CameraView&, const CameraView&) = default;
};

struct GiWindow {
    CameraView view;
    int resolution = 1; // texels per world unit
    int width = 0;      // texels
    int height = 0;

    glm::vec2 texel_center(int i, int j) const {
        return {view.min_x + (float(i) + 0.5f) / float(resolution), view.min_z + (float(j) + 0.5f) / float(resolution)};
    }
    glm::vec2 center() const { return {view.min_x + view.width * 0.5f, view.min_z + view.height * 0.5f}; }
    friend bool operator==(const GiWindow&, const GiWindow&) = default;
};

// A hash of everything that places the window (its cache-key input).
std::uint64_t hash_window(const GiWindow& w);

inline constexpr int min_texture_size = 64;

// The visible ground rectangle (min corner and size, world units) before padding, or
// nullopt when it cannot be computed: a corner ray parallel to the ground (|dir.y| < 1e-4),
// hitting it behind the camera, or any non-finite value. `reason` says which.
struct VisibleArea {
    glm::vec2 min{0.0f};
    glm::vec2 size{0.0f};
};
std::optional<VisibleArea> visible_area(const scene::ViewSpec& view, std::string* reason = nullptr);

// Pads the visible area around its centre, phase-locks the origin to whole tiles and sizes
// the textures: ceil(size * res), snapped up to a multiple of res, at least 64 texels.
// nullopt (no GI this frame, never a crash) when the visible area is unavailable or the
// result is not finite. Texture sizes above max_texels per side are reported through
// `reason` too (the caller decides whether that is an error).
// `snap_texels`: the origin's lock in texels (res: whole tiles; 0 means res).
// `margin_tiles`: whole tiles added on every side after that (gi.gather.margin).
std::optional<GiWindow> compute_window(const scene::ViewSpec& view, float padding, int resolution,
                                       std::string* reason = nullptr, int max_texels = 1 << 16, int snap_texels = 0,
                                       int margin_tiles = 0);
// The window of a scene's gi settings: padding, resolution, gi.window_snap ("texel" locks
// to min(res, heat scale) texels, so heat texels stay whole) and, for gi.method = gather,
// gi.gather.margin.
std::optional<GiWindow> compute_window(const scene::ViewSpec& view, const scene::GiSettings& gi,
                                       std::string* reason = nullptr, int max_texels = 1 << 16);
// The texels the lock steps by for these settings.
int window_snap_texels(const scene::GiSettings& gi);
// The global index of the window's first texel column and row: round(min * res).
glm::ivec2 window_texel_origin(const GiWindow& w);

// Whether every block of 4 x block_h window texels (a GI pass's invocation, 4-aligned in x
// and block_h-aligned in z) lies in one wall tile, with every texel centre exact in float
// as the shaders compute it: the resolution a power of two that 4 and block_h divide, the
// window's texel origin whole and a multiple of 4 in x and of block_h in z, and every
// texel index of the window within 2^22. The passes that need a texel's tile then look it
// up once a block (their FEATURES bit; docs/gi.md, "Wall indirect").
bool blocks_in_one_tile(const GiWindow& w, std::uint32_t block_h);

} // namespace lantern::gi

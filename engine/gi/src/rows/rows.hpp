// The rows of the built-in GI methods (pass_table.hpp), defined beside their recorders:
// direct_light.cpp (conduction, ao, direct, directional), indirect_light.cpp (emission,
// heat, blur, wall_indirect), radiosity.cpp (distance_field, radiosity) and lit_image.cpp (lit). Constant-initialised, so the method
// lists in pass_table.cpp can point at them from any translation unit.
#pragma once

#include "lantern/core/hash.hpp"
#include "lantern/gi/pass_table.hpp"
#include "lantern/gi/reference_indirect.hpp"
#include "lantern/gi/vulkan/pass_recorder.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <span>
#include <vector>

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
extern const PassRow gather;
extern const PassRow mixed;
extern const PassRow baked_sample;
extern const PassRow baked;
extern const PassRow probes;

// Records the upsample of a grid texture (heat, radiosity) into Tex::indirect (gi_upsample);
// `heat_mask`: the grid is the heat grid, whose walls the tap masks (Tex::heat_mask) mark.
void record_upsample(vk::PassRecorder& r, Tex src, const HeatGrid& grid, bool heat_mask = false);

// Adds to `h` the GI window and the walls in it: what a row's kept work (the direct pass's
// light bins, the heat row's tap masks) depends on besides its own inputs.
Hasher& add_window_and_walls(Hasher& h, const FrameInputs& in);

// The workgroup grid of a block pass over a texture of this pitch and height (Renderer's
// dispatch_blocks: blocks of 4 x block_h texels, group_x x group_y blocks a workgroup).
struct WorkgroupGrid {
    std::uint32_t x = 0, y = 0;
};
WorkgroupGrid workgroup_grid(const vk::PassRecorder& r, int pitch, int height);

// Light bins (docs/gi.md, "Dirty light bins"): per bin (row-major, bins_x x bins_y of bin_w x
// bin_h texels, a block pass's workgroups), a hash of the lights that can reach one of its
// texels, in index order (points, then emissives: the direct pass's order), or no_light_bin
// where none can: there the direct pass writes no light, and the mixed set holds zeros.
inline constexpr std::uint64_t no_light_bin = 0x62696e73ull;
std::vector<std::uint64_t> bin_lights(std::span<const GpuPointLight> points, std::span<const GpuPointLight> emissives,
                                      const GiWindow& w, std::uint32_t bins_x, std::uint32_t bins_y, float bin_w, float bin_h);

// The workgroups of `grid` (a block pass over the window's textures) in which the baked row
// adds the mixed set into the direct textures: those a mixed point light or emissive can
// reach (the mixed set is zero elsewhere), or nullopt for all of them (a mixed sun, a
// renderer without dirty bins, more than one dispatch row holds). Defined in baked.cpp.
std::optional<std::vector<std::uint32_t>> mixed_add_bins(const vk::PassRecorder& r, WorkgroupGrid grid);

// Scrolling a window-keyed row's outputs at a window step (docs/gi.md, "Scrolling at a window
// step"; scroll.cpp). For rows whose texel depends on its world point and the walls within
// `margin` tiles of its tile alone, never on where the window lies: when the window steps by
// whole texels and nothing else changed, the texels both windows hold are the last run's,
// shifted, and only the new strips need computing. Exact when every texel centre is exact in
// float (a power-of-two resolution, an origin on the half-texel grid, coordinates that need
// no rounding), so that a texel's world point is the same number from either origin.
struct WindowScroll {
    // The last run: everything its outputs depend on but the window's origin and the walls (0:
    // nothing to scroll from), its window, and the wall cells of its tiles and `margin` around.
    std::uint64_t content = 0;
    GiWindow window;
    glm::ivec2 cells_lo{0}, cells_size{0};
    std::vector<std::uint8_t> cells;
    gpu::Buffer scratch; // the shift's intermediate copy
};
// Whether this run may scroll from the last (the same `content` and `outputs` (their identity,
// pitch and size), walls within `margin` tiles of the shared texels, exact texel centres, a
// shift by whole texels that are multiples of `align` and smaller than the window, a renderer
// with partial recording); then `shift` is the texels the window moved by. Records this run
// as the last either way.
bool scroll_from_last(vk::PassRecorder& r, WindowScroll& s, std::uint64_t content, std::span<const Tex> outputs, int margin,
                      glm::ivec2 align, glm::ivec2& shift);
// Moves each output's texels (`texel_bytes` each, in a buffer of its pitch) by `shift`: texel
// (x, y) receives the old (x + shift.x, y + shift.y). The texels outside the shared part
// receive other texels' values: the caller computes them again.
void shift_outputs(vk::PassRecorder& r, WindowScroll& s, std::span<const Tex> outputs, glm::ivec2 shift, VkDeviceSize texel_bytes);
// Records a scrolling row's work and counts its workgroups: without `scrolls`, one dispatch
// over the window; with it, the outputs shifted (shift_outputs) and the new strips, the
// columns the window moved into (every row) and then the rows (every column), each from a
// multiple of `x_align` texels. `at(x0, y0)` sets the row's parameters for a dispatch from
// texel (x0, y0); a dispatch rounds up to whole workgroups, and the shared texels it covers
// beyond its strip are written again with the value they hold.
template <typename At>
void dispatch_scrolled(vk::PassRecorder& r, WindowScroll& s, bool scrolls, glm::ivec2 shift, std::span<const Tex> outputs,
                       VkDeviceSize texel_bytes, int x_align, At&& at) {
    const GiWindow& w = r.in.window;
    const std::uint64_t all = r.dispatch_groups(w.width, w.height);
    if (!scrolls) {
        at(0, 0);
        r.dispatch(w.width, w.height);
        r.count_workgroups(all, all);
        return;
    }
    shift_outputs(r, s, outputs, shift, texel_bytes);
    std::uint64_t recorded = 0;
    auto strip = [&](int x0, int y0, int width, int height) {
        const int from = x0 / x_align * x_align;
        at(from, y0);
        r.dispatch(width + (x0 - from), height);
        recorded += r.dispatch_groups(width + (x0 - from), height);
    };
    if (shift.x != 0) strip(shift.x > 0 ? w.width - shift.x : 0, 0, std::abs(shift.x), w.height);
    if (shift.y != 0) strip(0, shift.y > 0 ? w.height - shift.y : 0, w.width, std::abs(shift.y));
    r.count_workgroups(all, recorded);
}

// The blocks of the window's texels (4 x block_h, as x | y << 16, row-major) that hold a
// wall texel, or nullopt when every block does or there are more than `most`. A wall face's
// light is zero elsewhere: the passes that write face textures write zeros off wall texels.
// A texel's tile is its centre's (GiWindow::texel_center, texel_center in gi_common.glsl); a
// block is listed when any tile within 1e-3 of its texels' centres is a wall, so that a centre
// rounded differently on a GPU lists a block too many, never too few.
std::optional<std::vector<std::uint32_t>> wall_blocks(const FrameInputs& in, int block_h, std::uint64_t most);

// A host-built table in a texel buffer (or with VK_FORMAT_UNDEFINED a storage buffer), grown
// as needed.
struct UploadedArray {
    gpu::Buffer buffer;
    gpu::BufferView view;
};

template <typename T>
void upload_array(vk::PassRecorder& r, UploadedArray& a, std::span<const T> data, VkFormat format, const char* name) {
    const VkDeviceSize bytes = (VkDeviceSize(data.size_bytes()) + 15) & ~VkDeviceSize(15);
    if (!a.buffer || a.buffer.size() < bytes) {
        gpu::BufferDesc desc;
        desc.size = std::max<VkDeviceSize>(bytes + bytes / 4, 16); // room to grow
        desc.usage = format == VK_FORMAT_UNDEFINED ? VK_BUFFER_USAGE_STORAGE_BUFFER_BIT : VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
        desc.name = name;
        a.buffer = r.device().create_buffer(desc);
        if (format != VK_FORMAT_UNDEFINED) a.view = r.device().create_buffer_view(a.buffer, format, 0, VK_WHOLE_SIZE, name);
    }
    r.cmd.upload(a.buffer, 0, std::as_bytes(data));
}

// Uploads a list of workgroups or blocks into `a` (a storage buffer), or, without one, a
// stand-in to bind where the shader reads none, unless `a` already holds a buffer.
inline void upload_list(vk::PassRecorder& r, UploadedArray& a, const std::vector<std::uint32_t>* list, const char* name) {
    if (!list && a.buffer) return;
    const std::uint32_t stand_in = 0;
    upload_array(r, a, list ? std::span<const std::uint32_t>(*list) : std::span(&stand_in, 1), VK_FORMAT_UNDEFINED, name);
    r.cmd.barrier_transfer_to_compute();
}

// Dispatches one invocation per entry of a list of `blocks` blocks (wall_blocks; the
// shaders' listed_block_index), in one dimension of whole workgroups; returns how many.
inline std::uint64_t dispatch_listed_blocks(vk::PassRecorder& r, std::size_t blocks) {
    const std::uint64_t per_group = std::uint64_t(r.group_x()) * r.group_y();
    const std::uint64_t groups = (std::uint64_t(blocks) + per_group - 1) / per_group;
    if (groups > 0) r.cmd.dispatch(std::uint32_t(groups), 1);
    return groups;
}

} // namespace lantern::gi::rows

// Scrolling a window-keyed row's outputs at a window step (rows.hpp WindowScroll; docs/gi.md,
// "Scrolling at a window step"), and the window's blocks that hold a wall texel (wall_blocks).
#include "rows/rows.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <vector>

namespace lantern::gi::rows {

using vk::PassRecorder;

namespace {

// Whether `w`'s texel centres (min + (i + 0.5) / res in float: GiWindow::texel_center, the
// shaders' grid_texel_center) are exact: a power-of-two resolution, an origin on the
// half-texel grid, and coordinates that need no rounding.
bool exact_texel_centres(const GiWindow& w) {
    const int res = w.resolution;
    if (res <= 0 || (res & (res - 1)) != 0 || w.width <= 0 || w.height <= 0) return false;
    const double scale = 2.0 * res;
    const double lo_x = double(w.view.min_x), lo_z = double(w.view.min_z);
    if (!std::isfinite(lo_x) || !std::isfinite(lo_z) || lo_x * scale != std::floor(lo_x * scale) ||
        lo_z * scale != std::floor(lo_z * scale))
        return false;
    const double far = std::max({std::abs(lo_x), std::abs(lo_z), std::abs(lo_x + double(w.width) / res),
                                 std::abs(lo_z + double(w.height) / res)});
    return far * scale < double(1 << 23) && w.width < 0x8000 && w.height < 0x8000;
}

// The wall cells of the window's tiles and `margin` tiles around them, into s.
void keep_cells(WindowScroll& s, const FrameInputs& in, int margin) {
    const GiWindow& w = in.window;
    s.cells_lo = glm::ivec2(int(std::floor(w.view.min_x)) - margin, int(std::floor(w.view.min_z)) - margin);
    const glm::ivec2 hi(int(std::floor(double(w.view.min_x) + double(w.width) / w.resolution)) + margin,
                        int(std::floor(double(w.view.min_z) + double(w.height) / w.resolution)) + margin);
    s.cells_size = hi - s.cells_lo + 1;
    s.cells.resize(std::size_t(s.cells_size.x) * std::size_t(s.cells_size.y));
    for (int z = 0; z < s.cells_size.y; ++z)
        for (int x = 0; x < s.cells_size.x; ++x)
            s.cells[std::size_t(z) * std::size_t(s.cells_size.x) + std::size_t(x)] = in.walls.cell(s.cells_lo.x + x, s.cells_lo.y + z);
}

// Whether the walls hold the kept cells where the kept rectangle and the window's (with its
// margin) meet: every tile a shared texel's value depends on.
bool same_walls(const WindowScroll& s, const FrameInputs& in, int margin) {
    const GiWindow& w = in.window;
    const glm::ivec2 lo(std::max(s.cells_lo.x, int(std::floor(w.view.min_x)) - margin),
                        std::max(s.cells_lo.y, int(std::floor(w.view.min_z)) - margin));
    const glm::ivec2 hi(std::min(s.cells_lo.x + s.cells_size.x - 1, int(std::floor(double(w.view.min_x) + double(w.width) / w.resolution)) + margin),
                        std::min(s.cells_lo.y + s.cells_size.y - 1, int(std::floor(double(w.view.min_z) + double(w.height) / w.resolution)) + margin));
    for (int z = lo.y; z <= hi.y; ++z)
        for (int x = lo.x; x <= hi.x; ++x)
            if (s.cells[std::size_t(z - s.cells_lo.y) * std::size_t(s.cells_size.x) + std::size_t(x - s.cells_lo.x)] != in.walls.cell(x, z))
                return false;
    return true;
}

} // namespace

bool scroll_from_last(PassRecorder& r, WindowScroll& s, std::uint64_t content, std::span<const Tex> outputs, int margin,
                      glm::ivec2 align, glm::ivec2& shift) {
    const FrameInputs& in = r.in;
    const GiWindow& w = in.window, old = s.window;
    Hasher h(content);
    for (const Tex t : outputs) h.add(std::uint32_t(t)).add(r.serial(t)).add(r.pitch(t)).add(r.buffer(t).size());
    content = h.value() | 1; // 0 is "nothing to scroll from"
    bool scrolls = r.dirty_bins() && s.content == content && old.resolution == w.resolution && old.width == w.width &&
                   old.height == w.height && exact_texel_centres(old) && exact_texel_centres(w);
    if (scrolls) {
        const double dx = (double(w.view.min_x) - double(old.view.min_x)) * w.resolution,
                     dz = (double(w.view.min_z) - double(old.view.min_z)) * w.resolution;
        scrolls = dx == std::floor(dx) && dz == std::floor(dz) && std::abs(dx) < w.width && std::abs(dz) < w.height;
        if (scrolls) {
            shift = glm::ivec2(int(dx), int(dz));
            scrolls = shift.x % align.x == 0 && shift.y % align.y == 0 && same_walls(s, in, margin);
        }
    }
    s.content = content;
    s.window = w;
    keep_cells(s, in, margin);
    return scrolls;
}

void shift_outputs(PassRecorder& r, WindowScroll& s, std::span<const Tex> outputs, glm::ivec2 shift, VkDeviceSize texel_bytes) {
    if (shift == glm::ivec2(0)) return;
    VkDeviceSize most = 0;
    for (const Tex t : outputs) most = std::max(most, r.buffer(t).size());
    if (!s.scratch || s.scratch.size() < most) {
        gpu::BufferDesc desc;
        desc.size = most;
        desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
        desc.name = "gi window scroll";
        s.scratch = r.device().create_buffer(desc);
    }
    // Texel (x, y) of the new window is (x + dx, y + dy) of the old: one shift of the whole
    // buffer by dy x pitch + dx texels, through the scratch buffer (a copy may not overlap
    // itself). The texels it wraps into are the new strips'.
    r.cmd.barrier_compute_to_transfer();
    for (const Tex t : outputs) {
        const gpu::Buffer& buffer = r.buffer(t);
        const std::int64_t by = (std::int64_t(shift.y) * r.pitch(t) + shift.x) * std::int64_t(texel_bytes);
        const VkDeviceSize size = buffer.size() - VkDeviceSize(std::abs(by));
        r.cmd.copy_buffer(buffer, by > 0 ? VkDeviceSize(by) : 0, s.scratch, 0, size);
        r.cmd.barrier_transfer_to_transfer();
        r.cmd.copy_buffer(s.scratch, 0, buffer, by < 0 ? VkDeviceSize(-by) : 0, size);
        r.cmd.barrier_transfer_to_transfer();
    }
    r.cmd.barrier_transfer_to_compute();
}

std::optional<std::vector<std::uint32_t>> wall_blocks(const FrameInputs& in, int block_h, std::uint64_t most) {
    const GiWindow& w = in.window;
    const int blocks_x = (w.width + 3) / 4, blocks_y = (w.height + block_h - 1) / block_h;
    if (blocks_x > 65536 || blocks_y > 65536) return std::nullopt;
    constexpr float margin = 1e-3f;
    auto cells = [&](int first, int last, int axis) {
        const float lo = axis == 0 ? w.texel_center(first, 0).x : w.texel_center(0, first).y;
        const float hi = axis == 0 ? w.texel_center(last, 0).x : w.texel_center(0, last).y;
        return glm::ivec2(int(std::floor(lo - margin)), int(std::floor(hi + margin)));
    };
    std::vector<glm::ivec2> columns(static_cast<std::size_t>(blocks_x)), rows_z(static_cast<std::size_t>(blocks_y));
    for (int bx = 0; bx < blocks_x; ++bx) columns[std::size_t(bx)] = cells(4 * bx, std::min(4 * bx + 3, w.width - 1), 0);
    for (int by = 0; by < blocks_y; ++by)
        rows_z[std::size_t(by)] = cells(by * block_h, std::min(by * block_h + block_h - 1, w.height - 1), 1);
    std::vector<std::uint32_t> list;
    for (int by = 0; by < blocks_y; ++by)
        for (int bx = 0; bx < blocks_x; ++bx) {
            const glm::ivec2 cx = columns[std::size_t(bx)], cz = rows_z[std::size_t(by)];
            bool wall = false;
            for (int z = cz.x; z <= cz.y && !wall; ++z)
                for (int x = cx.x; x <= cx.y && !wall; ++x) wall = in.walls.is_wall(x, z);
            if (wall) list.push_back(std::uint32_t(bx) | std::uint32_t(by) << 16);
        }
    if (list.size() == std::size_t(blocks_x) * std::size_t(blocks_y) || list.size() > most) return std::nullopt;
    return list;
}


} // namespace lantern::gi::rows

#include "lantern/gi/window.hpp"

#include "lantern/core/hash.hpp"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace lantern::gi {
namespace {

bool finite(glm::vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

void set_reason(std::string* reason, const char* text) {
    if (reason) *reason = text;
}

std::optional<VisibleArea> ortho_area(const scene::OrthoView& v, std::string* reason) {
    if (!finite(v.center) || !finite(v.size) || v.size.x <= 0.0f || v.size.y <= 0.0f) {
        set_reason(reason, "view centre or size is not finite and positive");
        return std::nullopt;
    }
    return VisibleArea{v.center - v.size * 0.5f, v.size};
}

std::optional<VisibleArea> camera_area(const scene::PerspectiveCamera& c, std::string* reason) {
    const std::optional<scene::GroundArea> ground = scene::ground_footprint(c, reason);
    if (!ground) return std::nullopt;
    return VisibleArea{ground->min, ground->size};
}

} // namespace

std::optional<VisibleArea> visible_area(const scene::ViewSpec& view, std::string* reason) {
    return std::visit(
        [&](const auto& v) -> std::optional<VisibleArea> {
            if constexpr (std::is_same_v<std::decay_t<decltype(v)>, scene::OrthoView>)
                return ortho_area(v, reason);
            else
                return camera_area(v, reason);
        },
        view);
}

std::optional<GiWindow> compute_window(const scene::ViewSpec& view, float padding, int resolution,
                                       std::string* reason, int max_texels, int snap_texels, int margin_tiles) {
    auto area = visible_area(view, reason);
    if (!area) return std::nullopt;
    const int res = std::max(1, resolution);
    const double center_x = double(area->min.x) + double(area->size.x) * 0.5;
    const double center_z = double(area->min.y) + double(area->size.y) * 0.5;
    const double size_x = double(area->size.x) * double(padding);
    const double size_z = double(area->size.y) * double(padding);
    const double min_x = center_x - size_x * 0.5, min_z = center_z - size_z * 0.5;
    // Phase lock: the origin snaps down to a whole tile (res texels) or to `snap` texels.
    const double snap = snap_texels > 0 ? double(snap_texels) : double(res);
    const double tex_x = std::floor(min_x * res), tex_z = std::floor(min_z * res);
    const double snapped_x0 = std::floor(tex_x / snap) * snap, snapped_z0 = std::floor(tex_z / snap) * snap;
    // Size: whole texels, then whole tiles, then the 64-texel minimum.
    double w = std::ceil(size_x * res), h = std::ceil(size_z * res);
    w = std::max(std::ceil(w / res) * res, double(min_texture_size));
    h = std::max(std::ceil(h / res) * res, double(min_texture_size));
    // A margin of whole tiles on every side (the gather method's domain, as the transport
    // reference's): the phase is kept.
    const double margin = double(std::max(0, margin_tiles)) * res;
    const double snapped_x = snapped_x0 - margin, snapped_z = snapped_z0 - margin;
    w += 2.0 * margin;
    h += 2.0 * margin;
    if (!std::isfinite(snapped_x) || !std::isfinite(snapped_z) || !std::isfinite(w) || !std::isfinite(h)) {
        set_reason(reason, "the GI window is not finite");
        return std::nullopt;
    }
    if (w > max_texels || h > max_texels) {
        set_reason(reason, "the GI window is larger than the texture size limit");
        return std::nullopt;
    }
    GiWindow win;
    win.resolution = res;
    win.width = int(w);
    win.height = int(h);
    win.view = CameraView{float(snapped_x / res), float(snapped_z / res), float(w / res), float(h / res)};
    return win;
}

int window_snap_texels(const scene::GiSettings& gi) {
    const int res = std::max(1, gi.resolution);
    if (gi.window_snap == scene::WindowSnap::tile) return res;
    // The indirect grid's texels (1, 2 or 4 window texels) stay whole.
    const int grid = gi.method == scene::GiMethod::radiosity ? int(gi.radiosity.scale)
                     : gi.method == scene::GiMethod::gather  ? int(gi.gather.scale)
                                                             : int(gi.heat_scale);
    return std::min(res, grid);
}

std::optional<GiWindow> compute_window(const scene::ViewSpec& view, const scene::GiSettings& gi, std::string* reason,
                                       int max_texels) {
    const int margin = gi.method == scene::GiMethod::gather ? gi.gather.margin : 0;
    return compute_window(view, gi.padding, gi.resolution, reason, max_texels, window_snap_texels(gi), margin);
}

glm::ivec2 window_texel_origin(const GiWindow& w) {
    return {int(std::lround(double(w.view.min_x) * w.resolution)), int(std::lround(double(w.view.min_z) * w.resolution))};
}

bool blocks_in_one_tile(const GiWindow& w, std::uint32_t block_h) {
    const int res = w.resolution;
    if (res < 4 || (res & (res - 1)) != 0 || block_h == 0 || res % int(block_h) != 0) return false;
    // The texel origin: min * res is exact for a power of two; it must be a whole number.
    const double tx = double(w.view.min_x) * res, tz = double(w.view.min_z) * res;
    constexpr double limit = double(1 << 22); // centres (t + i + 0.5) / res exact in a float
    if (!(std::abs(tx) + w.width < limit && std::abs(tz) + w.height < limit)) return false;
    if (tx != std::floor(tx) || tz != std::floor(tz)) return false;
    const auto x = std::int64_t(tx), z = std::int64_t(tz);
    return x % 4 == 0 && z % std::int64_t(block_h) == 0;
}

std::uint64_t hash_window(const GiWindow& w) {
    return Hasher().add(w.view.min_x).add(w.view.min_z).add(w.view.width).add(w.view.height).add(w.width)
        .add(w.height).add(w.resolution).value();
}

} // namespace lantern::gi

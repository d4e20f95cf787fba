// Rows of the direct-light passes (seed 000): conduction, ambient occlusion, point and
// emissive lights ("DDA"), directional lights ("DDA_Directional"). Each row: its textures,
// settings and inputs, its Vulkan recorder and its C++ reference.
#include "rows/rows.hpp"

#include "lantern/core/hash.hpp"
#include "lantern/gi/point_map.hpp"
#include "lantern/gi/sun_map.hpp"
#include "lantern/gi/vulkan/pass_recorder.hpp"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <array>
#include <cstring>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

namespace lantern::gi::rows {
namespace {

using vk::PassRecorder;

constexpr Tex direct_set[] = {Tex::direct, Tex::shadow, Tex::wall_direct_px, Tex::wall_direct_nx, Tex::wall_direct_pz, Tex::wall_direct_nz};
// The realtime suns alone: the directional pass writes them, the direct pass adds them.
constexpr Tex sun_set[] = {Tex::direct_sun,         Tex::shadow_sun,         Tex::wall_direct_sun_px,
                           Tex::wall_direct_sun_nx, Tex::wall_direct_sun_pz, Tex::wall_direct_sun_nz};

constexpr Tex upper_set[] = {Tex::wall_upper_px, Tex::wall_upper_nx, Tex::wall_upper_pz, Tex::wall_upper_nz};
constexpr Tex upper_sun_set[] = {Tex::wall_upper_sun_px, Tex::wall_upper_sun_nx, Tex::wall_upper_sun_pz,
                                 Tex::wall_upper_sun_nz};
// The mixed lights alone (a bake is used): written by the mixed pass, added by the baked pass.
constexpr Tex mixed_set[] = {Tex::direct_mixed,         Tex::shadow_mixed,         Tex::wall_direct_mixed_px,
                             Tex::wall_direct_mixed_nx, Tex::wall_direct_mixed_pz, Tex::wall_direct_mixed_nz};
constexpr Tex upper_mixed_set[] = {Tex::wall_upper_mixed_px, Tex::wall_upper_mixed_nx, Tex::wall_upper_mixed_pz,
                                   Tex::wall_upper_mixed_nz};
// The mixed suns alone: written by the mixed pass beside the mixed lights' set, added by the
// baked pass after it.
constexpr Tex mixed_sun_set[] = {Tex::direct_mixed_sun,         Tex::shadow_mixed_sun,
                                 Tex::wall_direct_mixed_sun_px, Tex::wall_direct_mixed_sun_nx,
                                 Tex::wall_direct_mixed_sun_pz, Tex::wall_direct_mixed_sun_nz};
constexpr Tex upper_mixed_sun_set[] = {Tex::wall_upper_mixed_sun_px, Tex::wall_upper_mixed_sun_nx,
                                       Tex::wall_upper_mixed_sun_pz, Tex::wall_upper_mixed_sun_nz};

// The upper-face textures that go with a set (unfolded proxy shadows).
std::span<const Tex> upper_outputs(std::span<const Tex> ids) {
    if (ids.data() == sun_set) return upper_sun_set;
    if (ids.data() == mixed_sun_set) return upper_mixed_sun_set;
    return ids.data() == mixed_set ? std::span<const Tex>(upper_mixed_set) : std::span<const Tex>(upper_set);
}

TexSet face_set(std::span<const Tex> ids, const FrameInputs& in) {
    TexSet set;
    set.add(ids[0]).add(ids[1]);
    const std::uint32_t faces = computed_faces(in.settings);
    const bool unfold = unfolds_proxy_shadows(in);
    for (int f = 0; f < 4; ++f)
        if (computes_face(faces, f)) {
            set.add(ids[std::size_t(2 + f)]);
            if (unfold) set.add(upper_outputs(ids)[std::size_t(f)]);
        }
    return set;
}

// The direct pass writes the contract set (the colour, the shadow map, the faces computed:
// computed_faces); the directional pass the suns' own set, which the direct pass reads.
TexSet direct_writes(const FrameInputs& in) { return face_set(direct_set, in); }
TexSet directional_writes(const FrameInputs& in) { return face_set(sun_set, in); }

void put_direct(ReferenceStore& store, std::span<const Tex> ids, DirectTextures d) {
    store.put(ids[0], std::move(d.direct));
    store.put(ids[1], std::move(d.shadow));
    for (std::size_t f = 0; f < 4; ++f) {
        if (d.wall_direct[f].width > 0) store.put(ids[2 + f], std::move(d.wall_direct[f]));
        if (d.wall_upper[f].width > 0) store.put(upper_outputs(ids)[f], std::move(d.wall_upper[f]));
    }
}

// An upper-face texture's buffer, or for one not stored the first output's (never written:
// the shader writes uppers only when its `upper` parameter is set, and then all computed).
const gpu::Buffer& upper_buffer(PassRecorder& r, std::span<const Tex> ids, int face) {
    const Tex t = upper_outputs(ids)[std::size_t(face)];
    return r.has(t) ? r.buffer(t) : r.buffer(ids[0]);
}

// A face texture's buffer, or for a face not computed the first output's: the shader never
// writes a face whose bit is clear in its `faces` parameter.
const gpu::Buffer& face_buffer(PassRecorder& r, std::span<const Tex> ids, int face) {
    const Tex t = ids[std::size_t(2 + face)];
    return r.has(t) ? r.buffer(t) : r.buffer(ids[0]);
}

// The parameters of each shader (GI_PASS_PARAMS, mirrored field by field; checked against
// the shader when its pipeline is created).
struct AoParams {
    float radius = 0, power = 0, strength = 0, dither = 0;
    std::int32_t range = 0;
    std::int32_t offset = 0; // the dispatch's first texel, x | y << 16
    std::int32_t pad1 = 0, pad2 = 0;
};
struct LightBinParams {
    std::int32_t bins_x = 0, bins_y = 0, words = 0, bin_w = 0, bin_h = 0, proxy_words = 0;
    float proxy_pad = 0;
    std::int32_t per_light = 0;
};
struct DirectParams {
    float light_softness = 0, face_exponent = 1;
    std::int32_t pad_f = 0; // (the faces computed: PipelineSpec::faces)
    float wall_height = 0;
    std::int32_t proxy_per_light = 0;
    std::int32_t bins_x = 0, bins_y = 0; // the workgroup grid (with feature_list: one workgroup per listed bin)
    std::int32_t list_first = 0;         // feature_list: the first listed bin this dispatch computes
};
struct DirectionalParams {
    float wall_height = 0, angle_scale = 0, face_exponent = 1;
    std::int32_t pad_f = 0; // (the faces computed: PipelineSpec::faces)
    std::int32_t pad0 = 0, pad1 = 0, pad2 = 0, pad3 = 0;
};
// FEATURES bits of the direct and directional shaders.
constexpr std::uint32_t feature_upper = 1;   // unfolded proxy shadows (unfolds_proxy_shadows)
constexpr std::uint32_t feature_sun_map = 2; // gi.sun_shadow_method shadow_map
constexpr std::uint32_t feature_point_map = 4; // gi.shadow_method shadow_map
constexpr std::uint32_t feature_linear_falloff = 8; // gi.light_softness 1: no pow (gi_direct.comp)
constexpr std::uint32_t feature_list = 16; // gi_direct.comp: one workgroup per listed bin (dirty light bins)
constexpr std::uint32_t feature_no_lights = 32; // gi_direct.comp: bins no light reaches (the light loops left out)
constexpr std::uint32_t feature_mixed_suns = 64; // gi_directional.comp: the mixed suns (else the realtime ones)
constexpr std::uint32_t feature_suns = 128; // gi_direct.comp: adds the realtime suns' own textures (sun_set)
constexpr std::uint32_t feature_linear_faces = 256; // gi.wall_face_exponent 1: no pow (wall_facing)

// The feature bits both the direct and the directional shaders take from the settings.
std::uint32_t face_features(const FrameInputs& in) {
    return in.settings.wall_face_exponent == 1.0f ? feature_linear_faces : 0u;
}

// The directional shader's FEATURES for a frame (also what the direct row prefetches).
std::uint32_t directional_features(const FrameInputs& in, bool sun_map) {
    return (unfolds_proxy_shadows(in) ? feature_upper : 0u) | (sun_map ? feature_sun_map : 0u) | face_features(in);
}

// ---- conduction

void record_conduction(PassRecorder& r) {
    const GiWindow& w = r.in.window;
    r.cmd.bind(r.pipeline("gi_conduction.comp", {.proxies = false}));
    r.cmd.push_descriptors(
        gpu::DescriptorWrites().uniform_texel_buffer(0, r.walls()).uniform_buffer(1, r.proxies()).storage_buffer(2, r.buffer(Tex::conduction)));
    r.cmd.push_constants(r.params(w.width, w.height));
    r.dispatch(w.width, w.height);
    r.cmd.barrier_compute_to_compute();
}

void reference_conduction_row(ReferenceContext& c) { c.store.put(Tex::conduction, reference_conduction(c.in, c.options)); }

// ---- ambient occlusion

// The AO weight table (AoKernel) on the GPU: uploaded when the resolution or the AO shape
// changes.
struct AoState : vk::PassState {
    gpu::Buffer kernel;
    gpu::BufferView view;
    std::tuple<int, float, float> key{0, 0.0f, 0.0f}; // resolution, radius, power
    int range = 0;
    WindowScroll scroll; // at a window step, the shared texels are shifted, not computed again
};

void record_ao(PassRecorder& r) {
    const GiWindow& w = r.in.window;
    const scene::AoSettings& settings = r.in.settings.ao;
    AoState& s = r.state<AoState>();
    const auto key = std::make_tuple(w.resolution, settings.radius, settings.power);
    if (!s.kernel || s.key != key) {
        const AoKernel k = ao_kernel(w.resolution, settings);
        std::vector<float> table(k.weights);
        table.insert(table.end(), k.totals.begin(), k.totals.end());
        gpu::BufferDesc desc;
        desc.size = (table.size() * sizeof(float) + 15) & ~std::size_t(15);
        desc.usage = VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
        desc.name = "ao kernel";
        s.kernel = r.device().create_buffer(desc);
        s.view = r.device().create_buffer_view(s.kernel, VK_FORMAT_R32_SFLOAT, 0, VK_WHOLE_SIZE, "ao kernel");
        r.cmd.upload(s.kernel, 0, std::as_bytes(std::span<const float>(table)));
        r.cmd.barrier_transfer_to_compute();
        s.key = key;
        s.range = k.range;
    }
    r.cmd.bind(r.pipeline<AoParams>("gi_ao.comp", {.proxies = false}));
    r.cmd.push_descriptors(gpu::DescriptorWrites()
                               .uniform_texel_buffer(0, r.walls())
                               .uniform_buffer(1, r.proxies())
                               .uniform_texel_buffer(2, s.view)
                               .storage_buffer(3, r.buffer(Tex::ao)));
    auto p = r.params<AoParams>(w.width, w.height);
    p.pass = {.radius = settings.radius, .power = settings.power, .strength = settings.strength,
              .dither = settings.dither ? 1.0f : 0.0f, .range = s.range};
    // Scrolling (rows.hpp WindowScroll): a texel depends on its place in its tile (the global
    // texel index) and the walls within `range` tiles of it; the dither on its window texel
    // modulo 4, so with dithering the window moves by multiples of 4 texels. An invocation
    // writes 4 texels' word: strips start at a multiple of 4.
    Hasher h;
    h.add(w.resolution).add(w.width).add(w.height).add(settings.radius).add(settings.power).add(settings.strength);
    h.add(settings.dither).add(s.range);
    const Tex out[] = {Tex::ao};
    glm::ivec2 shift(0);
    const int align = settings.dither ? 4 : 1;
    const bool scrolls = scroll_from_last(r, s.scroll, h.value(), out, s.range + 1, glm::ivec2(align), shift);
    dispatch_scrolled(r, s.scroll, scrolls, shift, out, 1 /* r8 */, 4, [&](int x0, int y0) {
        p.pass.offset = x0 | (y0 << 16);
        r.cmd.push_constants(p);
    });
    r.cmd.barrier_compute_to_compute();
}

void reference_ao_row(ReferenceContext& c) { c.store.put(Tex::ao, reference_ao(c.in, c.options)); }

// ---- point and emissive lights

// Light bins: one per direct-pass workgroup, a bitmask of the lights reaching it, and one of
// the proxies that can shade it. The point lights' shadow maps (point_map.hpp): built and
// uploaded whenever the pass runs with gi.shadow_method = shadow_map (a one-element
// stand-in otherwise); their headers ride in the spare fields of the pass's own copy of the
// lights.
struct DirectState : vk::PassState {
    gpu::Buffer bins, proxy_bins, lights;
    UploadedArray map_bins;
    // Dirty light bins: what the outputs hold (the context of the last run, 0 when they hold
    // anything else) and each bin's lights then; the bins recorded this run.
    std::uint64_t context = 0;
    std::vector<std::uint64_t> bin_lights;
    gpu::Buffer dirty;
    // The bins the baked row added the mixed set to after the last run (1 each; empty: none).
    std::vector<std::uint8_t> added;
};

// ---- dirty light bins (docs/gi.md, "Dirty light bins")
//
// A direct-pass workgroup (a light bin) writes its own texels only, and what it writes
// depends on the window, the walls, the proxies, the settings, the output textures and the
// lights that reach its texels (a texel farther from a light than its radius gets nothing
// from it), taken in index order. The row keeps a hash of the first group (the context) and
// one per bin of the second; when only lights changed since it last ran, a bin whose lights
// did not change holds what a new run would write, and the row records the other bins
// alone (a torch's flicker, the player's lantern: a few bins of the window).

// Everything the outputs depend on but the lights: with the suns' textures added
// (feature_suns), also what those depend on besides the walls, proxies and window hashed
// already (the suns and the suns' settings), so a bin is kept only over the same sunlight.
std::uint64_t direct_context(PassRecorder& r, std::span<const Tex> out, std::uint32_t features, std::uint32_t proxy_bands) {
    const FrameInputs& in = r.in;
    Hasher h;
    add_window_and_walls(h, in).add_span(std::span(in.proxies)).add(in.wall_height).add(r.plan.has_walls_in_window);
    h.add(in.settings.light_softness).add(in.settings.wall_face_exponent).add(computed_faces(in.settings));
    h.add(features).add(proxy_bands).add(r.block_h()).add(r.group_x()).add(r.group_y());
    h.add(reinterpret_cast<std::uintptr_t>(out.data()));
    for (const Tex t : out) h.add(r.has(t) ? r.serial(t) : 0);
    for (const Tex t : upper_outputs(out)) h.add(r.has(t) ? r.serial(t) : 0);
    if (features & feature_suns) {
        h.add_span(std::span(in.directional_lights)).add(in.settings.directional_angle_scale);
        h.add(int(in.settings.sun_shadow_method)).add(int(in.settings.proxy_wall_shadows));
        for (const Tex t : sun_set) h.add(r.has(t) ? r.serial(t) : 0);
        for (const Tex t : upper_sun_set) h.add(r.has(t) ? r.serial(t) : 0);
    }
    const std::uint64_t v = h.value();
    return v ? v : 1;
}

// The bins [lo, hi) of `count` bins of `size` texels that [c - reach, c + reach] meets (texels).
void bin_span(double c, double reach, double size, std::uint32_t count, std::uint32_t& lo, std::uint32_t& hi) {
    lo = std::uint32_t(std::clamp(std::floor((c - reach) / size), 0.0, double(count)));
    hi = std::uint32_t(std::clamp(std::floor((c + reach) / size) + 1.0, 0.0, double(count)));
}

} // namespace

WorkgroupGrid workgroup_grid(const vk::PassRecorder& r, int pitch, int height) {
    const std::uint32_t blocks_x = std::uint32_t(pitch / 4);
    const std::uint32_t blocks_y = (std::uint32_t(height) + r.block_h() - 1) / r.block_h();
    return {(blocks_x + r.group_x() - 1) / r.group_x(), (blocks_y + r.group_y() - 1) / r.group_y()};
}

std::vector<std::uint64_t> bin_lights(std::span<const GpuPointLight> points, std::span<const GpuPointLight> emissives,
                                      const GiWindow& w, std::uint32_t bins_x, std::uint32_t bins_y, float bin_w, float bin_h) {
    std::vector<std::uint64_t> out(std::size_t(bins_x) * bins_y, no_light_bin);
    const float res = float(w.resolution);
    auto add = [&](const GpuPointLight& l, std::uint64_t id) {
        const std::uint64_t light = Hasher().add(id).add_bytes(&l, sizeof l).value();
        // In texel units: texel x's centre is x + 0.5. A texel is reached when its centre is
        // within the radius; one texel more, and the float error of far coordinates, pad it.
        const double cx = (double(l.position_radius.x) - double(w.view.min_x)) * res,
                     cz = (double(l.position_radius.y) - double(w.view.min_z)) * res;
        const double reach = double(l.position_radius.z) * res + 1.0 +
                             1e-5 * res * (std::abs(double(l.position_radius.x)) + std::abs(double(l.position_radius.y)) +
                                           std::abs(double(l.position_radius.z)));
        std::uint32_t x0 = 0, x1 = bins_x, z0 = 0, z1 = bins_y;
        const bool finite = std::isfinite(cx) && std::isfinite(cz) && std::isfinite(reach);
        if (finite) {
            if (!(reach >= 0.0)) return; // a negative radius reaches nothing
            bin_span(cx, reach, bin_w, bins_x, x0, x1);
            bin_span(cz, reach, bin_h, bins_y, z0, z1);
        }
        for (std::uint32_t bz = z0; bz < z1; ++bz)
            for (std::uint32_t bx = x0; bx < x1; ++bx) {
                if (finite) { // the disc against the bin's rectangle
                    const double dx = std::max({double(bx) * bin_w - cx, 0.0, cx - double(bx + 1) * bin_w}),
                                 dz = std::max({double(bz) * bin_h - cz, 0.0, cz - double(bz + 1) * bin_h});
                    if (dx * dx + dz * dz > reach * reach) continue;
                }
                std::uint64_t& h = out[std::size_t(bz) * bins_x + bx];
                h = Hasher(h).add(light).value();
            }
    };
    for (std::size_t i = 0; i < points.size(); ++i) add(points[i], i);
    for (std::size_t i = 0; i < emissives.size(); ++i) add(emissives[i], (std::uint64_t(1) << 32) | (points.size() + i));
    return out;
}

namespace {

// Per bin (as bin_lights), whether a shadow proxy may be in its proxy mask (gi_light_bins:
// within proxy_reach of the bin's texel centres padded by `pad`), or surely none: there the
// direct pass runs its variant without proxy loops (HAS_PROXIES false), which writes what an
// empty mask does (every proxy shadow 1, no unfolded reach). Conservative: the bin's whole
// rectangle, a texel more, and the float error of far coordinates.
std::vector<std::uint8_t> bin_proxies(std::span<const GpuShadowProxy> proxies, const GiWindow& w, std::uint32_t bins_x,
                                      std::uint32_t bins_y, float bin_w, float bin_h, float pad) {
    std::vector<std::uint8_t> out(std::size_t(bins_x) * bins_y, 0);
    const double res = double(w.resolution);
    for (const GpuShadowProxy& p : proxies) {
        const glm::vec4 ps = p.position_size, l = p.lengths;
        const double along = std::max(double(l.x) + double(l.w), 0.0);
        const double across = std::abs(double(ps.z)) + std::abs(double(ps.w)) + std::max(double(l.z), 0.0);
        const double slop = 1e-5 * (std::abs(double(ps.x)) + std::abs(double(ps.y)) + std::abs(double(w.view.min_x)) +
                                    std::abs(double(w.view.min_z)) + along + across + 1.0);
        // In texels from the window's corner.
        const double reach = (std::sqrt(along * along + across * across) * 1.0001 + 1e-3 + double(pad) + slop) * res + 1.0;
        const double cx = (double(ps.x) - double(w.view.min_x)) * res, cz = (double(ps.y) - double(w.view.min_z)) * res;
        if (!std::isfinite(cx) || !std::isfinite(cz) || !std::isfinite(reach)) {
            std::fill(out.begin(), out.end(), std::uint8_t(1));
            return out;
        }
        std::uint32_t x0 = 0, x1 = 0, z0 = 0, z1 = 0;
        bin_span(cx, reach, bin_w, bins_x, x0, x1);
        bin_span(cz, reach, bin_h, bins_y, z0, z1);
        for (std::uint32_t bz = z0; bz < z1; ++bz)
            for (std::uint32_t bx = x0; bx < x1; ++bx) out[std::size_t(bz) * bins_x + bx] = 1;
    }
    return out;
}

// Whether a row after this one writes one of `outputs` this frame. The baked row adds the
// mixed lights' light into the direct textures in place, after the bounce passes read them:
// the texture then holds more than this row's light, and a kept bin would hold it twice.
bool written_later(PassRecorder& r, TexSet outputs, bool but_baked = false) {
    bool after = false;
    for (const PassRow* row : method(r.in.settings.method).rows) {
        if (after && r.plan.run.has(row->pass) && row->outputs(r.in).intersects(outputs) && !(but_baked && row->pass == Pass::baked))
            return true;
        after = after || row->pass == r.row().pass;
    }
    return false;
}

// Uploads this frame's point-light maps and the lights with their headers; false (the
// DDA) when the maps exceed what a storage buffer holds.
bool upload_point_maps(PassRecorder& r, const FrameInputs& in, DirectState& s, bool wanted) {
    PointMaps maps = wanted ? build_point_maps(in) : PointMaps{};
    if (maps.bins.size() * sizeof(glm::uvec2) > r.device().capabilities().max_storage_buffer_range) {
        maps = PointMaps{};
        wanted = false;
    }
    if (maps.bins.empty()) maps.bins.emplace_back(0u);
    if (!s.lights) {
        gpu::BufferDesc desc;
        desc.size = r.lights().size();
        desc.usage = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
        desc.name = "gi direct lights";
        s.lights = r.device().create_buffer(desc);
    }
    std::vector<GpuPointLight> lights(in.point_lights);
    lights.insert(lights.end(), in.emissive_lights.begin(), in.emissive_lights.end());
    for (std::size_t i = 0; i < in.point_lights.size(); ++i) {
        const glm::vec2 h = wanted ? maps.headers[i] : glm::vec2(-1.0f, 0.0f);
        lights[i].position_radius.w = h.x;
        lights[i].color.w = h.y;
    }
    if (!lights.empty())
        r.cmd.update_buffer(s.lights, 0, std::as_bytes(std::span<const GpuPointLight>(lights)).first(
                                             std::min<std::size_t>(lights.size() * sizeof(GpuPointLight), s.lights.size())));
    upload_array(r, s.map_bins, std::span<const glm::uvec2>(maps.bins), VK_FORMAT_UNDEFINED, "point map bins");
    r.cmd.barrier_transfer_to_compute();
    return wanted;
}

// How far beyond its texel centres a bin's proxy queries reach: face points half a tile
// off, and with unfolded proxy shadows points a wall height beyond those.
float proxy_pad(const FrameInputs& in) { return 0.51f + (unfolds_proxy_shadows(in) ? std::max(in.wall_height, 0.0f) : 0.0f); }

// The point and emissive lights of `lights` (its point_lights and emissive_lights; window,
// walls, proxies and settings are the frame's) into the texture set `out`, with `suns` the
// realtime suns' own textures (sun_set, the directional pass's) added texel by texel.
void record_direct_lights(PassRecorder& r, const FrameInputs& lights, std::span<const Tex> out, bool suns = false) {
    const FrameInputs& in = r.in;
    const GiWindow& w = in.window;
    const std::uint32_t faces = computed_faces(in.settings);
    // No point or emissive lights and no suns: the outputs are zero (with suns, the shader's
    // light-free variant copies theirs). No wall in view: the shader skips the faces, which
    // stay zero.
    const bool no_lights = lights.point_lights.empty() && lights.emissive_lights.empty() && !suns;
    if (no_lights || (!r.plan.has_walls_in_window && faces != 0)) {
        for (std::size_t i = no_lights ? 0 : 2; i < out.size(); ++i)
            if (r.has(out[i])) r.clear(out[i]);
        for (Tex t : upper_outputs(out))
            if (r.has(t)) r.clear(t);
        r.cmd.barrier_transfer_to_compute();
    }
    DirectState& s = r.state<DirectState>();
    if (no_lights) {
        s.context = 0; // cleared, not what a run writes (face flags)
        return;
    }
    const bool want_map = in.settings.shadow_method == scene::ShadowMethod::shadow_map && !lights.point_lights.empty();
    const WorkgroupGrid grid = workgroup_grid(r, r.pitch(out[0]), w.height);
    const std::uint32_t bins_x = grid.x, bins_y = grid.y;
    const std::uint32_t words = std::uint32_t((lights.point_lights.size() + lights.emissive_lights.size() + 31) / 32);
    const VkDeviceSize bin_bytes = std::max<VkDeviceSize>(16, VkDeviceSize(bins_x) * bins_y * std::max(words, 1u) * 4);
    const std::uint32_t proxy_words = std::uint32_t((in.proxies.size() + 31) / 32);
    // Proxy masks per bin, then per (bin, point light, band, strip): the bin's rows in
    // `bands` bands (one per workgroup row at most) by the invocations' 4 texel columns,
    // the finest whose masks fit in RendererOptions::proxy_list_bytes (0 bands: none fit);
    // then per (bin, band, strip) a mask of the point lights whose list there is not empty.
    const VkDeviceSize per_bin = VkDeviceSize(bins_x) * bins_y * proxy_words * 4;
    const VkDeviceSize point_words = (lights.point_lights.size() + 31) / 32;
    const VkDeviceSize per_band = (per_bin * lights.point_lights.size() + VkDeviceSize(bins_x) * bins_y * point_words * 4) * 4;
    std::uint32_t bands = 0;
    if (proxy_words > 0 && per_band > 0)
        for (std::uint32_t b = r.group_y(); b >= 1 && bands == 0; --b)
            if (r.group_y() % b == 0 && per_band * b <= r.proxy_list_bytes()) bands = b;
    const VkDeviceSize per_light = per_band * bands;
    const std::uint32_t base_features = (unfolds_proxy_shadows(in) ? feature_upper : 0u) |
                                        (in.settings.light_softness == 1.0f ? feature_linear_falloff : 0u) |
                                        face_features(in) | (suns ? feature_suns : 0u);

    // Dirty light bins: the bins to record, all of them unless only lights changed. Of those,
    // the bins no light reaches take the light-free variant.
    const std::uint32_t bin_count = bins_x * bins_y;
    const std::uint64_t context = direct_context(r, out, base_features | (want_map ? feature_point_map : 0u), bands);
    std::vector<std::uint64_t> hashes =
        bin_lights(lights.point_lights, lights.emissive_lights, w, bins_x, bins_y, float(4 * r.group_x()), float(r.block_h() * r.group_y()));
    // The baked row adds the mixed set into the direct textures in place, after the bounce
    // passes read them, in the bins mixed_add_bins lists: those then hold more than this
    // pass's light, and are recorded again the next time. Another row writing them later
    // keeps no bin.
    bool overwritten = !r.dirty_bins();
    const std::vector<std::uint8_t> added_before = std::move(s.added);
    s.added.clear();
    if (!overwritten && written_later(r, face_set(out, in))) {
        overwritten = written_later(r, face_set(out, in), true);
        const std::optional<std::vector<std::uint32_t>> added = mixed_add_bins(r, grid);
        s.added.assign(bin_count, added ? 0 : 1);
        if (added)
            for (const std::uint32_t b : *added) s.added[b] = 1;
    }
    bool kept = s.context == context && s.bin_lights.size() == hashes.size() && !overwritten;
    std::vector<std::uint32_t> lit, dark;
    auto list_bins = [&] {
        lit.clear(), dark.clear();
        for (std::uint32_t b = 0; b < bin_count; ++b)
            if (!kept || hashes[b] != s.bin_lights[b] || (b < added_before.size() && added_before[b] != 0))
                (hashes[b] == no_light_bin ? dark : lit).push_back(b);
    };
    list_bins();
    s.context = overwritten ? 0 : context;
    std::swap(s.bin_lights, hashes); // hashes: the last run's
    if (lit.empty() && dark.empty()) { // nothing reaching the window changed
        r.count_workgroups(bin_count, 0);
        return;
    }

    const bool point_map = upload_point_maps(r, lights, s, want_map);
    if (point_map != want_map) { // the maps did not fit: the DDA, which sums in another order
        s.context = 0;
        if (kept) {
            kept = false;
            std::swap(s.bin_lights, hashes);
            list_bins();
            std::swap(s.bin_lights, hashes);
        }
    }
    // The lit bins no proxy can shade take the variant without proxy loops (lavapipe runs a
    // loop's body at least once, masked: an empty proxy mask costs about what a proxy does).
    std::vector<std::uint32_t> plain;
    if (!in.proxies.empty() && r.dirty_bins()) {
        const std::vector<std::uint8_t> proxied =
            bin_proxies(in.proxies, w, bins_x, bins_y, float(4 * r.group_x()), float(r.block_h() * r.group_y()), proxy_pad(in));
        std::erase_if(lit, [&](std::uint32_t b) { return proxied[b] == 0 && (plain.push_back(b), true); });
    }
    // Lists (lit bins with proxies, without, then dark ones) unless every bin is lit with
    // proxies; one dispatch row each.
    const bool listed = r.dirty_bins() && lit.size() < bin_count &&
                        std::max({lit.size(), plain.size(), dark.size()}) <= 65535;
    if (!listed) { // every bin, with proxies
        lit.insert(lit.end(), plain.begin(), plain.end());
        plain.clear();
    }
    std::vector<std::uint32_t> list;
    if (listed) {
        list = lit;
        list.insert(list.end(), plain.begin(), plain.end());
        list.insert(list.end(), dark.begin(), dark.end());
    }
    const VkDeviceSize proxy_bytes = std::max<VkDeviceSize>(16, per_bin + per_light);
    const VkDeviceSize list_bytes = std::max<VkDeviceSize>(16, VkDeviceSize(list.size()) * 4);
    for (auto [buffer, bytes, name] : {std::tuple{&s.bins, bin_bytes, "gi light bins"}, std::tuple{&s.proxy_bins, proxy_bytes, "gi proxy bins"},
                                       std::tuple{&s.dirty, list_bytes, "gi dirty light bins"}})
        if (!*buffer || buffer->size() < bytes) {
            gpu::BufferDesc desc;
            desc.size = bytes;
            desc.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
            desc.name = name;
            *buffer = r.device().create_buffer(desc);
        }
    if (listed) {
        r.cmd.upload(s.dirty, 0, std::as_bytes(std::span<const std::uint32_t>(list)));
        r.cmd.barrier_transfer_to_compute();
    }
    r.count_workgroups(bin_count, lit.size() + plain.size() + dark.size());
    const glm::ivec2 counts(int(lights.point_lights.size()), int(lights.emissive_lights.size()));
    // One workgroup per bin: 4 strips by 8 rows of bands (gi_light_bins), timed on its own.
    const std::uint32_t bins_part = r.begin_part("light bins");
    r.cmd.bind(r.pipeline<LightBinParams>("gi_light_bins.comp", {.proxies = false, .block_h = 1, .group_x = 4, .group_y = 8}));
    r.cmd.push_descriptors(gpu::DescriptorWrites()
                               .uniform_buffer(0, s.lights)
                               .storage_buffer(1, s.bins)
                               .uniform_buffer(2, r.proxies())
                               .storage_buffer(3, s.proxy_bins));
    auto b = r.params<LightBinParams>(w.width, w.height);
    b.counts.x = counts.x, b.counts.y = counts.y;
    // A bin's proxy queries reach proxy_pad beyond its texel centres.
    b.pass = {.bins_x = std::int32_t(bins_x), .bins_y = std::int32_t(bins_y), .words = std::int32_t(words),
              .bin_w = std::int32_t(4 * r.group_x()), .bin_h = std::int32_t(r.block_h() * r.group_y()),
              .proxy_words = std::int32_t(proxy_words),
              .proxy_pad = proxy_pad(in),
              .per_light = std::int32_t(bands)};
    r.cmd.push_constants(b);
    r.cmd.dispatch(bins_x, bins_y);
    r.cmd.barrier_compute_to_compute();
    r.end_part(bins_part);

    const std::uint32_t features = base_features | (point_map ? feature_point_map : 0u);
    gpu::DescriptorWrites writes = gpu::DescriptorWrites()
                                             .uniform_texel_buffer(0, r.walls())
                                             .uniform_buffer(1, r.proxies())
                                             .uniform_buffer(2, s.lights)
                                             .storage_buffer(3, r.buffer(out[0]))
                                             .storage_buffer(4, r.buffer(out[1]))
                                             .storage_buffer(5, face_buffer(r, out, 0))
                                             .storage_buffer(6, face_buffer(r, out, 1))
                                             .storage_buffer(7, face_buffer(r, out, 2))
                                             .storage_buffer(8, face_buffer(r, out, 3))
                                             .storage_buffer(9, s.bins)
                                             .storage_buffer(10, upper_buffer(r, out, 0))
                                             .storage_buffer(11, upper_buffer(r, out, 1))
                                             .storage_buffer(12, upper_buffer(r, out, 2))
                                             .storage_buffer(13, upper_buffer(r, out, 3))
                                             .storage_buffer(14, s.map_bins.buffer)
                                             .storage_buffer(15, s.proxy_bins)
                                             .storage_buffer(16, s.dirty);
    // The suns' textures (faces not computed, and without suns all of them: bound to the
    // output's colour buffer, never read).
    for (std::uint32_t i = 0; i < 6; ++i)
        writes.uniform_texel_buffer(17 + i, suns && r.has(sun_set[i]) ? r.view(sun_set[i]) : r.view(out[0]));
    for (std::uint32_t f = 0; f < 4; ++f)
        writes.uniform_texel_buffer(23 + f, suns && r.has(upper_sun_set[f]) ? r.view(upper_sun_set[f]) : r.view(out[0]));
    auto p = r.params<DirectParams>(w.width, w.height);
    p.counts.x = counts.x, p.counts.y = counts.y;
    p.pass.light_softness = in.settings.light_softness;
    p.pass.face_exponent = in.settings.wall_face_exponent;
    p.pass.wall_height = in.wall_height;
    p.pass.proxy_per_light = std::int32_t(bands);
    p.pass.bins_x = std::int32_t(bins_x);
    p.pass.bins_y = std::int32_t(bins_y);
    auto run = [&](std::uint32_t variant, std::size_t first, std::size_t count, bool proxies = true) {
        r.cmd.bind(r.pipeline<DirectParams>("gi_direct.comp", {.proxies = proxies && !in.proxies.empty(),
                                                              .walls = r.plan.has_walls_in_window,
                                                              .features = features | variant,
                                                              .faces = faces}));
        r.cmd.push_descriptors(writes);
        p.pass.list_first = std::int32_t(first);
        r.cmd.push_constants(p);
        if (variant & feature_list)
            r.cmd.dispatch(std::uint32_t(count), 1);
        else
            r.dispatch(w.width, w.height);
    };
    if (!listed) {
        run(0, 0, 0);
    } else {
        if (!lit.empty()) run(feature_list, 0, lit.size());
        if (!plain.empty()) run(feature_list, lit.size(), plain.size(), false);
        if (!dark.empty()) run(feature_list | feature_no_lights, lit.size() + plain.size(), dark.size());
    }
    r.cmd.barrier_compute_to_compute();
    if (out.data() != direct_set) return;
    // What a later frame may need, before it does (creating it then stalls that frame): this
    // pass with proxies and walls come or gone, with and without suns, and the suns' pass.
    const bool sun_map = in.settings.sun_shadow_method == scene::SunShadowMethod::shadow_map;
    for (int flip = 0; flip < 8; ++flip) {
        const bool proxies = (flip & 1) != 0, walls = (flip & 2) != 0;
        const std::uint32_t with_suns = (flip & 4) != 0 ? (features ^ feature_suns) : features;
        for (std::uint32_t variant : {0u, feature_list, feature_list | feature_no_lights})
            r.prefetch_pipeline<DirectParams>("gi_direct.comp",
                                              {.proxies = proxies, .walls = walls, .features = with_suns | variant, .faces = faces});
        if (flip & 4) continue;
        for (std::uint32_t variant : {0u, feature_mixed_suns})
            r.prefetch_pipeline<DirectionalParams>(
                "gi_directional.comp",
                {.proxies = proxies, .walls = walls, .features = directional_features(in, sun_map) | variant, .faces = faces});
    }
}

void record_direct(PassRecorder& r) { record_direct_lights(r, r.in, direct_set, has_live_suns(r.in)); }

// The realtime suns' own textures from the store (what the directional row wrote).
DirectTextures stored_suns(const ReferenceStore& store) {
    DirectTextures d{store.at(Tex::direct_sun), store.at(Tex::shadow_sun), {}, {}};
    for (std::size_t f = 0; f < 4; ++f) {
        if (const Texture* face = store.find(sun_set[2 + f])) d.wall_direct[f] = *face;
        if (const Texture* upper = store.find(upper_sun_set[f])) d.wall_upper[f] = *upper;
    }
    return d;
}

void reference_direct_row(ReferenceContext& c) {
    if (!has_live_suns(c.in)) {
        put_direct(c.store, direct_set, reference_direct(c.in, c.options));
        return;
    }
    const DirectTextures suns = stored_suns(c.store);
    put_direct(c.store, direct_set, reference_direct(c.in, c.options, &suns));
}

// ---- mixed lights: their direct light on its own (a bake holds their bounce; the baked
// pass adds this after the live indirect passes, so the live bounce leaves them out)

// The frame with the mixed lights as its point and emissive lights.
FrameInputs mixed_inputs(const FrameInputs& in) {
    FrameInputs m = in;
    m.point_lights = in.mixed_lights;
    m.emissive_lights = in.mixed_emissives;
    m.directional_lights.clear();
    return m;
}

// The mixed lights' set, and with mixed suns theirs.
TexSet mixed_writes(const FrameInputs& in) {
    TexSet set = face_set(mixed_set, in);
    if (has_mixed_suns(in)) set |= face_set(mixed_sun_set, in);
    return set;
}

// Planned whenever a bake is used, with or without mixed lights in reach (then its textures
// are cleared once and kept): its textures stay allocated while mixed lights come and go.
const char* mixed_not_needed(const FrameInputs& in, bool, bool) { return in.baked ? nullptr : "no baked light in use"; }

void record_suns(PassRecorder& r, bool mixed);

DirectTextures reference_suns_alone(const FrameInputs& in, bool mixed, const RefOptions& options);

// The mixed point and emissive lights (their bins kept while only the suns change), then the
// mixed suns into their own set.
void record_mixed(PassRecorder& r) {
    record_direct_lights(r, mixed_inputs(r.in), mixed_set);
    if (has_mixed_suns(r.in)) record_suns(r, true);
}

void reference_mixed_row(ReferenceContext& c) {
    put_direct(c.store, mixed_set, reference_direct(mixed_inputs(c.in), c.options));
    if (has_mixed_suns(c.in)) put_direct(c.store, mixed_sun_set, reference_suns_alone(c.in, true, c.options));
}

// ---- directional lights

// The suns' shadow maps on the GPU (sun_map.hpp): rebuilt and uploaded whenever the pass
// runs with gi.sun_shadow_method = shadow_map; a one-element stand-in otherwise. And the
// proxies each workgroup visits (sun_proxy_bins), every time it runs.
struct SunMapState : vk::PassState {
    UploadedArray headers, first, entries;
    UploadedArray proxy_bins;
};

// For each sun and workgroup of the pass (row-major), a mask of the proxies whose shadow from
// that sun can reach the workgroup's texels or their wall faces' targets (and, unfolded, the
// tops of those faces): gi_shadow.glsl's proxy_occlusion is 0 beyond `along` in
// (0, max length + penumbra length] and a perpendicular distance of the proxy's width plus
// its penumbra width, so the others are skipped without changing a result. Boxes, padded.
// Only the suns the pass lights (`mixed`: the mixed ones, else the realtime ones) have masks.
std::vector<std::uint32_t> sun_proxy_bins(const PassRecorder& r, bool mixed) {
    const FrameInputs& in = r.in;
    const GiWindow& w = in.window;
    const WorkgroupGrid grid = workgroup_grid(r, r.pitch(direct_set[0]), w.height);
    const int bins_x = int(grid.x), bins_y = int(grid.y);
    const int group_w = int(r.group_x()) * 4, group_h = int(r.group_y() * r.block_h()); // texels
    const int words = (int(in.proxies.size()) + 31) / 32;
    std::vector<std::uint32_t> masks(std::max<std::size_t>(1, in.directional_lights.size() * std::size_t(bins_x) *
                                                                   std::size_t(bins_y) * std::size_t(words)),
                                     0u);
    if (words == 0) return masks;
    // A texel's face targets lie on its tile's edges (within a tile of it); unfolded shadows
    // also test a face's top, the wall height further along the sun's travel.
    const float margin = 1.01f + (unfolds_proxy_shadows(in) ? std::max(in.wall_height, 0.0f) : 0.0f);
    // The first and last bin of `count` bins of `size` texels whose texels meet [lo, hi] (world
    // units from `min`); clamped as floats before the int, so far coordinates stay in range.
    const auto bin_range = [&](float lo, float hi, float min, int size, int count) {
        const float res = float(w.resolution), end = float(size * count);
        const int a = int(std::floor(std::clamp((lo - min) * res, -1.0f, end)));
        const int b = int(std::floor(std::clamp((hi - min) * res, -1.0f, end)));
        return std::pair{std::clamp(a / size, 0, count), b < 0 ? -1 : std::min(b / size, count - 1)};
    };
    for (std::size_t sun = 0; sun < in.directional_lights.size(); ++sun) {
        if (is_mixed_sun(in.directional_lights[sun]) != mixed) continue; // the shader skips it
        const glm::vec3 dir = glm::vec3(in.directional_lights[sun].direction_base);
        const float xz = std::sqrt(dir.x * dir.x + dir.z * dir.z);
        if (!(xz >= 1e-4f)) continue; // straight down: the shader tests no proxy
        const glm::vec2 travel(dir.x / xz, dir.z / xz);
        for (std::size_t i = 0; i < in.proxies.size(); ++i) {
            const GpuShadowProxy& p = in.proxies[i];
            const glm::vec2 c(p.position_size.x, p.position_size.y);
            const float width = (p.modes.y > 0.5f ? p.position_size.z : p.position_size.z + p.position_size.w) +
                                std::max(p.lengths.z, 0.0f) + margin + 0.01f;
            const glm::vec2 end = c + travel * (std::max(p.lengths.x, 0.0f) + std::max(p.lengths.w, 0.0f));
            const glm::vec2 lo = glm::min(c, end) - width, hi = glm::max(c, end) + width;
            if (!(lo.x <= hi.x && lo.y <= hi.y)) continue; // not finite
            const auto [x0, x1] = bin_range(lo.x, hi.x, w.view.min_x, group_w, bins_x);
            const auto [y0, y1] = bin_range(lo.y, hi.y, w.view.min_z, group_h, bins_y);
            for (int by = y0; by <= y1; ++by)
                for (int bx = x0; bx <= x1; ++bx) {
                    const std::size_t bin = std::size_t(by) * std::size_t(bins_x) + std::size_t(bx);
                    const std::size_t at = (sun * std::size_t(bins_x) * std::size_t(bins_y) + bin) * std::size_t(words);
                    masks[at + i / 32] |= 1u << (i % 32);
                }
        }
    }
    return masks;
}

// Uploads this frame's maps of the suns the pass lights (the mixed ones or the realtime
// ones; the others' are stand-ins); false (use the DDA) when they exceed what a texel buffer
// holds.
bool upload_sun_maps(PassRecorder& r, bool wanted, bool mixed) {
    SunMapState& s = r.state<SunMapState>();
    PackedSunMaps packed =
        pack_sun_maps(wanted ? build_sun_maps(r.in, mixed ? SunKinds::mixed : SunKinds::realtime) : std::vector<SunMap>{});
    const std::uint32_t limit = r.device().capabilities().max_texel_buffer_elements;
    if (packed.entries.size() > limit || packed.first.size() > limit) {
        packed = pack_sun_maps({});
        wanted = false;
    }
    if (!wanted && s.headers.buffer) return false; // the stand-ins are bound already
    upload_array(r, s.headers, std::span<const glm::vec4>(packed.headers), VK_FORMAT_R32G32B32A32_SFLOAT, "sun map headers");
    upload_array(r, s.first, std::span<const std::uint32_t>(packed.first), VK_FORMAT_R32_UINT, "sun map bins");
    upload_array(r, s.entries, std::span<const glm::vec4>(packed.entries), VK_FORMAT_R32G32B32A32_SFLOAT, "sun map tiles");
    r.cmd.barrier_transfer_to_compute();
    return wanted;
}

// The suns' pass: the realtime suns into their own textures (sun_set; the direct pass adds
// them), or the mixed suns (`mixed`, the mixed row) into theirs (mixed_sun_set; the baked pass
// adds them). The shader lights the suns of its kind (is_mixed_sun) from the frame's sun
// list and reads no texture, so their shadow maps and proxy bins keep their indices.
void record_suns(PassRecorder& r, bool mixed) {
    const FrameInputs& in = r.in;
    const GiWindow& w = in.window;
    const bool sun_map = upload_sun_maps(r, in.settings.sun_shadow_method == scene::SunShadowMethod::shadow_map, mixed);
    SunMapState& maps = r.state<SunMapState>();
    const std::uint32_t faces = computed_faces(in.settings);
    upload_array(r, maps.proxy_bins, std::span<const std::uint32_t>(sun_proxy_bins(r, mixed)), VK_FORMAT_UNDEFINED,
                 "sun proxy bins");
    r.cmd.barrier_transfer_to_compute();
    const std::span<const Tex> outs = mixed ? std::span<const Tex>(mixed_sun_set) : std::span<const Tex>(sun_set);
    const std::span<const Tex> upper_outs = upper_outputs(outs);
    if (!r.plan.has_walls_in_window && faces != 0) { // the shader skips the faces: they stay zero
        for (std::size_t f = 0; f < 4; ++f)
            for (Tex t : {outs[2 + f], upper_outs[f]})
                if (r.has(t)) r.clear(t);
        r.cmd.barrier_transfer_to_compute();
    }
    r.cmd.bind(r.pipeline<DirectionalParams>("gi_directional.comp",
                                             {.proxies = !in.proxies.empty(),
                                              .walls = r.plan.has_walls_in_window,
                                              .features = directional_features(in, sun_map) | (mixed ? feature_mixed_suns : 0u),
                                              .faces = faces}));
    gpu::DescriptorWrites writes;
    writes.uniform_texel_buffer(0, r.walls()).uniform_buffer(1, r.proxies()).uniform_buffer(2, r.suns());
    // Faces not computed: bound to the colour's buffers, never written.
    for (std::uint32_t i = 0; i < 6; ++i) writes.storage_buffer(3 + i, r.buffer(r.has(outs[i]) ? outs[i] : outs[0]));
    writes.uniform_texel_buffer(9, maps.headers.view).uniform_texel_buffer(10, maps.first.view).uniform_texel_buffer(11, maps.entries.view);
    for (std::uint32_t f = 0; f < 4; ++f) {
        const Tex out_upper = upper_outs[f];
        writes.storage_buffer(12 + f, r.buffer(r.has(out_upper) ? out_upper : outs[0]));
    }
    writes.storage_buffer(16, maps.proxy_bins.buffer);
    r.cmd.push_descriptors(writes);
    auto p = r.params<DirectionalParams>(w.width, w.height);
    p.pass = {.wall_height = in.wall_height,
              .angle_scale = in.settings.directional_angle_scale,
              .face_exponent = in.settings.wall_face_exponent,
};
    r.cmd.push_constants(p);
    r.dispatch(w.width, w.height);
    r.cmd.barrier_compute_to_compute();
}

void record_directional(PassRecorder& r) { record_suns(r, false); }

// The realtime suns (or the mixed ones) onto zero textures (what the direct pass writes
// without lights).
DirectTextures reference_suns_alone(const FrameInputs& in, bool mixed, const RefOptions& options) {
    FrameInputs suns = with_suns(in, mixed);
    suns.point_lights.clear();
    suns.emissive_lights.clear();
    DirectTextures d = reference_direct(suns, options);
    reference_directional(suns, d, options);
    return d;
}

void reference_directional_row(ReferenceContext& c) { put_direct(c.store, sun_set, reference_suns_alone(c.in, false, c.options)); }

// The direct pass reads the suns' own textures when realtime suns light the frame.
constexpr Tex direct_reads[] = {Tex::direct_sun,        Tex::shadow_sun,        Tex::wall_direct_sun_px,
                                Tex::wall_direct_sun_nx, Tex::wall_direct_sun_pz, Tex::wall_direct_sun_nz,
                                Tex::wall_upper_sun_px,  Tex::wall_upper_sun_nx,  Tex::wall_upper_sun_pz,
                                Tex::wall_upper_sun_nz};

const char* ao_not_needed(const FrameInputs& in, bool, bool) { return in.settings.ao.enabled ? nullptr : "AO disabled"; }
const char* directional_not_needed(const FrameInputs& in, bool, bool) {
    if (in.directional_lights.empty()) return "no directional lights";
    return has_live_suns(in) ? nullptr : "every sun is mixed (the mixed row lights them)";
}

constexpr Tex conduction_writes[] = {Tex::conduction};
constexpr Tex ao_writes[] = {Tex::ao};
constexpr std::string_view ao_settings[] = {"ao.enabled", "ao.radius", "ao.power", "ao.strength", "ao.dither"};
// shadow_method is listed although the maps are exact: a change of method reruns the pass,
// so that switching it shows what it costs.
constexpr std::string_view direct_settings[] = {"light_softness", "wall_face_exponent", "wall_lighting",
                                                "wall_faces.px",  "wall_faces.nx",      "wall_faces.pz",
                                                "wall_faces.nz",  "proxy_wall_shadows", "shadow_method"};
// sun_shadow_method is listed although the map is exact: a change of method reruns the
// pass, so that switching it shows what it costs.
constexpr std::string_view directional_settings[] = {"directional_angle_scale", "wall_face_exponent", "wall_lighting",
                                                     "wall_faces.px",           "wall_faces.nx",      "wall_faces.pz",
                                                     "wall_faces.nz",           "sun_shadow_method",  "proxy_wall_shadows"};
// The mixed row lights mixed point lights and mixed suns: both passes' settings.
constexpr std::string_view mixed_settings[] = {"light_softness",     "wall_face_exponent", "wall_lighting",
                                               "wall_faces.px",      "wall_faces.nx",      "wall_faces.pz",
                                               "wall_faces.nz",      "proxy_wall_shadows", "shadow_method",
                                               "directional_angle_scale", "sun_shadow_method"};

} // namespace

constinit const PassRow conduction{
    .pass = Pass::conduction,
    .name = "conduction",
    .writes = conduction_writes,
    .inputs = input_walls,
    .record = record_conduction,
    .reference = reference_conduction_row,
};

constinit const PassRow ao{
    .pass = Pass::ao,
    .name = "ao",
    .writes = ao_writes,
    .settings = ao_settings,
    .inputs = input_walls,
    .not_needed = ao_not_needed,
    .record = record_ao,
    .reference = reference_ao_row,
};

constinit const PassRow direct{
    .pass = Pass::direct,
    .name = "direct",
    .reads = direct_reads,
    .writes_for = direct_writes,
    .settings = direct_settings,
    .inputs = input_walls | input_lights | input_proxies | input_wall_height | input_walls_in_window,
    .record = record_direct,
    .reference = reference_direct_row,
};

constinit const PassRow mixed{
    .pass = Pass::mixed,
    .name = "mixed",
    .writes_for = mixed_writes,
    .settings = mixed_settings,
    .inputs = input_walls | input_mixed_lights | input_mixed_suns | input_proxies | input_wall_height | input_walls_in_window,
    .not_needed = mixed_not_needed,
    .record = record_mixed,
    .reference = reference_mixed_row,
};

constinit const PassRow directional{
    .pass = Pass::directional,
    .name = "directional",
    .writes_for = directional_writes,
    .settings = directional_settings,
    .inputs = input_walls | input_proxies | input_suns | input_wall_height | input_walls_in_window,
    .not_needed = directional_not_needed,
    .record = record_directional,
    .reference = reference_directional_row,
};

} // namespace lantern::gi::rows

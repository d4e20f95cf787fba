#include "lantern/transport/cache.hpp"

#include "lantern/core/file.hpp"
#include "lantern/core/hash.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <type_traits>

namespace lantern::transport {
namespace {

constexpr char magic[8] = {'L', 'T', 'R', 'A', 'N', 'S', 'P', '1'};

void hash_lights(Hasher& h, const scene::Scene& s) {
    h.add(s.point_lights.size());
    for (const scene::PointLight& l : s.point_lights)
        h.add(l.position.x)
            .add(l.position.y)
            .add(l.height)
            .add(l.color.r)
            .add(l.color.g)
            .add(l.color.b)
            .add(l.intensity)
            .add(l.radius);
    h.add(s.emissive_lights.size());
    for (const scene::EmissiveLight& l : s.emissive_lights)
        h.add(l.position.x)
            .add(l.position.y)
            .add(l.color.r)
            .add(l.color.g)
            .add(l.color.b)
            .add(l.intensity)
            .add(l.radius);
    h.add(s.directional_lights.size());
    for (const scene::DirectionalLight& l : s.directional_lights)
        h.add(l.direction.x)
            .add(l.direction.y)
            .add(l.direction.z)
            .add(l.color.r)
            .add(l.color.g)
            .add(l.color.b)
            .add(l.intensity)
            .add(l.base_shadow_distance)
            .add(l.bounce_intensity);
    // Field by field: ShadowProxy has padding bytes.
    h.add(s.shadow_proxies.size());
    for (const scene::ShadowProxy& p : s.shadow_proxies)
        h.add(p.position.x)
            .add(p.position.y)
            .add(p.shape)
            .add(p.size.x)
            .add(p.size.y)
            .add(p.max_length)
            .add(p.end_cap_blend)
            .add(p.penumbra_width)
            .add(p.penumbra_length)
            .add(p.penumbra_power)
            .add(p.width_mode)
            .add(p.penumbra_mode);
}

void hash_settings(Hasher& h, const TransportSettings& t) {
    h.add(t.albedo)
        .add(t.max_bounces)
        .add(t.resolution)
        .add(t.margin)
        .add(t.target_relative_error)
        .add(t.photons_per_batch)
        .add(t.min_batches)
        .add(t.max_batches)
        .add(t.seed);
}

// ---- serialisation

class Writer {
  public:
    template <typename T>
    void put(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto* p = reinterpret_cast<const std::byte*>(&v);
        bytes.insert(bytes.end(), p, p + sizeof(T));
    }
    void floats(const std::vector<float>& v) {
        const auto* p = reinterpret_cast<const std::byte*>(v.data());
        bytes.insert(bytes.end(), p, p + v.size() * sizeof(float));
    }
    std::vector<std::byte> bytes;
};

class Reader {
  public:
    explicit Reader(const std::vector<std::uint8_t>& b) : bytes_(b) {}
    template <typename T>
    bool get(T& v) {
        if (bytes_.size() - at_ < sizeof(T)) return false;
        std::memcpy(&v, bytes_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return true;
    }
    // Reads v.size() floats; false when short or any is not finite.
    bool floats(std::vector<float>& v) {
        const std::size_t n = v.size() * sizeof(float);
        if (bytes_.size() - at_ < n) return false;
        std::memcpy(v.data(), bytes_.data() + at_, n);
        at_ += n;
        for (float f : v)
            if (!std::isfinite(f)) return false;
        return true;
    }
    bool at_end() const { return at_ == bytes_.size(); }

  private:
    const std::vector<std::uint8_t>& bytes_;
    std::size_t at_ = 0;
};

// The fields in file order; R is TransportResult or const TransportResult.
template <typename R, typename F>
void for_each_field(R& r, F&& f) {
    f(r.direct.rgb), f(r.indirect.rgb), f(r.indirect_error.rgb);
    f(r.face_direct.rgb), f(r.face_indirect.rgb), f(r.face_indirect_error.rgb);
}

void sized_fields(TransportResult& r) {
    const gi::GiWindow& w = r.window;
    r.direct = r.indirect = r.indirect_error = RgbField(w.width, w.height);
    r.face_direct = r.face_indirect = r.face_indirect_error =
        FaceField(FaceLayout{w.resolution, w.width, w.height});
}

bool read_header(Reader& in, std::uint64_t key, TransportResult& r) {
    char m[8];
    std::uint32_t version = 0;
    std::uint64_t stored_key = 0;
    if (!in.get(m) || std::memcmp(m, magic, sizeof(m)) != 0) return false;
    if (!in.get(version) || version != transport_code_version) return false;
    if (!in.get(stored_key) || stored_key != key) return false;
    gi::GiWindow& w = r.window;
    if (!in.get(w.resolution) || !in.get(w.width) || !in.get(w.height)) return false;
    if (!in.get(w.view.min_x) || !in.get(w.view.min_z) || !in.get(w.view.width) ||
        !in.get(w.view.height))
        return false;
    // Sizes bounded before anything is allocated (GI windows are at most 65536 texels a side).
    if (w.resolution < 1 || w.resolution > 32 || w.width < 1 || w.height < 1 || w.width > 65536 ||
        w.height > 65536)
        return false;
    std::int32_t converged = 0;
    TransportStats& s = r.stats;
    if (!in.get(s.photons) || !in.get(s.batches) || !in.get(converged) ||
        !in.get(s.relative_error) || !in.get(s.seconds))
        return false;
    s.converged = converged != 0;
    return true;
}

} // namespace

Result<std::uint64_t> cache_key(const scene::Scene& scene, const TransportSettings& settings) {
    std::string why;
    auto window = gi::compute_window(scene.view, scene.gi.padding, settings.resolution, &why);
    if (!window) return make_error("transport: the view has no GI window: " + why);
    Hasher h;
    h.add(transport_code_version);
    hash_settings(h, settings);
    h.add(window->view.min_x)
        .add(window->view.min_z)
        .add(window->view.width)
        .add(window->view.height)
        .add(window->resolution)
        .add(window->width)
        .add(window->height);
    h.add(scene.walls.width)
        .add(scene.walls.height)
        .add(scene.walls.origin.x)
        .add(scene.walls.origin.y);
    h.add_span(std::span<const std::uint8_t>(scene.walls.cells));
    h.add(scene.wall_height).add(scene.gi.light_softness).add(scene.gi.directional_angle_scale);
    hash_lights(h, scene);
    if (scene.gi.albedo_boost != 1.0f) h.add(scene.gi.albedo_boost); // (keys without it stay as they were)
    if (!scene.materials.empty()) { // (keys of scenes without materials stay as they were)
        h.add(scene.materials.size());
        for (const scene::Material& m : scene.materials)
        {
            h.add(m.albedo.r).add(m.albedo.g).add(m.albedo.b).add(m.emission.r).add(m.emission.g).add(m.emission.b);
            // (keys of materials at the defaults stay as they were)
            if (m.emission_gi != scene::EmissionGi::baked || m.opacity != 1.0f) h.add(int(m.emission_gi)).add(m.opacity);
        }
    }
    return h.value();
}

std::string cache_path(const std::string& dir, std::uint64_t key) {
    char name[32];
    std::snprintf(name, sizeof(name), "%016llx.ltr", static_cast<unsigned long long>(key));
    return (std::filesystem::path(dir) / name).string();
}

std::string default_cache_dir() {
    if (const char* d = std::getenv("LANTERN_TRANSPORT_CACHE")) return d;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x)
        return (std::filesystem::path(x) / "lantern" / "transport").string();
    if (const char* home = std::getenv("HOME"); home && *home)
        return (std::filesystem::path(home) / ".cache" / "lantern" / "transport").string();
    return "";
}

Result<TransportResult> read_cached(const std::string& path, std::uint64_t key) {
    auto bytes = read_binary_file(path);
    if (!bytes) return bytes.error();
    Reader in(*bytes);
    TransportResult r;
    if (!read_header(in, key, r))
        return make_error(path + ": not a transport result for this problem and version");
    sized_fields(r);
    bool ok = true;
    for_each_field(r, [&](std::vector<float>& v) { ok = ok && in.floats(v); });
    if (!ok || !in.at_end())
        return make_error(path + ": truncated, oversized or non-finite transport result");
    return r;
}

Result<void> write_cached(const std::string& path, std::uint64_t key,
                          const TransportResult& result) {
    const std::filesystem::path p(path);
    if (p.has_parent_path())
        if (auto ok = ensure_directory(p.parent_path().string()); !ok) return ok;
    Writer out;
    out.put(magic);
    out.put(transport_code_version);
    out.put(key);
    const gi::GiWindow& w = result.window;
    out.put(w.resolution), out.put(w.width), out.put(w.height);
    out.put(w.view.min_x), out.put(w.view.min_z), out.put(w.view.width), out.put(w.view.height);
    const TransportStats& s = result.stats;
    out.put(s.photons), out.put(s.batches), out.put(std::int32_t(s.converged)),
        out.put(s.relative_error), out.put(s.seconds);
    for_each_field(result, [&](const std::vector<float>& v) { out.floats(v); });
    return write_file_atomic(path, out.bytes);
}

} // namespace lantern::transport

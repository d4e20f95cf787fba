// Chunk cache files (bake.hpp, docs/baked.md "Cache files"). Layout, little-endian:
//   char[8]  magic "LGIBAKE\0"
//   u32      file format version (file_format_version)
//   u32      flags: 1 = holds textures (else an empty chunk: no payload); 2 = also holds a
//            pulsing part (with 1 only)
//   u64      key (chunk_key)
//   i32 x 3  chunk x, chunk z, resolution (texels per tile)
//   u32      sun keys: how many parts of the moving sun's keys follow (0, or 2..32; with
//            flag 1 only)
//   u64      payload bytes (inflated)
//   u64      hash of the payload (inflated)
//   u64      stored bytes: the payload deflated (zlib), what follows the header
//   payload  ground, then faces +X, -X, +Z, -Z: (32 x resolution)^2 texels x RGB, IEEE half;
//            then 16 x 16 light probes: 5 x RGB float32 each, then one validity byte each;
//            with flag 2, then the pulsing part's ground, faces and probes alike (no validity);
//            then each sun key's alike
// (Format 3 files wrote the sun keys' field as a reserved 0: they read as files without keys.)
// The payload's size follows from the resolution, so a file cannot make the reader inflate
// more than the largest chunk (resolution 16).
#include "lantern/bake/bake.hpp"

#include "lantern/core/file.hpp"
#include "lantern/core/hash.hpp"

#include <glm/gtc/packing.hpp>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

namespace lantern::bake {
namespace {

constexpr char magic[8] = {'L', 'G', 'I', 'B', 'A', 'K', 'E', '\0'};
// The file's layout (not the bake's: bake_code_version, in the key, says that): 2 stored the
// payload as is, 3 deflates it.
constexpr std::uint32_t file_format_version = 3;
constexpr std::size_t header_bytes = 8 + 4 + 4 + 8 + 4 * 3 + 4 + 8 + 8 + 8;
constexpr int texture_count = 5;

template <typename T>
void put(std::vector<std::byte>& out, T v) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    out.insert(out.end(), p, p + sizeof(T));
}

template <typename T>
T get(const std::uint8_t* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

constexpr std::size_t probe_count = std::size_t(chunk_probes) * std::size_t(chunk_probes);
constexpr std::size_t probe_floats = 5 * 3;

constexpr std::uint32_t max_sun_keys = 32; // bake::validate_settings' limit

std::size_t payload_bytes(int resolution, bool pulse = false, std::uint32_t sun_keys = 0) {
    const std::size_t side = std::size_t(chunk_tiles) * std::size_t(resolution);
    const std::size_t part = side * side * 3 * sizeof(std::uint16_t) * texture_count + probe_count * probe_floats * sizeof(float);
    return part + probe_count + (pulse ? part : 0) + std::size_t(sun_keys) * part;
}

} // namespace

std::string chunk_file_name(ChunkId c) {
    return "chunk_" + std::to_string(c.x) + "_" + std::to_string(c.z) + ".lbk";
}

std::vector<std::byte> encode_chunk(const ChunkBake& b) {
    std::vector<std::byte> payload;
    if (!b.empty) {
        payload.reserve(payload_bytes(b.resolution, b.pulses(), std::uint32_t(b.sun_keys.size())));
        auto halves = [&](const std::vector<float>& v) {
            // Above half's range (65504) a texel is clamped: light that bright is white anyway.
            for (float f : v) put(payload, std::uint16_t(glm::packHalf1x16(std::min(f, 65504.0f))));
        };
        auto floats = [&](const std::vector<CircularHarmonics>& probes) {
            for (const CircularHarmonics& h : probes)
                for (const glm::vec3& v : h.c)
                    for (int k = 0; k < 3; ++k) put(payload, v[k]);
        };
        // One part: its textures, then its probes.
        auto part = [&](const std::vector<float>& ground, const std::array<std::vector<float>, 4>& faces,
                        const std::vector<CircularHarmonics>& probes) {
            halves(ground);
            for (const auto& f : faces) halves(f);
            floats(probes);
        };
        part(b.ground, b.faces, b.probes);
        for (std::uint8_t valid : b.probe_valid) put(payload, valid);
        // The parts apart from the steady one: the pulsing glow's, then each sun key's.
        if (b.pulses()) part(b.pulse.ground, b.pulse.faces, b.pulse.probes);
        for (const LightPart& key : b.sun_keys) part(key.ground, key.faces, key.probes);
    }
    // Deflated: zero texels in rock and halves with low bits zero compress 5-17x.
    std::vector<std::byte> stored;
    if (!payload.empty()) {
        uLongf length = compressBound(uLong(payload.size()));
        stored.resize(length);
        const int z = compress2(reinterpret_cast<Bytef*>(stored.data()), &length,
                                reinterpret_cast<const Bytef*>(payload.data()), uLong(payload.size()), 6);
        LANTERN_ASSERT(z == Z_OK, "zlib's compress2 with a compressBound buffer");
        stored.resize(length);
    }
    std::vector<std::byte> out;
    out.reserve(header_bytes + stored.size());
    out.insert(out.end(), reinterpret_cast<const std::byte*>(magic), reinterpret_cast<const std::byte*>(magic) + 8);
    put(out, file_format_version);
    put(out, std::uint32_t(b.empty ? 0 : b.pulses() ? 3 : 1));
    put(out, b.key);
    put(out, std::int32_t(b.id.x));
    put(out, std::int32_t(b.id.z));
    put(out, std::int32_t(b.resolution));
    put(out, std::uint32_t(b.empty ? 0 : b.sun_keys.size()));
    put(out, std::uint64_t(payload.size()));
    put(out, Hasher().add_bytes(payload.data(), payload.size()).value());
    put(out, std::uint64_t(stored.size()));
    out.insert(out.end(), stored.begin(), stored.end());
    return out;
}

Result<ChunkBake> decode_chunk(std::span<const std::uint8_t> bytes) {
    if (bytes.size() < header_bytes) return make_error("truncated (" + std::to_string(bytes.size()) + " bytes)");
    const std::uint8_t* p = bytes.data();
    if (std::memcmp(p, magic, 8) != 0) return make_error("not a Lantern bake file");
    const auto version = get<std::uint32_t>(p + 8);
    if (version != file_format_version)
        return make_error("format version " + std::to_string(version) + ", this build reads " +
                          std::to_string(file_format_version));
    const auto flags = get<std::uint32_t>(p + 12);
    ChunkBake b;
    b.key = get<std::uint64_t>(p + 16);
    b.id = {get<std::int32_t>(p + 24), get<std::int32_t>(p + 28)};
    b.resolution = get<std::int32_t>(p + 32);
    const auto size = get<std::uint64_t>(p + 40);
    const auto hash = get<std::uint64_t>(p + 48);
    const auto stored = get<std::uint64_t>(p + 56);
    const auto sun_keys = get<std::uint32_t>(p + 36);
    if (flags != 0 && flags != 1 && flags != 3) return make_error("unknown flags");
    if (sun_keys == 1 || sun_keys > max_sun_keys || (flags == 0 && sun_keys != 0))
        return make_error("sun keys " + std::to_string(sun_keys) + " (0, or 2 to " + std::to_string(max_sun_keys) + " with textures)");
    if (b.resolution < 1 || b.resolution > 16) return make_error("resolution " + std::to_string(b.resolution));
    b.empty = flags == 0;
    const bool pulse = flags == 3;
    const std::uint64_t expected = b.empty ? 0 : payload_bytes(b.resolution, pulse, sun_keys);
    if (size != expected || bytes.size() - header_bytes != stored || (stored == 0) != (expected == 0))
        return make_error("sizes do not match (" + std::to_string(bytes.size()) + " bytes, " + std::to_string(stored) +
                          " stored after the header, payload " + std::to_string(size) + " for " +
                          std::to_string(expected) + ")");
    // Deflate expands by at most 1032x: a stream shorter than that cannot hold the payload
    // (and nothing is allocated for it).
    if (stored * 1032 + 64 < expected) return make_error("damaged (too short to inflate to " + std::to_string(expected) + " bytes)");
    std::vector<std::uint8_t> inflated(static_cast<std::size_t>(expected));
    if (expected > 0) {
        uLongf length = uLongf(expected);
        const int z = uncompress(inflated.data(), &length, p + header_bytes, uLong(stored));
        if (z != Z_OK || length != expected) return make_error("damaged (the payload does not inflate)");
    }
    const std::uint8_t* payload = inflated.data();
    if (Hasher().add_bytes(payload, std::size_t(size)).value() != hash) return make_error("damaged (hash mismatch)");
    if (b.empty) return b;
    const std::size_t n = std::size_t(b.side()) * std::size_t(b.side()) * 3;
    // One part (textures, then probes) from `at`; false on a bad value.
    auto read_part = [&](const std::uint8_t* at, std::vector<float>& ground, std::array<std::vector<float>, 4>& faces,
                         std::vector<CircularHarmonics>& probes) -> std::optional<std::string> {
        auto read = [&](std::vector<float>& v, std::size_t index) {
            v.resize(n);
            const std::uint8_t* t = at + index * n * sizeof(std::uint16_t);
            for (std::size_t i = 0; i < n; ++i) v[i] = glm::unpackHalf1x16(get<std::uint16_t>(t + i * 2));
        };
        read(ground, 0);
        for (std::size_t f = 0; f < 4; ++f) read(faces[f], f + 1);
        for (const auto* v : {&ground, &faces[0], &faces[1], &faces[2], &faces[3]})
            for (float x : *v)
                if (!std::isfinite(x) || x < 0.0f) return "holds a negative or non-finite value";
        const std::uint8_t* floats = at + texture_count * n * sizeof(std::uint16_t);
        probes.resize(probe_count);
        for (std::size_t i = 0; i < probe_count; ++i)
            for (std::size_t k = 0; k < probe_floats; ++k) {
                const float x = get<float>(floats + (i * probe_floats + k) * sizeof(float));
                if (!std::isfinite(x)) return "holds a non-finite probe";
                probes[i].c[k / 3][int(k % 3)] = x;
            }
        return std::nullopt;
    };
    const std::size_t part = texture_count * n * sizeof(std::uint16_t) + probe_count * probe_floats * sizeof(float);
    if (auto bad = read_part(payload, b.ground, b.faces, b.probes)) return make_error(*bad);
    b.probe_valid.resize(probe_count);
    for (std::size_t i = 0; i < probe_count; ++i) {
        b.probe_valid[i] = payload[part + i];
        if (b.probe_valid[i] > 1) return make_error("holds a probe flag other than 0 or 1");
    }
    const std::uint8_t* next = payload + part + probe_count;
    if (pulse) {
        if (auto bad = read_part(next, b.pulse.ground, b.pulse.faces, b.pulse.probes)) return make_error("pulsing part " + *bad);
        next += part;
    }
    b.sun_keys.resize(sun_keys);
    for (std::uint32_t k = 0; k < sun_keys; ++k, next += part)
        if (auto bad = read_part(next, b.sun_keys[k].ground, b.sun_keys[k].faces, b.sun_keys[k].probes))
            return make_error("sun key " + std::to_string(k) + " " + *bad);
    return b;
}

std::optional<ChunkBake> load_chunk(const std::string& dir, ChunkId c, std::uint64_t key, std::string* why) {
    const std::string path = (std::filesystem::path(dir) / chunk_file_name(c)).string();
    auto fail = [&](std::string reason) -> std::optional<ChunkBake> {
        if (why) *why = path + ": " + std::move(reason);
        return std::nullopt;
    };
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return fail("missing");
    // Deflate never grows data by more than 0.03 % plus a few bytes (compressBound).
    const std::size_t most = payload_bytes(16, true, max_sun_keys);
    auto bytes = read_binary_file(path, header_bytes + most + most / 1000 + 64);
    if (!bytes) return fail(bytes.error().message);
    auto b = decode_chunk(*bytes);
    if (!b) return fail(b.error().message);
    if (!(b->id == c)) return fail("holds chunk " + std::to_string(b->id.x) + ", " + std::to_string(b->id.z));
    if (b->key != key) return fail("stale: baked for other inputs (walls, materials, lights or settings changed)");
    return std::move(*b);
}

Result<void> save_chunk(const std::string& dir, const ChunkBake& b) {
    const std::vector<std::byte> bytes = encode_chunk(b);
    return write_file_atomic((std::filesystem::path(dir) / chunk_file_name(b.id)).string(), bytes);
}

} // namespace lantern::bake

#include "emitters.hpp"

#include "lantern/core/assert.hpp"

#include <algorithm>

namespace lantern::transport {
namespace {

std::vector<SourceRef> all_sources(const gi::FrameInputs& in) {
    std::vector<SourceRef> out;
    for (std::uint32_t i = 0; i < in.point_lights.size(); ++i)
        out.push_back({SourceKind::point, i});
    for (std::uint32_t i = 0; i < in.emissive_lights.size(); ++i)
        out.push_back({SourceKind::emissive, i});
    for (std::uint32_t i = 0; i < in.directional_lights.size(); ++i)
        out.push_back({SourceKind::directional, i});
    return out;
}

// The tile across the face must be air inside the domain (light from outside is lost).
bool face_in_domain(const Problem& p, FaceRef f) {
    const glm::ivec2 n(face_normal(f.face));
    const glm::ivec2 air = f.tile + n - p.domain.min_tile;
    const int tiles_x = p.domain.width / p.domain.resolution,
              tiles_z = p.domain.height / p.domain.resolution;
    return air.x >= 0 && air.y >= 0 && air.x < tiles_x && air.y < tiles_z &&
           face_exposed(p.inputs.walls, f);
}

} // namespace

EmitterTable EmitterTable::build(const Problem& p) {
    EmitterTable t;
    const std::vector<SourceRef> sources = all_sources(p.inputs);
    const int res = p.domain.resolution;
    const int tiles_x = p.domain.width / res, tiles_z = p.domain.height / res;
    for (int tz = 0; tz < tiles_z; ++tz)
        for (int tx = 0; tx < tiles_x; ++tx)
            for (int face = 0; face < 4; ++face) {
                const FaceRef f{p.domain.min_tile + glm::ivec2(tx, tz), face};
                if (!face_in_domain(p, f)) continue;
                const gi::GpuMaterial& m = p.materials[p.inputs.walls.cell(f.tile.x, f.tile.y)];
                const float reflects = std::max({m.albedo.r, m.albedo.g, m.albedo.b}),
                            emits = std::max({m.emission.r, m.emission.g, m.emission.b});
                auto add = [&](const Emitter& e) {
                    t.emitters_.push_back(e);
                    t.total_ += double(e.bound);
                    t.cumulative_.push_back(t.total_);
                };
                if (emits > 0.0f)
                    for (int k = 0; k < res; ++k) add({.face = f, .segment = k, .source = {}, .emission = true, .bound = emits});
                if (reflects <= 0.0f) continue; // a black wall sends no light on
                for (const SourceRef s : sources) {
                    if (source_face_bound(p.inputs, s, f, 0.0f, 1.0f) <= 0.0f)
                        continue; // whole face dark
                    for (int k = 0; k < res; ++k) {
                        const float bound = source_face_bound(p.inputs, s, f, float(k) / float(res),
                                                              float(k + 1) / float(res));
                        if (bound <= 0.0f) continue;
                        add({.face = f, .segment = k, .source = s, .emission = false, .bound = reflects * bound});
                    }
                }
            }
    return t;
}

const Emitter& EmitterTable::pick(double u) const {
    LANTERN_ASSERT(!emitters_.empty(), "pick() from an empty emitter table");
    const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), u * total_);
    const std::size_t i = std::min(std::size_t(it - cumulative_.begin()), emitters_.size() - 1);
    return emitters_[i];
}

} // namespace lantern::transport

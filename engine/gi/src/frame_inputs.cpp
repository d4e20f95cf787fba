#include "lantern/gi/frame_inputs.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::gi {

GpuPointLight pack_light(glm::vec2 position, glm::vec3 color, float intensity, float radius) {
    return GpuPointLight{glm::vec4(position, radius, 0.0f), glm::vec4(color * intensity, 0.0f)};
}

GpuShadowProxy pack_proxy(const scene::ShadowProxy& p, float strength) {
    return GpuShadowProxy{
        glm::vec4(p.position, p.size),
        glm::vec4(p.max_length, p.end_cap_blend, p.penumbra_width, p.penumbra_length),
        glm::vec4(p.penumbra_power, float(p.shape), float(p.width_mode), float(p.penumbra_mode)),
        glm::vec4(std::clamp(strength, 0.0f, 1.0f), 0.0f, 0.0f, 0.0f)};
}

float proxy_reach(const scene::ShadowProxy& p) {
    return std::max(p.size.x, p.size.y) + p.max_length + std::max(p.penumbra_width, p.penumbra_length);
}

bool sun_adds_light(glm::vec3 color, float intensity) {
    const glm::vec3 c = color * intensity;
    return std::max({c.r, c.g, c.b}) > 0.0f;
}

std::vector<std::uint32_t> gather_offers(const std::vector<Offer>& offers, const GiWindow& window, std::size_t cap) {
    return gather_offers_faded(offers, window, cap, 0.0f).ids;
}

FadedOffers gather_offers_faded(const std::vector<Offer>& offers, const GiWindow& window, std::size_t cap, float band) {
    FadedOffers out;
    std::vector<std::uint32_t>& ids = out.ids;
    for (std::uint32_t i = 0; i < offers.size(); ++i)
        if (distance_to_window(window, offers[i].position) <= offers[i].reach) ids.push_back(i);
    std::vector<float> priority;
    float cut = 0.0f;
    const bool capped = ids.size() > cap;
    if (capped) {
        const glm::vec2 center = window.center();
        priority.resize(offers.size());
        for (std::uint32_t i : ids) priority[i] = glm::distance(offers[i].position, center) - offers[i].bonus;
        std::sort(ids.begin(), ids.end(), [&](std::uint32_t a, std::uint32_t b) {
            return priority[a] != priority[b] ? priority[a] < priority[b] : offers[a].order < offers[b].order;
        });
        cut = priority[ids[cap]]; // the first offer left out
        ids.resize(cap);
    }
    std::sort(ids.begin(), ids.end(), [&](std::uint32_t a, std::uint32_t b) { return offers[a].order < offers[b].order; });
    out.fade.assign(ids.size(), 1.0f);
    if (capped && band > 0.0f)
        for (std::size_t k = 0; k < ids.size(); ++k) out.fade[k] = std::clamp((cut - priority[ids[k]]) / band, 0.0f, 1.0f);
    return out;
}

float distance_to_window(const GiWindow& w, glm::vec2 p) {
    const glm::vec2 lo(w.view.min_x, w.view.min_z);
    const glm::vec2 hi = lo + glm::vec2(w.view.width, w.view.height);
    return glm::length(glm::max(glm::max(lo - p, p - hi), glm::vec2(0.0f)));
}

GpuDirectionalLight pack_directional(const scene::DirectionalLight& l, scene::GiMethod method) {
    const glm::vec3 dir = glm::normalize(l.direction);
    const float multiplier = 1.0f / std::max(std::abs(dir.y), 0.02f);
    return GpuDirectionalLight{glm::vec4(dir, l.base_shadow_distance),
                               glm::vec4(l.color * l.intensity, multiplier),
                               glm::vec4(method == scene::GiMethod::gather ? 0.0f : l.bounce_intensity, 0.0f,
                                         0.0f, 0.0f)};
}

FrameInputs gather_frame_inputs(const scene::Scene& s, const GiWindow& window) {
    FrameInputs in;
    in.window = window;
    in.walls = WallView::of(s.walls);
    in.wall_height = s.wall_height;
    in.settings = s.gi;
    std::vector<Offer> offers;
    auto light_offers = [&](const auto& lights) {
        offers.clear();
        for (std::uint32_t i = 0; i < lights.size(); ++i) offers.push_back({lights[i].position, lights[i].radius, i});
        return offers;
    };
    in.point_light_ids = gather_offers(light_offers(s.point_lights), window, std::size_t(std::max(0, s.gi.max_lights)));
    for (std::uint32_t i : in.point_light_ids) {
        const auto& l = s.point_lights[i];
        in.point_lights.push_back(pack_light(l.position, l.color, l.intensity, l.radius));
    }
    in.emissive_ids = gather_offers(light_offers(s.emissive_lights), window, s.emissive_lights.size());
    for (std::uint32_t i : in.emissive_ids) {
        const auto& l = s.emissive_lights[i];
        in.emissive_lights.push_back(pack_light(l.position, l.color, l.intensity, l.radius));
    }
    for (const auto& d : s.directional_lights)
        if (sun_adds_light(d.color, d.intensity)) in.directional_lights.push_back(pack_directional(d, s.gi.method));
    offers.clear();
    for (std::uint32_t i = 0; i < s.shadow_proxies.size(); ++i)
        offers.push_back({s.shadow_proxies[i].position, proxy_reach(s.shadow_proxies[i]), i});
    in.proxy_ids = gather_offers(offers, window, std::size_t(std::max(0, s.gi.max_shadow_proxies)));
    for (std::uint32_t i : in.proxy_ids) in.proxies.push_back(pack_proxy(s.shadow_proxies[i]));
    for (const scene::Material& m : s.materials) in.materials.push_back(pack_material(m));
    return in;
}

void split_for_bake(FrameInputs& in, const scene::Scene& s) {
    auto split = [](std::vector<GpuPointLight>& live, std::vector<std::uint32_t>& ids, std::vector<GpuPointLight>& mixed,
                    const auto& lights) {
        std::vector<GpuPointLight> kept;
        std::vector<std::uint32_t> kept_ids;
        for (std::size_t k = 0; k < ids.size(); ++k) {
            const scene::LightMode mode = lights[ids[k]].mode;
            if (mode == scene::LightMode::mixed) mixed.push_back(live[k]);
            if (mode != scene::LightMode::realtime) continue;
            kept.push_back(live[k]);
            kept_ids.push_back(ids[k]);
        }
        live = std::move(kept);
        ids = std::move(kept_ids);
    };
    split(in.point_lights, in.point_light_ids, in.mixed_lights, s.point_lights);
    split(in.emissive_lights, in.emissive_ids, in.mixed_emissives, s.emissive_lights);
    // The suns, in gather_frame_inputs' order (those that add light).
    std::vector<GpuDirectionalLight> suns;
    std::size_t k = 0;
    for (const scene::DirectionalLight& d : s.directional_lights) {
        if (!sun_adds_light(d.color, d.intensity)) continue;
        if (k >= in.directional_lights.size()) break;
        GpuDirectionalLight sun = in.directional_lights[k++];
        if (d.mode == scene::LightMode::baked) continue;
        if (d.mode == scene::LightMode::mixed) mark_mixed(sun);
        suns.push_back(sun);
    }
    in.directional_lights = std::move(suns);
}

bool has_live_suns(const FrameInputs& in) {
    return std::any_of(in.directional_lights.begin(), in.directional_lights.end(),
                       [](const GpuDirectionalLight& s) { return !is_mixed_sun(s); });
}

bool has_mixed_suns(const FrameInputs& in) {
    return std::any_of(in.directional_lights.begin(), in.directional_lights.end(),
                       [](const GpuDirectionalLight& s) { return is_mixed_sun(s); });
}

bool penumbras_linear(const FrameInputs& in) {
    return std::all_of(in.proxies.begin(), in.proxies.end(), [](const GpuShadowProxy& p) { return p.modes.x == 1.0f; });
}

FrameInputs with_suns(const FrameInputs& in, bool mixed) {
    FrameInputs out = in;
    std::erase_if(out.directional_lights, [mixed](const GpuDirectionalLight& s) { return is_mixed_sun(s) != mixed; });
    return out;
}

FrameInputs warm_up_inputs(const FrameInputs& in) {
    FrameInputs out = in;
    const glm::vec2 c = in.window.center();
    const GpuPointLight light = pack_light(c, glm::vec3(1.0f, 0.8f, 0.6f), 1.0f, 4.0f);
    if (out.point_lights.empty()) {
        out.point_lights.push_back(light);
        out.point_light_ids.push_back(0);
    }
    if (in.baked && out.mixed_lights.empty()) out.mixed_lights.push_back(light);
    if (out.proxies.empty()) {
        scene::ShadowProxy p;
        p.position = c + glm::vec2(0.5f, 0.0f);
        out.proxies.push_back(pack_proxy(p));
        out.proxy_ids.push_back(0);
    }
    scene::DirectionalLight sun;
    sun.direction = glm::normalize(glm::vec3(0.4f, -0.8f, 0.3f));
    if (!has_live_suns(in)) out.directional_lights.push_back(pack_directional(sun, in.settings.method));
    if (in.baked && in.baked->sun_keys > 0 && !has_mixed_suns(in)) {
        GpuDirectionalLight mixed = pack_directional(sun, in.settings.method);
        mark_mixed(mixed);
        out.directional_lights.push_back(mixed);
    }
    return out;
}

GpuMaterial pack_material(const scene::Material& m) {
    // Seed 004's meta pass: opacity scales what the tile reflects and emits; emission GI
    // `none` keeps the glow out of the GI.
    const glm::vec3 emission = m.emission_gi == scene::EmissionGi::none ? glm::vec3(0.0f) : m.emission * m.opacity;
    return {glm::vec4(m.albedo * m.opacity, 0.0f), glm::vec4(emission, 0.0f)};
}

GpuMaterial material_of(const FrameInputs& in, std::uint8_t cell) {
    if (cell == 0) return {glm::vec4(0.0f), glm::vec4(0.0f)};
    const std::size_t k = std::size_t(cell) - std::size_t(scene::first_material_cell);
    GpuMaterial m = cell >= scene::first_material_cell && k < in.materials.size()
                        ? in.materials[k]
                        : GpuMaterial{glm::vec4(glm::vec3(in.settings.wall_albedo), 0.0f), glm::vec4(0.0f)};
    // Seed 004's meta pass: albedo^(1 / boost), clamped (boost 1 leaves it bit for bit).
    if (in.settings.albedo_boost != 1.0f)
        for (int c = 0; c < 3; ++c)
            m.albedo[c] = std::clamp(std::pow(m.albedo[c], 1.0f / in.settings.albedo_boost), 0.0f, 1.0f);
    return m;
}

std::vector<GpuMaterial> material_table(const FrameInputs& in) {
    std::vector<GpuMaterial> table(material_table_size);
    for (int cell = 0; cell < material_table_size; ++cell) table[std::size_t(cell)] = material_of(in, std::uint8_t(cell));
    return table;
}

bool has_emissive_materials(const FrameInputs& in) {
    for (const GpuMaterial& m : in.materials)
        if (m.emission.r > 0.0f || m.emission.g > 0.0f || m.emission.b > 0.0f) return true;
    return false;
}

} // namespace lantern::gi

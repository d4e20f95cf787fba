// C++ twin of shaders/include/lantern/shading.glsl.
#include "lantern/gi/shading.hpp"

#include "lantern/jobs/job_system.hpp"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lantern::gi {
namespace {

float saturate(float x) { return std::clamp(x, 0.0f, 1.0f); }

glm::ivec2 texel_at(const GiWindow& w, glm::vec2 p) {
    return {std::clamp(int(std::floor((p.x - w.view.min_x) * float(w.resolution))), 0, w.width - 1),
            std::clamp(int(std::floor((p.y - w.view.min_z) * float(w.resolution))), 0, w.height - 1)};
}

glm::vec3 fetch_rgb(const Texture* t, glm::ivec2 c) {
    if (!t) return glm::vec3(0.0f);
    const float* v = t->at(c.x, c.y);
    return {v[0], v[1], v[2]};
}

bool wall_at(const WallView& walls, glm::vec2 p) { return walls.is_wall(int(std::floor(p.x)), int(std::floor(p.y))); }

// Half a GI texel into the wall, so a face sample lands in the wall texel that stores it.
glm::vec2 wall_sample_position(const GiWindow& w, glm::vec3 pos, glm::vec3 normal) {
    return glm::vec2(pos.x, pos.z) - glm::vec2(normal.x, normal.z) * (0.5f / float(w.resolution));
}

// AO on a wall face (gi.ao.walls): the ground texel just outside the face, at the same
// place along it. `inside` is wall_sample_position, in the wall tile.
glm::vec2 face_ao_position(const GiWindow& w, glm::vec2 inside, glm::vec2 p, int face) {
    const glm::vec2 cell = glm::floor(inside);
    const float h = 0.5f / float(w.resolution);
    switch (face) {
    case face_pos_x: return {cell.x + 1.0f + h, p.y};
    case face_neg_x: return {cell.x - h, p.y};
    case face_pos_z: return {p.x, cell.y + 1.0f + h};
    default: return {p.x, cell.y - h};
    }
}

const GpuDirectionalLight* main_sun(const FrameInputs& f) {
    return f.directional_lights.empty() ? nullptr : &f.directional_lights.front();
}

float sun_angle(const GpuDirectionalLight& sun, float angle_scale) {
    return glm::mix(saturate(-sun.direction_base.y * 2.0f), 1.0f, angle_scale);
}

glm::vec3 ground_indirect_average(const ShadingInputs& in, glm::vec2 p) {
    const FrameInputs& f = *in.frame;
    const glm::vec2 cell_center = glm::floor(p) + 0.5f;
    glm::vec3 sum(0.0f);
    int n = 0;
    for (int dz = -1; dz <= 1; ++dz)
        for (int dx = -1; dx <= 1; ++dx) {
            const glm::vec2 q = cell_center + glm::vec2(float(dx), float(dz));
            if (wall_at(f.walls, q)) continue;
            sum += fetch_rgb(in.indirect, texel_at(f.window, q));
            ++n;
        }
    return n ? sum / float(n) : glm::vec3(0.0f);
}

} // namespace

glm::vec3 tone_map(glm::vec3 c, scene::ToneMap mode, float white_point) {
    c = glm::max(c, glm::vec3(0.0f));
    switch (mode) {
    case scene::ToneMap::none: return c;
    case scene::ToneMap::reinhard: return c / (1.0f + c);
    case scene::ToneMap::reinhard_white: return c * (1.0f + c / (white_point * white_point)) / (1.0f + c);
    case scene::ToneMap::aces: // Narkowicz's fit of the ACES filmic curve
        return glm::clamp((c * (2.51f * c + 0.03f)) / (c * (2.43f * c + 0.59f) + 0.14f), 0.0f, 1.0f);
    }
    return c;
}

int dominant_face(glm::vec3 n) {
    if (std::abs(n.x) >= std::abs(n.z)) return n.x >= 0.0f ? face_pos_x : face_neg_x;
    return n.z >= 0.0f ? face_pos_z : face_neg_z;
}

SurfaceKind classify_surface(const WallView& walls, const GiWindow& w, glm::vec3 pos, glm::vec3 n, bool wall_lighting) {
    if (!wall_lighting) return surface_ground; // gi.wall_lighting off: walls shade as ground
    const float nxz = std::sqrt(n.x * n.x + n.z * n.z);
    if (nxz >= 0.5f) {
        if (wall_at(walls, wall_sample_position(w, pos, n)) || wall_at(walls, {pos.x, pos.z})) return surface_wall_face;
    } else if (n.y >= 0.5f && nxz <= 0.35f) {
        if (wall_at(walls, glm::floor(glm::vec2(pos.x, pos.z)) + 0.5f)) return surface_wall_top;
    }
    return surface_ground;
}

namespace {

// A wall face's ambient occlusion at `pos` (1 without wall AO): the AO texel just outside it.
float wall_face_ao(const ShadingInputs& in, glm::vec2 inside, glm::vec3 pos, int face) {
    const FrameInputs& f = *in.frame;
    if (!f.settings.ao.walls || !in.ao) return 1.0f;
    const glm::ivec2 outside = texel_at(f.window, face_ao_position(f.window, inside, {pos.x, pos.z}, face));
    return in.ao->at(outside.x, outside.y)[0];
}

// A ground texel's bounce light: the indirect texture plus the suns' bounce, which fills
// their own shadows by bounce_intensity.
glm::vec3 ground_bounce(const ShadingInputs& in, glm::ivec2 t) {
    const FrameInputs& f = *in.frame;
    glm::vec3 indirect = fetch_rgb(in.indirect, t);
    const float sun_visibility = in.shadow ? in.shadow->at(t.x, t.y)[1] : 0.0f;
    for (const GpuDirectionalLight& sun : f.directional_lights)
        indirect += glm::vec3(sun.color_multiplier) * sun_angle(sun, f.settings.directional_angle_scale) *
                    sun.bounce.x * (1.0f - sun_visibility);
    return indirect;
}

} // namespace

glm::vec3 surface_light(const ShadingInputs& in, glm::vec3 pos, glm::vec3 n) {
    const FrameInputs& f = *in.frame;
    const GiWindow& w = f.window;
    switch (classify_surface(f.walls, w, pos, n, f.settings.wall_lighting)) {
    case surface_wall_face: {
        const glm::vec2 inside = wall_sample_position(w, pos, n);
        const glm::ivec2 t = texel_at(w, inside);
        const int face = dominant_face(n);
        glm::vec3 direct = fetch_rgb(in.wall_direct[face], t);
        if (const Texture* upper = in.wall_upper[face]) { // above the proxies' shadow edge: the light at the top
            const float* u = upper->at(t.x, t.y);
            if (pos.y >= u[3]) direct = glm::vec3(u[0], u[1], u[2]);
        }
        return (direct + fetch_rgb(in.wall_indirect[face], t)) * wall_face_ao(in, inside, pos, face);
    }
    case surface_wall_top: {
        glm::vec3 direct(0.0f);
        if (const GpuDirectionalLight* sun = main_sun(f))
            direct = glm::vec3(sun->color_multiplier) * sun_angle(*sun, f.settings.directional_angle_scale);
        return direct + ground_indirect_average(in, {pos.x, pos.z});
    }
    case surface_ground: break;
    }
    const glm::ivec2 t = texel_at(w, {pos.x, pos.z});
    glm::vec3 combined = fetch_rgb(in.direct, t) + ground_bounce(in, t);
    if (in.ao) combined *= in.ao->at(t.x, t.y)[0];
    combined *= wall_at(f.walls, {pos.x, pos.z}) ? 0.0f : 1.0f; // conduction
    return combined;
}

glm::vec3 surface_bounce(const ShadingInputs& in, glm::vec3 pos, glm::vec3 n) {
    const FrameInputs& f = *in.frame;
    const GiWindow& w = f.window;
    switch (classify_surface(f.walls, w, pos, n, f.settings.wall_lighting)) {
    case surface_wall_face: {
        const glm::vec2 inside = wall_sample_position(w, pos, n);
        const int face = dominant_face(n);
        return fetch_rgb(in.wall_indirect[face], texel_at(w, inside)) * wall_face_ao(in, inside, pos, face);
    }
    case surface_wall_top: return ground_indirect_average(in, {pos.x, pos.z});
    case surface_ground: break;
    }
    const glm::ivec2 t = texel_at(w, {pos.x, pos.z});
    glm::vec3 indirect = ground_bounce(in, t);
    if (in.ao) indirect *= in.ao->at(t.x, t.y)[0];
    return wall_at(f.walls, {pos.x, pos.z}) ? glm::vec3(0.0f) : indirect;
}

glm::vec3 shade(const ShadingInputs& in, glm::vec3 pos, glm::vec3 n) {
    return tone_map(surface_light(in, pos, n), in.frame->settings.tone_map, in.frame->settings.white_point);
}

void lit_surface_at(const FrameInputs& f, int x, int y, glm::vec3& pos, glm::vec3& normal) {
    const GiWindow& w = f.window;
    const glm::vec2 p = w.texel_center(x, y);
    const glm::ivec2 cell(int(std::floor(p.x)), int(std::floor(p.y)));
    pos = glm::vec3(p.x, 0.0f, p.y);
    normal = glm::vec3(0.0f, 1.0f, 0.0f);
    if (!f.walls.is_wall(cell.x, cell.y)) return;
    pos.y = f.wall_height;
    // Texels from each exposed edge, inside this tile.
    const int res = w.resolution;
    const int lx = int(std::floor((p.x - float(cell.x)) * float(res))), lz = int(std::floor((p.y - float(cell.y)) * float(res)));
    const int band = std::max(1, res / 4);
    // Only faces the GI computes (gi.wall_lighting, gi.wall_faces) show: the others have no light.
    const glm::vec4 mask = wall_face_mask(f.walls, cell) * face_bits_mask(computed_faces(f.settings));
    const int distance[4] = {res - 1 - lx, lx, res - 1 - lz, lz};
    static constexpr glm::vec3 normals[4] = {{1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}};
    int best = -1;
    for (int face = 0; face < 4; ++face)
        if (mask[face] > 0.0f && distance[face] < band && (best < 0 || distance[face] < distance[best])) best = face;
    if (best >= 0) {
        normal = normals[best];
        pos.y = f.wall_height * 0.5f;
    }
}

std::uint8_t linear_to_srgb8(float v) {
    v = saturate(v);
    const float s = v <= 0.0031308f ? v * 12.92f : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    return std::uint8_t(std::floor(s * 255.0f + 0.5f));
}

Image reference_lit_image(const ShadingInputs& in, const RefOptions& options) {
    const GiWindow& w = in.frame->window;
    Image img{w.width, w.height, std::vector<std::uint8_t>(std::size_t(w.width) * std::size_t(w.height) * 3)};
    auto row = [&](int y) {
        for (int x = 0; x < w.width; ++x) {
            glm::vec3 pos, n;
            lit_surface_at(*in.frame, x, y, pos, n);
            const glm::vec3 c = shade(in, pos, n);
            std::uint8_t* px = &img.rgb[(std::size_t(y) * std::size_t(w.width) + std::size_t(x)) * 3];
            px[0] = linear_to_srgb8(c.r);
            px[1] = linear_to_srgb8(c.g);
            px[2] = linear_to_srgb8(c.b);
        }
    };
    if (options.jobs)
        options.jobs->parallel_for("gi.reference", 0, std::uint32_t(w.height), 8,
                                   [&](std::uint32_t b, std::uint32_t e, std::uint32_t) {
                                       for (std::uint32_t y = b; y < e; ++y) row(int(y));
                                   });
    else
        for (int y = 0; y < w.height; ++y) row(y);
    return img;
}

} // namespace lantern::gi

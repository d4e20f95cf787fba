// The radiosity method's raymarch (seed 003's GI shader) on the radiosity grid, with
// temporal accumulation: N rays per texel, equally spaced, turned by the texel's blue-noise
// angle and the frame's shift; each ray steps through the distance field in fixed point
// until it finds a wall texel (distance steps < epsilon), then returns the brighter of the
// wall's light and the light one texel back in empty space; the seed's brightness
// normalisation. Mirrors radiosity_texel and reference_radiosity_march exactly: integer
// positions (1/4096 texel), step lengths (1/256 texel) and directions (a table of 4096).
// size = grid (w, h, pitch, -); parameters: RadiosityParams.
#version 450
#extension GL_GOOGLE_include_directive : require
struct RadiosityParams {
    int rays, steps;
    int epsilon_steps;     // hit when the distance steps < this
    int shift;             // the frame's angle shift (1/4096 turns)
    int noise_origin;      // the grid's global texel origin mod 64, x | y << 8; -1: no per-texel noise
    float accumulate_weight; // 1: replace; else previous + (new - previous) x weight
    float own_weight;        // the seed's own term: last frame's light at the texel x this
    int pad0;
};
#define GI_PASS_PARAMS RadiosityParams
#include "lantern/gi_common.glsl"

layout(binding = 0) uniform samplerBuffer u_light;
layout(binding = 1) uniform usamplerBuffer u_steps;
layout(binding = 2) uniform isamplerBuffer u_directions; // 4096 x (cos, sin) x 4096
layout(binding = 3) uniform usamplerBuffer u_noise;      // 64 x 64 blue-noise ranks
layout(std430, binding = 4) buffer Radiosity { uvec2 texels[]; } o_radiosity;

const int POSITION_UNIT = 4096;
const int STEP_MARGIN = 363;

int steps_at(ivec2 c) { return int(texelFetch(u_steps, texel_index(c.x, c.y)).r); }
vec3 light_at(ivec2 c) { return texelFetch(u_light, texel_index(c.x, c.y)).rgb; }
float max3(vec3 v) { return max(v.r, max(v.g, v.b)); }

// The smallest t >= 0 with t * den >= num: a float estimate corrected by integer products.
int ceil_div(int num, int den) {
    int t = int(float(num) / float(den));
    if (t * den < num) ++t;
    if (t > 0 && (t - 1) * den >= num) --t;
    return t;
}
int exit_steps(int p, int c, int d) {
    if (d > 0) return ceil_div(((c + 1) * POSITION_UNIT - p) * 256, d);
    if (d < 0) return ceil_div((p - c * POSITION_UNIT) * 256 + 1, -d);
    return 65535;
}

vec3 march(ivec2 start, ivec2 d, int dq0) {
    ivec2 p = start * POSITION_UNIT + POSITION_UNIT / 2;
    ivec2 c = start;
    int dq = dq0;
    for (int s = 0; s < pc.pass.steps; ++s) {
        int t = min(max(dq - STEP_MARGIN, min(exit_steps(p.x, c.x, d.x), exit_steps(p.y, c.y, d.y))), 65535);
        p += (d * t) >> 8;
        c = p >> 12;
        if (c.x < 0 || c.y < 0 || c.x >= pc.size.x || c.y >= pc.size.y) break;
        dq = steps_at(c);
        if (dq < pc.pass.epsilon_steps) {
            ivec2 back = clamp((p - d) >> 12, ivec2(0), pc.size.xy - 1);
            return max(light_at(c), light_at(back));
        }
    }
    return vec3(0.0);
}

vec3 radiosity(int i, int j, vec3 previous) {
    int dq0 = steps_at(ivec2(i, j));
    if (dq0 < pc.pass.epsilon_steps) return light_at(ivec2(i, j)); // the seed's early out: inside a wall
    // The seed's own term: the texel's last light (its base texture holds the last frame).
    vec3 own = pc.pass.own_weight > 0.0 ? previous * pc.pass.own_weight : vec3(0.0);
    int base = 0;
    int origin = pc.pass.noise_origin;
    if (origin >= 0)
        base = int(texelFetch(u_noise, ((j + (origin >> 8)) & 63) * 64 + ((i + (origin & 255)) & 63)).r);
    vec3 sum = own;
    float brightness = max3(own);
    for (int k = 0; k < pc.pass.rays; ++k) {
        ivec2 d = texelFetch(u_directions, (base + pc.pass.shift + k * 4096 / pc.pass.rays) & 4095).xy;
        vec3 hit = march(ivec2(i, j), d, dq0);
        sum += hit;
        brightness += max3(hit);
    }
    return brightness > 0.0 ? (sum / brightness) * (brightness / float(pc.pass.rays)) : vec3(0.0);
}

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int j = o.y + int(r);
        if (j >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int i = o.x + k;
            if (i >= pc.size.x) break;
            float w = pc.pass.accumulate_weight;
            // Last frame's radiosity at this texel (only read when the own term or the
            // accumulation needs it: on the first frame the buffer holds nothing yet).
            precise vec3 previous = w < 1.0 || pc.pass.own_weight > 0.0
                                        ? unpack_rgba16f(o_radiosity.texels[texel_index(i, j)]).rgb
                                        : vec3(0.0);
            precise vec3 value = radiosity(i, j, previous);
            if (w < 1.0) value = previous + (value - previous) * w;
            o_radiosity.texels[texel_index(i, j)] = pack_rgba16f(vec4(value, 1.0));
        }
    }
}

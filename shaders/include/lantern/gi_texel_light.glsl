// The light one texel gathers in the direct and directional passes (gi_direct.comp.glsl,
// gi_directional.comp.glsl; reference_passes.cpp TexelLight is its C++ twin).
#ifndef LANTERN_GI_TEXEL_LIGHT_GLSL
#define LANTERN_GI_TEXEL_LIGHT_GLSL

struct TexelLight {
    vec3 color;   // ground light
    float shadow; // max visibility
    vec3 face[4]; // per wall face (+x, -x, +z, -z), at the face's foot
    // Unfolded proxy shadows (gi.proxy_wall_shadows): the light at each face's top, and the
    // shadow edge's height summed weighted by the light the shadow takes.
    vec3 upper[4];
    float edge_sum[4];
    float edge_weight[4];
};

TexelLight no_texel_light() {
    TexelLight t;
    t.color = vec3(0.0);
    t.shadow = 0.0;
    for (int f = 0; f < 4; ++f) {
        t.face[f] = t.upper[f] = vec3(0.0);
        t.edge_sum[f] = t.edge_weight[f] = 0.0;
    }
    return t;
}

// Light `light` reaching face f with grid visibility `grid` and the proxies' (foot, top, edge) `s`.
// f may vary per invocation: every face adds, the others zero (exact: x + 0 = x), so no
// face array is indexed dynamically (lavapipe runs every branch of an if anyway).
void add_face(inout TexelLight t, int f, vec3 light, float grid, vec3 s) {
    float low = min(grid, s.x), high = min(grid, s.y);
    float taken = (light.r + light.g + light.b) * (high - low);
    for (int k = 0; k < 4; ++k) {
        bool on = k == f;
        t.face[k] += on ? light * low : vec3(0.0);
        t.upper[k] += on ? light * high : vec3(0.0);
        t.edge_sum[k] += on ? taken * s.z : 0.0;
        t.edge_weight[k] += on ? taken : 0.0;
    }
}
// Light `light` reaching face f (no unfolded proxy shadows).
void add_face_light(inout TexelLight t, int f, vec3 light) {
    for (int k = 0; k < 4; ++k) t.face[k] += k == f ? light : vec3(0.0);
}

float face_edge(TexelLight t, int f) { return t.edge_weight[f] > 0.0 ? t.edge_sum[f] / t.edge_weight[f] : 0.0; }

#endif

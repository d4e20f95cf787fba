// The mixed lights' direct light (the mixed pass's textures, read as texel buffers) added to
// the frame's: direct, the wall faces computed (FACES) and, with unfolded proxy shadows
// (FEATURES bit 1), the upper faces; rgb only, each texture's alpha (face flags, the
// proxies' edge heights) kept. Run by the baked pass, after the live indirect passes
// (docs/baked.md, "At run time"). C++ reference: engine/gi/src/rows/baked.cpp.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "lantern/gi_common.glsl"

const bool UPPER = (FEATURES & 1u) != 0u;

// The mixed pass's textures: direct, faces px nx pz nz, uppers px nx pz nz.
layout(binding = 0) uniform samplerBuffer u_direct;
layout(binding = 1) uniform samplerBuffer u_face_px;
layout(binding = 2) uniform samplerBuffer u_face_nx;
layout(binding = 3) uniform samplerBuffer u_face_pz;
layout(binding = 4) uniform samplerBuffer u_face_nz;
layout(binding = 5) uniform samplerBuffer u_upper_px;
layout(binding = 6) uniform samplerBuffer u_upper_nx;
layout(binding = 7) uniform samplerBuffer u_upper_pz;
layout(binding = 8) uniform samplerBuffer u_upper_nz;
// The frame's, added to in place.
layout(std430, binding = 9) buffer Out0 { uvec2 texels[]; } io_direct;
layout(std430, binding = 10) buffer Out1 { uvec2 texels[]; } io_face_px;
layout(std430, binding = 11) buffer Out2 { uvec2 texels[]; } io_face_nx;
layout(std430, binding = 12) buffer Out3 { uvec2 texels[]; } io_face_pz;
layout(std430, binding = 13) buffer Out4 { uvec2 texels[]; } io_face_nz;
layout(std430, binding = 14) buffer Out5 { uvec2 texels[]; } io_upper_px;
layout(std430, binding = 15) buffer Out6 { uvec2 texels[]; } io_upper_nx;
layout(std430, binding = 16) buffer Out7 { uvec2 texels[]; } io_upper_pz;
layout(std430, binding = 17) buffer Out8 { uvec2 texels[]; } io_upper_nz;

bool computes_face(uint faces, int face) { return ((faces >> uint(face)) & 1u) != 0u; }

uvec2 plus(uvec2 old, vec4 add) {
    vec4 o = unpack_rgba16f(old);
    return pack_rgba16f(vec4(o.rgb + add.rgb, o.a));
}

void main() {
    ivec2 o = block_origin();
    if (o.x >= pc.size.x) return;
    for (uint r = 0; r < BLOCK_H; ++r) {
        int y = o.y + int(r);
        if (y >= pc.size.y) return;
        for (int k = 0; k < 4; ++k) {
            int x = o.x + k;
            if (x >= pc.size.x) continue;
            int i = texel_index(x, y);
            io_direct.texels[i] = plus(io_direct.texels[i], texelFetch(u_direct, i));
            if (!HAS_WALLS) continue; // no wall in the window: the faces hold nothing
            if (computes_face(FACES, 0)) io_face_px.texels[i] = plus(io_face_px.texels[i], texelFetch(u_face_px, i));
            if (computes_face(FACES, 1)) io_face_nx.texels[i] = plus(io_face_nx.texels[i], texelFetch(u_face_nx, i));
            if (computes_face(FACES, 2)) io_face_pz.texels[i] = plus(io_face_pz.texels[i], texelFetch(u_face_pz, i));
            if (computes_face(FACES, 3)) io_face_nz.texels[i] = plus(io_face_nz.texels[i], texelFetch(u_face_nz, i));
            if (!UPPER) continue;
            if (computes_face(FACES, 0)) io_upper_px.texels[i] = plus(io_upper_px.texels[i], texelFetch(u_upper_px, i));
            if (computes_face(FACES, 1)) io_upper_nx.texels[i] = plus(io_upper_nx.texels[i], texelFetch(u_upper_nx, i));
            if (computes_face(FACES, 2)) io_upper_pz.texels[i] = plus(io_upper_pz.texels[i], texelFetch(u_upper_pz, i));
            if (computes_face(FACES, 3)) io_upper_nz.texels[i] = plus(io_upper_nz.texels[i], texelFetch(u_upper_nz, i));
        }
    }
}

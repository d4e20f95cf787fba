// One fetch from the GI texture `t` (shading.glsl's GI_* ids) at texel index `index`, for
// shaders that bind the GI textures as uniform texel buffers under the names below (the lit
// image pass gi_lit.comp.glsl and the game's world shaders). With `t` a constant at the call
// site (as the shading library's calls are) the chain folds to one fetch.
//
// Requires shading.glsl's ids and the declarations u_direct, u_indirect, u_ao, u_shadow,
// u_wall_direct_{px,nx,pz,nz}, u_wall_indirect_{px,nx,pz,nz}, u_wall_upper_{px,nx,pz,nz}
// (samplerBuffer).
#ifndef LANTERN_GI_TEXTURE_FETCH_GLSL
#define LANTERN_GI_TEXTURE_FETCH_GLSL

vec4 gi_texture_fetch(int t, int index) {
    if (t == GI_DIRECT) return texelFetch(u_direct, index);
    if (t == GI_INDIRECT) return texelFetch(u_indirect, index);
    if (t == GI_AO) return texelFetch(u_ao, index);
    if (t == GI_SHADOW) return texelFetch(u_shadow, index);
    if (t == GI_WALL_DIRECT + 0) return texelFetch(u_wall_direct_px, index);
    if (t == GI_WALL_DIRECT + 1) return texelFetch(u_wall_direct_nx, index);
    if (t == GI_WALL_DIRECT + 2) return texelFetch(u_wall_direct_pz, index);
    if (t == GI_WALL_DIRECT + 3) return texelFetch(u_wall_direct_nz, index);
    if (t == GI_WALL_INDIRECT + 0) return texelFetch(u_wall_indirect_px, index);
    if (t == GI_WALL_INDIRECT + 1) return texelFetch(u_wall_indirect_nx, index);
    if (t == GI_WALL_INDIRECT + 2) return texelFetch(u_wall_indirect_pz, index);
    if (t == GI_WALL_INDIRECT + 3) return texelFetch(u_wall_indirect_nz, index);
    if (t == GI_WALL_UPPER + 0) return texelFetch(u_wall_upper_px, index);
    if (t == GI_WALL_UPPER + 1) return texelFetch(u_wall_upper_nx, index);
    if (t == GI_WALL_UPPER + 2) return texelFetch(u_wall_upper_pz, index);
    return texelFetch(u_wall_upper_nz, index);
}

#endif

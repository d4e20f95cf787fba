// The wall grid as shaders read it: tile lookups in the toroidal wall buffer.
//
// Requires before inclusion: a block instance `pc` with ivec4 `grid` (width, height,
// origin x, origin z) and ivec4 `grid_phase` (the GI passes' push constants, or the game's
// frame uniforms), and `usamplerBuffer u_walls` (R8_UINT, 0 = air, else a wall and its material).
#ifndef LANTERN_GI_WALLS_GLSL
#define LANTERN_GI_WALLS_GLSL

// The wall grid is a pc.grid.xy rectangle of tiles from world tile pc.grid.zw, stored
// toroidally with phase pc.grid_phase.xy (a streaming world rewrites only changed chunks):
// engine/gi/include/lantern/gi/frame_inputs.hpp WallView.
bool in_grid(int x, int z) {
    int c = x - pc.grid.z, r = z - pc.grid.w;
    return c >= 0 && r >= 0 && c < pc.grid.x && r < pc.grid.y;
}
// The tile's cell value: 0 air (also out of bounds), else a wall of that material
// (lantern/scene/scene.hpp: 1 the default wall, 2 + k the scene's material k).
uint wall_cell(int x, int z) {
    if (!in_grid(x, z)) return 0u;
    int c = x - pc.grid.z + pc.grid_phase.x, r = z - pc.grid.w + pc.grid_phase.y;
    if (c >= pc.grid.x) c -= pc.grid.x;
    if (r >= pc.grid.y) r -= pc.grid.y;
    return texelFetch(u_walls, r * pc.grid.x + c).r;
}
bool is_wall(int x, int z) { return wall_cell(x, z) != 0u; }
bool is_wall(ivec2 c) { return is_wall(c.x, c.y); }

#endif

// The gather's ray traversal (gather.hpp gather_trace, integer for integer): shared by the
// gather (gi_gather.comp.glsl) and the live probes (gi_probes.comp.glsl). The includer's
// parameters (pc.pass) have the GatherFrame's fields origin_x, origin_z, offset (x | y << 8 |
// resolution << 16), tiles (x | y << 16) and window (width | height << 16), and it includes
// lantern/gi_walls.glsl (is_wall) first.
#ifndef LANTERN_GI_GATHER_TRACE_GLSL
#define LANTERN_GI_GATHER_TRACE_GLSL

const int UNIT = 4096;     // fixed point: 1/4096 tile (gather_unit)
const int MAX_STEPS = 255; // gather_max_steps

ivec2 origin_tile() { return ivec2(pc.pass.origin_x, pc.pass.origin_z); }
ivec2 offset() { return ivec2(pc.pass.offset & 255, (pc.pass.offset >> 8) & 255); }
int resolution() { return pc.pass.offset >> 16; }
ivec2 tiles() { return ivec2(pc.pass.tiles & 0xFFFF, pc.pass.tiles >> 16); }
ivec2 window_size() { return ivec2(pc.pass.window & 0xFFFF, pc.pass.window >> 16); }
int window_index(int x, int y) { return y * ((window_size().x + 3) & ~3) + x; }

// gather_trace: the first wall tile the ray enters (face -1: none), and the window texel
// holding that face at the entry point.
int trace(ivec2 p, ivec2 cell, ivec2 d, out ivec2 texel) {
    texel = ivec2(0);
    int sx = d.x > 0 ? 1 : d.x < 0 ? -1 : 0, sz = d.y > 0 ? 1 : d.y < 0 ? -1 : 0;
    uint ax = uint(abs(d.x)), az = uint(abs(d.y));
    int nx = sx > 0 ? (cell.x + 1) * UNIT - p.x : p.x - cell.x * UNIT;
    int nz = sz > 0 ? (cell.y + 1) * UNIT - p.y : p.y - cell.y * UNIT;
    ivec2 n_tiles = tiles(), off = offset(), size = window_size();
    int r = resolution();
    int max_steps = min(n_tiles.x + n_tiles.y + 2, MAX_STEPS);
    for (int s = 0; s < max_steps; ++s) {
        bool step_x = az == 0u || (ax != 0u && uint(nx) * az <= uint(nz) * ax);
        int face, t_num;
        if (step_x) {
            cell.x += sx;
            t_num = nx;
            nx += UNIT;
            face = sx > 0 ? 1 : 0;
        } else {
            cell.y += sz;
            t_num = nz;
            nz += UNIT;
            face = sz > 0 ? 3 : 2;
        }
        if (cell.x < 0 || cell.y < 0 || cell.x >= n_tiles.x || cell.y >= n_tiles.y) return -1;
        if (!is_wall(origin_tile() + cell)) continue;
        if (step_x) {
            int dz = int((az * uint(t_num)) / ax);
            int along = sz >= 0 ? p.y + dz : p.y - dz;
            int row = clamp((along * r) / UNIT, cell.y * r, cell.y * r + r - 1);
            texel = ivec2((face == 1 ? cell.x * r : cell.x * r + r - 1) - off.x, row - off.y);
        } else {
            int dx = int((ax * uint(t_num)) / az);
            int along = sx >= 0 ? p.x + dx : p.x - dx;
            int col = clamp((along * r) / UNIT, cell.x * r, cell.x * r + r - 1);
            texel = ivec2(col - off.x, (face == 3 ? cell.y * r : cell.y * r + r - 1) - off.y);
        }
        if (texel.x < 0 || texel.y < 0 || texel.x >= size.x || texel.y >= size.y) return -1;
        return face;
    }
    return -1;
}

#endif

// The transport reference's per-texel outputs: RGB values over a GI window's texel grid
// (ground fluence, standard errors) and over the exposed faces of its wall tiles (face
// irradiance). Plain floats, not quantised to a GPU storage format.
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace lantern::transport {

// One RGB value per texel of a width x height grid, row-major, row 0 at the window's min z.
struct RgbField {
    int width = 0, height = 0;
    std::vector<float> rgb; // width * height * 3

    RgbField() = default;
    RgbField(int w, int h) : width(w), height(h), rgb(std::size_t(w) * std::size_t(h) * 3, 0.0f) {}

    std::size_t index(int x, int y) const {
        return (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
    }
    glm::vec3 at(int x, int y) const {
        const float* v = &rgb[index(x, y)];
        return {v[0], v[1], v[2]};
    }
    void set(int x, int y, glm::vec3 v) {
        float* d = &rgb[index(x, y)];
        d[0] = v.x, d[1] = v.y, d[2] = v.z;
    }
    friend bool operator==(const RgbField&, const RgbField&) = default;
};

// The wall-face segments of a window: the face of a tile is split into `resolution`
// segments, one per texel along it. Faces are indexed like gi::Face (+X, -X, +Z, -Z). A
// +-X face segment is addressed by (tile column, texel row), a +-Z one by (tile row, texel
// column), so any texel (i, j) of a wall tile finds its faces' segments at its own position
// along them, as Lantern's wall textures store face light.
struct FaceLayout {
    int resolution = 1;        // texels per world unit
    int width = 0, height = 0; // the window's texel grid

    int tiles_x() const { return (width + resolution - 1) / resolution; }
    int tiles_z() const { return (height + resolution - 1) / resolution; }
    std::size_t segments() const {
        return 2 * (std::size_t(tiles_x()) * std::size_t(height) +
                    std::size_t(tiles_z()) * std::size_t(width));
    }
    // The segment of `face` seen from texel (i, j) of its tile (0 <= i < width, 0 <= j < height).
    std::size_t segment(int face, int i, int j) const {
        const std::size_t x_faces = std::size_t(tiles_x()) * std::size_t(height);
        if (face < 2)
            return std::size_t(face) * x_faces + std::size_t(i / resolution) * std::size_t(height) +
                   std::size_t(j);
        return 2 * x_faces + std::size_t(face - 2) * std::size_t(tiles_z()) * std::size_t(width) +
               std::size_t(j / resolution) * std::size_t(width) + std::size_t(i);
    }
    friend bool operator==(const FaceLayout&, const FaceLayout&) = default;
};

// One RGB value per face segment of a layout. Faces that are not exposed (a wall on the
// other side) and tiles that are not walls hold 0.
struct FaceField {
    FaceLayout layout;
    std::vector<float> rgb; // layout.segments() * 3

    FaceField() = default;
    explicit FaceField(FaceLayout l) : layout(l), rgb(l.segments() * 3, 0.0f) {}

    glm::vec3 at(int face, int i, int j) const {
        const float* v = &rgb[layout.segment(face, i, j) * 3];
        return {v[0], v[1], v[2]};
    }
    void set(int face, int i, int j, glm::vec3 v) {
        float* d = &rgb[layout.segment(face, i, j) * 3];
        d[0] = v.x, d[1] = v.y, d[2] = v.z;
    }
    friend bool operator==(const FaceField&, const FaceField&) = default;
};

} // namespace lantern::transport

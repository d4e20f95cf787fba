// A transport problem: the output window, the transport domain around it as a texel grid
// with its walls, and the sources that reach the domain.
#pragma once

#include "lantern/core/result.hpp"
#include "lantern/gi/frame_inputs.hpp"
#include "lantern/transport/solver.hpp"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace lantern::transport {

// The domain as texels at the output resolution: whole tiles, the window plus the margin.
struct Domain {
    int resolution = 1;
    glm::ivec2 min_tile{0};    // world tile of domain texel (0, 0)
    int width = 0, height = 0; // texels
    int offset = 0;            // output texel (0, 0) is domain texel (offset, offset)
    int window_width = 0, window_height = 0;
    std::vector<std::uint8_t> wall; // per domain texel: its tile's cell value (0 air, else a wall's material)

    bool contains(glm::ivec2 t) const {
        return t.x >= 0 && t.y >= 0 && t.x < width && t.y < height;
    }
    bool is_wall(glm::ivec2 t) const { return cell(t) != 0; }
    std::uint8_t cell(glm::ivec2 t) const {
        return wall[std::size_t(t.y) * std::size_t(width) + std::size_t(t.x)];
    }
    // Output-window texel of a domain texel; inside the window when in_window() holds.
    glm::ivec2 to_window(glm::ivec2 t) const { return t - offset; }
    bool in_window(glm::ivec2 w) const {
        return w.x >= 0 && w.y >= 0 && w.x < window_width && w.y < window_height;
    }
};

struct Problem {
    gi::GiWindow window;    // the output window
    gi::FrameInputs inputs; // window = the domain; all sources reaching it; the scene's walls
    Domain domain;
    // Per wall cell value: albedo and emission (gi::material_table; the default wall's
    // albedo is TransportSettings::albedo).
    std::vector<gi::GpuMaterial> materials;

    glm::dvec3 albedo(std::uint8_t cell) const { return glm::dvec3(glm::vec3(materials[cell].albedo)); }
    glm::dvec3 emission(std::uint8_t cell) const { return glm::dvec3(glm::vec3(materials[cell].emission)); }
};

// Builds the problem of a scene. `inputs.walls` refers to scene.walls: the problem must not
// outlive the scene. Errors: no GI window for the view.
Result<Problem> make_problem(const scene::Scene& scene, const TransportSettings& settings);

} // namespace lantern::transport

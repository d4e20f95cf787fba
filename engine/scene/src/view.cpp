// The ground a perspective camera sees (scene.hpp: ground_footprint).
#include "lantern/scene/scene.hpp"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>
#include <limits>

namespace lantern::scene {
namespace {

bool finite(glm::vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

void set_reason(std::string* reason, const char* text) {
    if (reason) *reason = text;
}

} // namespace

std::optional<GroundArea> ground_footprint(const PerspectiveCamera& c, std::string* reason) {
    using dvec3 = glm::dvec3;
    const dvec3 origin(c.position);
    dvec3 forward = dvec3(c.target) - origin;
    const double forward_len = glm::length(forward);
    if (!(forward_len > 1e-9) || !std::isfinite(forward_len)) {
        set_reason(reason, "camera position and target coincide or are not finite");
        return std::nullopt;
    }
    forward /= forward_len;
    // Screen up follows world +y; a camera looking straight down uses +z instead (only the
    // footprint's bounding box matters, so the choice does not change the window).
    dvec3 up_hint = std::abs(forward.y) > 0.999 ? dvec3(0, 0, 1) : dvec3(0, 1, 0);
    dvec3 right = glm::normalize(glm::cross(forward, up_hint));
    dvec3 up = glm::cross(right, forward);
    const double half_h = std::tan(double(c.fov_deg) * 0.5 * 3.14159265358979323846 / 180.0);
    const double half_w = half_h * double(c.aspect);
    glm::dvec2 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    for (int corner = 0; corner < 4; ++corner) {
        double sx = (corner & 1) ? 1.0 : -1.0, sy = (corner & 2) ? 1.0 : -1.0;
        dvec3 dir = glm::normalize(forward + right * (sx * half_w) + up * (sy * half_h));
        if (std::abs(dir.y) < 1e-4) {
            set_reason(reason, "a viewport corner ray is parallel to the ground");
            return std::nullopt;
        }
        double t = -origin.y / dir.y;
        if (!(t > 0.0) || !std::isfinite(t)) {
            set_reason(reason, "a viewport corner ray does not hit the ground in front of the camera");
            return std::nullopt;
        }
        dvec3 hit = origin + dir * t;
        lo = glm::min(lo, glm::dvec2(hit.x, hit.z));
        hi = glm::max(hi, glm::dvec2(hit.x, hit.z));
    }
    GroundArea area{glm::vec2(lo), glm::vec2(hi - lo)};
    if (!finite(area.min) || !finite(area.size)) {
        set_reason(reason, "the camera footprint is not finite");
        return std::nullopt;
    }
    return area;
}

} // namespace lantern::scene

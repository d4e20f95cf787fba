#include "lantern/gi/passes.hpp"

#include <cmath>

namespace lantern::gi {

bool walls_in_window(const FrameInputs& in) {
    const CameraView& v = in.window.view;
    const int x0 = int(std::floor(v.min_x)), z0 = int(std::floor(v.min_z));
    const int x1 = int(std::ceil(v.min_x + v.width)), z1 = int(std::ceil(v.min_z + v.height));
    for (int z = z0; z < z1; ++z)
        for (int x = x0; x < x1; ++x)
            if (in.walls.is_wall(x, z)) return true;
    return false;
}

} // namespace lantern::gi

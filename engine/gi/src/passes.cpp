#include "lantern/gi/passes.hpp"

#include <cmath>

namespace lantern::gi {

const char* pass_name(Pass p) {
    static constexpr const char* names[pass_count] = {"conduction", "ao",   "direct",        "directional", "emission",
                                                      "heat",       "blur", "wall_indirect", "lit"};
    return names[int(p)];
}

bool walls_in_window(const FrameInputs& in) {
    const CameraView& v = in.window.view;
    const int x0 = int(std::floor(v.min_x)), z0 = int(std::floor(v.min_z));
    const int x1 = int(std::ceil(v.min_x + v.width)), z1 = int(std::ceil(v.min_z + v.height));
    for (int z = z0; z < z1; ++z)
        for (int x = x0; x < x1; ++x)
            if (in.walls.is_wall(x, z)) return true;
    return false;
}

PassPlan plan_passes(const FrameInputs& in, bool lit_image, Pass through) {
    PassPlan plan;
    plan.has_walls_in_window = walls_in_window(in);
    for (int p = 0; p <= int(through) && p < pass_count; ++p) plan.run.add(Pass(p));
    for (int p = int(through) + 1; p < pass_count; ++p) plan.reason[p] = "not requested";
    auto leave_out = [&](Pass p, const char* why) {
        if (!plan.run.has(p)) return;
        plan.run.remove(p);
        plan.reason[int(p)] = why;
    };
    if (!in.settings.ao.enabled) leave_out(Pass::ao, "AO disabled");
    if (in.directional_lights.empty()) leave_out(Pass::directional, "no directional lights");
    if (!in.settings.blur) leave_out(Pass::blur, "blur disabled");
    if (!plan.has_walls_in_window) leave_out(Pass::wall_indirect, "no walls in the GI window");
    if (!lit_image) leave_out(Pass::lit, "no lit image requested");
    return plan;
}

} // namespace lantern::gi

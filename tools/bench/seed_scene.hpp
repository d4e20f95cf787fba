// The configuration of seed 000's performance table as a Lantern scene: internal 480x270
// pixels (a 30 x 16.875-tile view), padding 1.4, 20 heat rounds, radius-10 point lights
// spread over the window, 38 shadow proxies, optional emissives and a sun, over procedural
// caves (so walls are present, as in the seed's captures).
#pragma once

#include "lantern/scene/scene.hpp"

#include <string>
#include <vector>

namespace lantern::bench {

struct SeedRow {
    int resolution = 16;
    scene::HeatScale scale = scene::HeatScale::full;
    int points = 1;
    int emissives = 0;
    int directionals = 0;
    // heat (seed 000) or radiosity (seed 003, its grid at `scale`, default rays and steps)
    scene::GiMethod method = scene::GiMethod::heat;
    int bounces = 2; // gather: gi.gather.bounces (the cost of one more bounce from two rows)
    std::string label() const;
};

// The rows of the seed's giResolution 16 and 8 tables, in its order, then the many-light
// rows and seed 003's radiosity beside them.
std::vector<SeedRow> seed_rows();
scene::Scene seed_scene(const SeedRow& row);

} // namespace lantern::bench

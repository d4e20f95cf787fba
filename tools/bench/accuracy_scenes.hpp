// The scenes of lantern-bench accuracy: procedural ones built in code and two real maps
// from ../shared/maps/dao (skipped, with a note, when that folder is absent). Every view is
// the seed's: 30 x 16.875 tiles (480x270 pixels at 16 per tile), padding 1.4.
#pragma once

#include "lantern/scene/scene.hpp"

#include <string>
#include <vector>

namespace lantern::bench {

struct AccuracyScene {
    std::string name;        // file-name safe
    std::string description; // one line for the report
    scene::Scene scene;
};

// All scenes (quick: only "rooms"), each with a note in `notes` for what was skipped.
std::vector<AccuracyScene> accuracy_scenes(const std::string& maps_dir, bool quick,
                                           std::vector<std::string>& notes);

} // namespace lantern::bench

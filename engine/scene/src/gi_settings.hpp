// Internal: reading the "gi" object of a scene and single `--set gi.KEY=VALUE` keys, both
// through one table of keys, ranges and fields (gi_settings.cpp) so that files, overrides
// and validate_gi_settings cannot disagree.
#pragma once

#include "lantern/scene/json_reader.hpp"
#include "lantern/scene/scene.hpp"

#include <string_view>

namespace lantern::scene::reading {

// Reads the members of the "gi" object at JSON path "gi" into `gi`; absent keys keep
// their values. Returns reader.ok().
bool read_gi_settings(Reader& reader, const json::Value& object, GiSettings& gi);

// Reads one key given as a dotted path below "gi" ("resolution", "ao.radius"), reporting
// problems under the path "gi.<key>". Returns reader.ok().
bool read_gi_key(Reader& reader, std::string_view key, const json::Value& value, GiSettings& gi);

} // namespace lantern::scene::reading

// Internal: the rule for MapImportOptions::extra_floor_chars, shared by the importer and
// the scene loader (which reports it at the position of "extra_floor_chars").
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace lantern::scene::reading {

// What is wrong with `chars` as extra floor characters, or nothing when they are usable:
// printable ASCII, none of the Moving AI characters ".GSW@OT".
std::optional<std::string> extra_floor_chars_problem(std::string_view chars);

} // namespace lantern::scene::reading

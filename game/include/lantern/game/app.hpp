// The game: a window with the timer HUD when a display can open, else (or with
// --headless) the scripted demo writing screenshots and the profiler report. docs/game.md.
#pragma once

#include "lantern/game/extension.hpp"
#include "lantern/game/options.hpp"

#include <vector>

namespace lantern::game {

// Runs the game as `options` say, with `extensions`' systems and save data (extension.hpp).
// Returns the process exit status: 0 success, 1 a runtime failure (no Vulkan device, cannot
// write output, a malformed extension), 2 bad input (world or save files).
int run_game(const GameOptions& options, std::vector<GameExtension> extensions = {});

} // namespace lantern::game

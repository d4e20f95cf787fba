// Extending the game from outside the engine (docs/extending.md, examples/fireflies): an
// extension adds its own systems to the frame's schedule and its own data to saves,
// without editing Lantern.
//
//   game::GameExtension fireflies;
//   fireflies.name = "fireflies";
//   fireflies.setup = [](ecs::World& w) { w.set_resource<FireflyRules>(); };
//   fireflies.add_systems = [](ecs::Schedule& s) { s.add("fireflies", ...).reads<...>().writes<...>(); };
//   fireflies.save = [](ecs::World& w, json::Writer& out) { ... one JSON value ... };
//   fireflies.load = [](ecs::World& w, const json::Value& v, scene::reading::Reader& r, const std::string& path) { ... };
//   return game::run_game(options, {fireflies});
//
// Contract (all hooks run on the main thread, between frames, never concurrently):
//  - setup(world): once per session (start, and every load: a load makes a new session),
//    after the game made its world and before any system runs. Create resources here.
//  - add_systems(schedule): once per session, after the game's gameplay systems and before
//    the baker and the frame's own systems (camera_view ... gpu_submit), so an
//    extension's systems may name gameplay systems in after(). The schedule orders them by
//    their declared access like any other (lantern --schedule draws the result).
//  - save(world, writer): when the game saves; writes exactly one JSON value, stored in the
//    save under "extensions": {"<name>": value}. Entities an extension saves itself carry
//    game::ExtensionOwned, so the game's own entity list leaves them out (a firefly is an
//    EmissiveLight the game would otherwise save as a plain light).
//  - load(world, value, reader, path): after setup, when a save is loaded and has the
//    extension's value; validate with the reader (reader.fail(value.position(), path, ...)
//    or scene::reading::Fields) and apply only when reader.ok() at the end: the game turns
//    the first problem into "save.json:LINE:COL: extensions.NAME...: what", refuses the save
//    (exit status 2 at start-up, a HUD message on F9) and drops the half-made session.
//    Before an in-game load (F9) drops the running world, load also runs once on a scratch
//    world holding only what setup made, to check the data: it must touch nothing else.
//  A save holding data for an extension this game does not have loads with a warning; that
//  data is not carried into the next save.
#pragma once

#include "lantern/core/json.hpp"
#include "lantern/core/json_writer.hpp"
#include "lantern/core/result.hpp"
#include "lantern/ecs/schedule.hpp"
#include "lantern/ecs/world.hpp"
#include "lantern/scene/json_reader.hpp"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace lantern::game {

// On entities an extension saves and loads itself: the game's save leaves them out.
struct ExtensionOwned {};

struct GameExtension {
    std::string name; // the key in the save's "extensions" object: [a-z0-9_]+, unique
    std::function<void(ecs::World&)> setup;
    std::function<void(ecs::Schedule&)> add_systems;
    std::function<void(ecs::World&, json::Writer&)> save;
    std::function<void(ecs::World&, const json::Value&, scene::reading::Reader&, const std::string& path)> load;
};

// An extension's data in a save: its name and the JSON value its save hook wrote.
using ExtensionData = std::vector<std::pair<std::string, json::Value>>;

// What the extensions' save hooks write for this world (in the order of `extensions`).
ExtensionData capture_extensions(const std::vector<GameExtension>& extensions, ecs::World& world);

// Runs each extension's load hook on its data in `data` (read from `file`); the first
// problem as "<file>:<line>:<col>: extensions.<name>...: <what>" (exit status 2). Data for
// an extension not in `extensions` is skipped and named in `ignored`.
Result<void> load_extensions(const std::vector<GameExtension>& extensions, const ExtensionData& data,
                             ecs::World& world, const std::string& file, std::vector<std::string>* ignored = nullptr);

// Checks names ([a-z0-9_]+, unique) and that every hook a save needs is there (save and
// load come together); the message names the extension.
Result<void> check_extensions(const std::vector<GameExtension>& extensions);

} // namespace lantern::game

// The sandbox game with fireflies: Lantern's game, its options and its schedule, plus one
// extension from outside the tree (fireflies.hpp). `fireflies --help` lists the game's options.
#include "fireflies.hpp"

#include <lantern/game/app.hpp>

int main(int argc, char** argv) {
    lantern::game::GameOptions options;
    if (auto exit = lantern::game::parse_options(argc, argv, options)) return *exit;
    return lantern::game::run_game(options, {fireflies::extension()});
}

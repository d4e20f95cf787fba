// lantern: the sandbox game. `lantern --help` lists the options; docs/game.md the game.
#include "lantern/game/app.hpp"

int main(int argc, char** argv) {
    lantern::game::GameOptions options;
    if (auto exit = lantern::game::parse_options(argc, argv, options)) return *exit;
    return lantern::game::run_game(options);
}

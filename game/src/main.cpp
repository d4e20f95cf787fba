// lantern: the sandbox game. `lantern --help` lists the options; docs/game.md the game.
#include "lantern/game/app.hpp"

#include <cstdio>

int main(int argc, char** argv) {
    bool help = false;
    auto options = lantern::game::parse_options(argc, argv, &help);
    if (!options) {
        std::fprintf(stderr, "%s\n", options.error().message.c_str());
        return options.error().exit_code;
    }
    if (help) {
        std::fputs(lantern::game::usage().c_str(), stdout);
        return 0;
    }
    return lantern::game::run_game(*options);
}

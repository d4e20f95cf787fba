#include "render_cli.hpp"

int main(int argc, char** argv) { return lantern::tools::render_main(argc, argv); }

// libFuzzer target: the game's settings file. Settings that parse are written again and read
// back: they must read, and read as the same settings.
#include "lantern/game/settings.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    auto settings = lantern::game::parse_settings(text, "fuzz.json");
    if (settings) {
        auto again = lantern::game::parse_settings(lantern::game::format_settings(*settings), "again.json");
        if (!again || !(*again == *settings)) std::abort(); // what Lantern writes must read back the same
    }
    return 0;
}

// The HUD's GI views by name (lantern/game/gi_view.hpp).
#include "lantern/game/gi_view.hpp"

#include <array>
#include <cstddef>

namespace lantern::game {
namespace {

constexpr std::array<const char*, std::size_t(GiDebugView::count)> view_names = {
    "lit", "direct", "indirect", "light_image", "radiosity", "distance", "direction", "jump_flood", "baked", "bricks"};

} // namespace

std::span<const char* const> gi_debug_view_names() {
    return view_names;
}

std::optional<GiDebugView> gi_debug_view_by_name(std::string_view name) {
    for (std::size_t i = 0; i < view_names.size(); ++i)
        if (name == view_names[i]) return GiDebugView(i);
    return std::nullopt;
}

} // namespace lantern::game

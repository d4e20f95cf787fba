#include "lantern/game/extension.hpp"

#include "lantern/core/assert.hpp"
#include "lantern/core/text.hpp"

#include <algorithm>

namespace lantern::game {

ExtensionData capture_extensions(const std::vector<GameExtension>& extensions, ecs::World& world) {
    ExtensionData out;
    for (const GameExtension& e : extensions) {
        if (!e.save) continue;
        json::Writer w;
        e.save(world, w);
        // Parsed back, so a save holds values (written with the save's own writer) and a
        // hook that wrote anything but one well-formed value is caught here, not on load.
        auto value = json::parse(w.take(), "extension " + e.name);
        LANTERN_ASSERT(value.ok(), "an extension's save hook must write one JSON value");
        out.emplace_back(e.name, std::move(*value));
    }
    return out;
}

Result<void> load_extensions(const std::vector<GameExtension>& extensions, const ExtensionData& data,
                             ecs::World& world, const std::string& file, std::vector<std::string>* ignored) {
    for (const auto& entry : data) { // not a structured binding: clang 14 cannot capture one
        const std::string& name = entry.first;
        const json::Value& value = entry.second;
        auto e = std::find_if(extensions.begin(), extensions.end(), [&](const GameExtension& x) { return x.name == name; });
        if (e == extensions.end() || !e->load) {
            if (ignored) ignored->push_back(name);
            continue;
        }
        scene::reading::Reader reader("the save");
        e->load(world, value, reader, "extensions." + name);
        if (!reader.ok()) return scene::reading::issue_error(file, reader.issue());
    }
    return {};
}

Result<void> check_extensions(const std::vector<GameExtension>& extensions) {
    for (std::size_t i = 0; i < extensions.size(); ++i) {
        const GameExtension& e = extensions[i];
        const bool name_ok = !e.name.empty() && e.name.size() <= 64 && std::all_of(e.name.begin(), e.name.end(), [](char c) {
                                 return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
                             });
        if (!name_ok)
            return make_error("game extension " + std::to_string(i) + ": name '" + printable(e.name, 80) +
                                  "' must be 1 to 64 of [a-z0-9_]",
                              1);
        for (std::size_t j = 0; j < i; ++j)
            if (extensions[j].name == e.name) return make_error("game extension '" + e.name + "' given twice", 1);
        if (bool(e.save) != bool(e.load))
            return make_error("game extension '" + e.name + "': save and load come together (one without the other "
                              "would lose its data on the next load)",
                              1);
    }
    return {};
}

} // namespace lantern::game

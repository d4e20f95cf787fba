#include "lantern/scene/loader.hpp"

#include "gi_settings.hpp"
#include "lantern/scene/color.hpp"
#include "lantern/scene/json_reader.hpp"
#include "lantern/core/file.hpp"
#include "lantern/core/json.hpp"
#include "moving_ai_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace lantern::scene {
namespace {

using reading::any_number;
using reading::world_coordinate;
using reading::at_least;
using reading::between;
using reading::EnumName;
using reading::Fields;
using reading::greater_than;
using reading::IntRange;
using reading::Reader;
using reading::read_directional_light;
using reading::read_emissive_light;
using reading::read_point_light;
using reading::read_shadow_proxy;

constexpr int supported_version = 1;
// World positions are floats, which hold whole tiles exactly only up to 2^24.
constexpr int max_origin = 1 << 24;
constexpr float tree_proxy_radius = 0.4f;
constexpr int max_material_regions = 4096;
constexpr float tree_proxy_max_length = 3.0f;

constexpr std::array<EnumName<TreeMode>, 2> tree_modes{{
    {"wall", TreeMode::wall},
    {"proxy", TreeMode::proxy},
}};
constexpr std::array<EnumName<LightMode>, 3> light_modes{{
    {"realtime", LightMode::realtime},
    {"mixed", LightMode::mixed},
    {"baked", LightMode::baked},
}};
constexpr std::array<EnumName<EmissionGi>, 3> emission_gi_modes{{
    {"baked", EmissionGi::baked},
    {"realtime", EmissionGi::realtime},
    {"none", EmissionGi::none},
}};
constexpr std::array<EnumName<BakeSolver>, 2> bake_solvers{{
    {"gather", BakeSolver::gather},
    {"seed002", BakeSolver::seed002},
}};
constexpr std::array<EnumName<ProxyShape>, 2> proxy_shapes{{
    {"box", ProxyShape::box},
    {"circle", ProxyShape::circle},
}};
constexpr std::array<EnumName<WidthMode>, 2> width_modes{{
    {"projected", WidthMode::projected},
    {"max_axis", WidthMode::max_axis},
}};
constexpr std::array<EnumName<PenumbraMode>, 3> penumbra_modes{{
    {"inward", PenumbraMode::inward},
    {"outward", PenumbraMode::outward},
    {"both", PenumbraMode::both},
}};

// What "world" says about a map file; the import runs once the whole scene has been read.
struct MapSpec {
    std::string path;        // as written, relative to the scene's folder; empty for "rows"
    json::Position position; // of the "map" value
    MapImportOptions options;
};

Error file_error(const std::string& file, const reading::Issue& issue) {
    return reading::issue_error(file, issue);
}

std::string grid_size_text(std::size_t width, std::size_t height) {
    return std::to_string(width) + " x " + std::to_string(height);
}

// Checks the size of a "rows" grid from its first row, before any cell is stored.
bool check_rows_size(Reader& reader, const json::Value& rows, std::size_t width,
                     std::size_t height) {
    const json::Value& first = rows.as_array()[0];
    if (width == 0) return reader.fail(first.position(), "world.rows[0]", "row is empty");
    if (width > std::size_t(max_grid_side))
        return reader.fail(first.position(), "world.rows[0]",
                           "row has " + std::to_string(width) + " cells, above the limit of " +
                               std::to_string(max_grid_side));
    if (height > std::size_t(max_grid_side) || std::int64_t(width * height) > max_grid_cells)
        return reader.fail(rows.position(), "world.rows",
                           "a grid of " + grid_size_text(width, height) +
                               " cells is above the limits (" + std::to_string(max_grid_side) +
                               " per side, " + std::to_string(max_grid_cells) + " in all)");
    return true;
}

// The cell value of each row character: '#' the default wall, '.' floor, and each
// material's symbol its material's wall; -1 for the rest.
using RowLegend = std::array<int, 256>;

RowLegend row_legend(const std::vector<Material>& materials, const std::vector<char>& symbols) {
    RowLegend legend;
    legend.fill(-1);
    legend[std::uint8_t('#')] = default_wall_cell;
    legend[std::uint8_t('.')] = 0;
    for (std::size_t k = 0; k < materials.size(); ++k)
        if (symbols[k] != 0) legend[std::uint8_t(symbols[k])] = material_cell(int(k));
    return legend;
}

// One row string: '#' wall, '.' floor, a material's symbol its wall. A bad character is
// reported at its own column (exact as long as the characters before it are not spelled as
// \u escapes).
bool read_row(Reader& reader, const json::Value& row, const std::string& path, std::size_t width,
              const RowLegend& legend, std::vector<std::uint8_t>& cells) {
    if (!reader.expect(row, path, json::Type::string)) return false;
    const std::string& text = row.as_string();
    if (text.size() != width)
        return reader.fail(row.position(), path,
                           "row has " + std::to_string(text.size()) + " cells, row 0 has " +
                               std::to_string(width));
    for (std::size_t col = 0; col < text.size(); ++col) {
        const int cell = legend[std::uint8_t(text[col])];
        if (cell < 0) {
            const json::Position at{row.position().line, row.position().column + 1 + int(col)};
            return reader.fail(at, path,
                               "unknown cell character " + reading::quote_char(text[col]) +
                                   " (rows use '#' for wall, '.' for floor and the symbols of "
                                   "\"materials\")");
        }
        cells.push_back(std::uint8_t(cell));
    }
    return true;
}

// Fills the size and cells of `grid` (not its origin) from "rows".
void read_rows(Reader& reader, const json::Value& rows, const RowLegend& legend, WallGrid& grid) {
    if (!reader.expect(rows, "world.rows", json::Type::array)) return;
    const json::Value::Array& items = rows.as_array();
    if (items.empty()) {
        reader.fail(rows.position(), "world.rows", "needs at least one row");
        return;
    }
    if (!reader.expect(items[0], "world.rows[0]", json::Type::string)) return;
    const std::size_t width = items[0].as_string().size();
    if (!check_rows_size(reader, rows, width, items.size())) return;
    // No reserve from the first row's size: the other rows may be empty, and memory must
    // follow the input's size, not what it claims.
    std::vector<std::uint8_t> cells;
    for (std::size_t row = 0; row < items.size(); ++row)
        if (!read_row(reader, items[row], reading::index_path("world.rows", row), width, legend, cells))
            return;
    grid.width = int(width);
    grid.height = int(items.size());
    grid.cells = std::move(cells);
}

void read_map_spec(Reader& reader, Fields& world, MapSpec& map) {
    world.required("map", map.path)
        .optional("trees", map.options.trees, tree_modes)
        .optional("extra_floor_chars", map.options.extra_floor_chars);
    if (!reader.ok()) return;
    map.position = world.find("map")->position();
    if (map.path.empty()) world.fail("map", "must name a map file");
    if (auto problem = reading::extra_floor_chars_problem(map.options.extra_floor_chars))
        world.fail("extra_floor_chars", *problem);
}

void read_world(Reader& reader, const json::Value& value, const RowLegend& legend, Scene& scene,
                MapSpec& map) {
    Fields world(reader, value, "world",
                 {"map", "rows", "origin", "wall_height", "trees", "extra_floor_chars"});
    world.optional("origin", scene.walls.origin, IntRange{-max_origin, max_origin})
        .optional("wall_height", scene.wall_height, greater_than(0.0));
    const std::string_view source = world.one_of("map", "rows");
    if (source == "map") {
        read_map_spec(reader, world, map);
    } else if (source == "rows") {
        for (std::string_view key : {"trees", "extra_floor_chars"})
            if (world.find(key)) world.fail(key, "applies to \"map\" worlds only");
        if (reader.ok()) read_rows(reader, *world.find("rows"), legend, scene.walls);
    }
}

void read_camera(Reader& reader, const json::Value& value, PerspectiveCamera& camera) {
    constexpr reading::Range fov_range{.min = 0.0, .max = 180.0, .min_open = true, .max_open = true};
    Fields fields(reader, value, "camera", {"position", "target", "fov_deg", "aspect"});
    fields.required("position", camera.position, world_coordinate)
        .required("target", camera.target, world_coordinate)
        .optional("fov_deg", camera.fov_deg, fov_range)
        .optional("aspect", camera.aspect, greater_than(0.0));
    if (fields.ok() && camera.position == camera.target)
        fields.fail("target", "must differ from camera.position");
    // The renderer needs the ground rectangle the camera sees: refused here, with the
    // camera's position, rather than at the first frame.
    std::string why;
    if (fields.ok() && !ground_footprint(camera, &why)) fields.fail("target", "the camera sees no ground: " + why);
}

void read_view(Reader& reader, Fields& top, ViewSpec& view) {
    const std::string_view kind = top.one_of("view", "camera");
    if (kind == "view") {
        OrthoView ortho;
        Fields(reader, *top.find("view"), "view", {"center", "size"})
            .required("center", ortho.center, world_coordinate)
            .optional("size", ortho.size, greater_than(0.0));
        view = ortho;
    } else if (kind == "camera") {
        PerspectiveCamera camera;
        read_camera(reader, *top.find("camera"), camera);
        view = camera;
    }
}

// What is wrong with the GI texture size of the scene's view, if anything: a top-down view's
// size, or the ground a perspective camera sees (the game may move the camera later; its
// windows are then checked by the GI code each frame).
std::optional<std::string> gi_window_problem(const ViewSpec& view, const GiSettings& gi) {
    glm::vec2 size(0.0f);
    const bool ortho_view = std::holds_alternative<OrthoView>(view);
    if (const OrthoView* ortho = std::get_if<OrthoView>(&view)) {
        size = ortho->size;
    } else if (auto ground = ground_footprint(std::get<PerspectiveCamera>(view))) {
        size = ground->size;
    } else {
        return std::nullopt; // refused by read_camera
    }
    const double texels_per_unit = double(gi.padding) * gi.resolution;
    const double width = double(size.x) * texels_per_unit;
    const double height = double(size.y) * texels_per_unit;
    if (width <= max_gi_texels_per_side && height <= max_gi_texels_per_side) return std::nullopt;
    return "the GI texture would be " + reading::format_number(std::ceil(width)) + " x " +
           reading::format_number(std::ceil(height)) +
           " texels (" + (ortho_view ? "view.size" : "the ground the camera sees") +
           " x gi.padding x gi.resolution), above the limit of " +
           reading::format_number(max_gi_texels_per_side) + " per side";
}

void check_gi_window(Reader& reader, const Fields& top, const Scene& scene) {
    if (!reader.ok()) return;
    const std::optional<std::string> problem = gi_window_problem(scene.view, scene.gi);
    if (!problem) return;
    const bool ortho = std::holds_alternative<OrthoView>(scene.view);
    const json::Value& view = *top.find(ortho ? "view" : "camera");
    if (const json::Value* size = view.find("size"); ortho && size)
        reader.fail(size->position(), "view.size", *problem);
    else
        reader.fail(view.position(), ortho ? "view" : "camera", *problem);
}

template <typename T>
using ReadItem = void (*)(Reader&, const json::Value&, const std::string&, T&);

// An optional list of objects; an absent key leaves `out` empty.
template <typename T>
void read_list(Reader& reader, const Fields& top, std::string_view key, ReadItem<T> read_item,
               std::vector<T>& out) {
    const json::Value* list = top.find(key);
    const std::string path(key);
    if (!list || !reader.expect(*list, path, json::Type::array)) return;
    const json::Value::Array& items = list->as_array();
    out.reserve(items.size());
    for (std::size_t i = 0; i < items.size(); ++i) {
        T item;
        read_item(reader, items[i], reading::index_path(path, i), item);
        if (!reader.ok()) return;
        out.push_back(item);
    }
}

// "materials": names unique, of letters, digits and '_'; symbols unique, printable, not
// '#', '.' or a space. `symbols` gets each material's symbol (0: none).
void read_materials(Reader& reader, const Fields& top, std::vector<Material>& out,
                    std::vector<char>& symbols) {
    const json::Value* list = top.find("materials");
    if (!list || !reader.expect(*list, "materials", json::Type::array)) return;
    const json::Value::Array& items = list->as_array();
    if (items.size() > std::size_t(max_materials)) {
        reader.fail(list->position(), "materials",
                    "has " + std::to_string(items.size()) + " materials, above the limit of " +
                        std::to_string(max_materials));
        return;
    }
    for (std::size_t i = 0; i < items.size() && reader.ok(); ++i) {
        const std::string path = reading::index_path("materials", i);
        Material m;
        std::string symbol;
        Fields fields(reader, items[i], path, {"name", "albedo", "emission", "gi", "opacity", "pulse", "symbol"});
        fields.required("name", m.name)
            .optional("albedo", m.albedo, between(0.0, 1.0))
            .optional("emission", m.emission, at_least(0.0))
            .optional("gi", m.emission_gi, emission_gi_modes)
            .optional("opacity", m.opacity, between(0.0, 1.0))
            .optional("pulse", m.pulse, between(0.0, 60.0))
            .optional("symbol", symbol);
        if (!reader.ok()) return;
        if (m.pulse > 0.0f) {
            if (m.emission_gi != EmissionGi::baked) {
                fields.fail("pulse", "only a baked glow pulses (\"gi\": \"baked\"): its light is baked apart and "
                                     "scaled at run time");
                return;
            }
            for (const Material& earlier : out)
                if (earlier.pulse > 0.0f && earlier.pulse != m.pulse) {
                    fields.fail("pulse", "every pulsing material pulses at one frequency (the bake keeps one pulsing "
                                         "part); \"" + earlier.name + "\" pulses at " + reading::format_float(earlier.pulse) + " Hz");
                    return;
                }
        }
        const bool word = !m.name.empty() && m.name.size() <= 64 &&
                          std::all_of(m.name.begin(), m.name.end(), [](char c) {
                              return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                                     (c >= '0' && c <= '9') || c == '_';
                          });
        if (!word) {
            fields.fail("name", "must be 1 to 64 letters, digits or '_', got \"" +
                                    reading::shorten(m.name) + "\"");
            return;
        }
        for (const Material& earlier : out)
            if (earlier.name == m.name) {
                fields.fail("name", "material \"" + m.name + "\" is defined twice");
                return;
            }
        char c = 0;
        if (fields.find("symbol")) {
            if (symbol.size() != 1 || symbol[0] <= ' ' || symbol[0] > '~' || symbol[0] == '#' ||
                symbol[0] == '.') {
                fields.fail("symbol", "must be one printable ASCII character other than '#', '.' "
                                      "and space, got \"" + reading::shorten(symbol) + "\"");
                return;
            }
            c = symbol[0];
            for (std::size_t k = 0; k < out.size(); ++k)
                if (symbols[k] == c) {
                    fields.fail("symbol", "symbol " + reading::quote_char(c) + " is taken by material \"" +
                                              out[k].name + "\"");
                    return;
                }
        }
        out.push_back(std::move(m));
        symbols.push_back(c);
    }
}

// "material_regions": which rectangle of tiles (inclusive world tiles) takes which material;
// read before the map import, applied after it, in order, to the wall tiles inside.
struct MaterialRegion {
    glm::ivec2 min{0}, max{0};
    std::uint8_t cell = default_wall_cell;
};

void read_material_regions(Reader& reader, const Fields& top, const std::vector<Material>& materials,
                           std::vector<MaterialRegion>& out) {
    const json::Value* list = top.find("material_regions");
    if (!list || !reader.expect(*list, "material_regions", json::Type::array)) return;
    if (list->as_array().size() > std::size_t(max_material_regions)) {
        reader.fail(list->position(), "material_regions",
                    "has " + std::to_string(list->as_array().size()) + " regions, above the limit of " +
                        std::to_string(max_material_regions));
        return;
    }
    for (std::size_t i = 0; i < list->as_array().size() && reader.ok(); ++i) {
        const std::string path = reading::index_path("material_regions", i);
        MaterialRegion region;
        std::string name;
        Fields fields(reader, list->as_array()[i], path, {"material", "min", "max"});
        fields.required("material", name)
            .required("min", region.min, IntRange{-max_origin, max_origin})
            .required("max", region.max, IntRange{-max_origin, max_origin});
        if (!reader.ok()) return;
        if (region.max.x < region.min.x || region.max.y < region.min.y) {
            fields.fail("max", "must not be below min in x or z");
            return;
        }
        const auto it = std::find_if(materials.begin(), materials.end(),
                                     [&](const Material& m) { return m.name == name; });
        if (it == materials.end()) {
            fields.fail("material", "unknown material \"" + reading::shorten(name) +
                                        "\" (not in \"materials\")");
            return;
        }
        region.cell = material_cell(int(it - materials.begin()));
        out.push_back(region);
    }
}

// Last region wins. Painted from the last region back, each row keeping a "next cell not yet
// decided" link per cell (path-halving), so every cell is visited once however the regions
// overlap: O(rows x regions + cells), never regions x area (hostile input).
void apply_material_regions(const std::vector<MaterialRegion>& regions, WallGrid& grid) {
    if (regions.empty() || grid.width <= 0) return;
    std::vector<int> next(std::size_t(grid.width) + 1);
    auto find = [&](int c) {
        while (next[std::size_t(c)] != c) {
            next[std::size_t(c)] = next[std::size_t(next[std::size_t(c)])];
            c = next[std::size_t(c)];
        }
        return c;
    };
    for (int row = 0; row < grid.height; ++row) {
        const std::int64_t z = std::int64_t(grid.origin.y) + row;
        bool reset = false;
        for (auto r = regions.rbegin(); r != regions.rend(); ++r) {
            if (z < r->min.y || z > r->max.y) continue;
            // In 64 bits: the region may reach far beyond the grid.
            const std::int64_t c0 = std::max<std::int64_t>(0, std::int64_t(r->min.x) - grid.origin.x),
                               c1 = std::min<std::int64_t>(grid.width - 1, std::int64_t(r->max.x) - grid.origin.x);
            if (c0 > c1) continue;
            if (!reset) {
                for (int c = 0; c <= grid.width; ++c) next[std::size_t(c)] = c;
                reset = true;
            }
            for (int c = find(int(c0)); c <= int(c1); c = find(c)) {
                std::uint8_t& cell = grid.cells[std::size_t(row) * std::size_t(grid.width) + std::size_t(c)];
                if (cell != 0) cell = r->cell;
                next[std::size_t(c)] = c + 1; // decided
            }
        }
    }
}

void read_version(Reader& reader, Fields& top) {
    int version = 0;
    top.required("lantern_scene", version, IntRange{});
    if (reader.ok() && version != supported_version)
        top.fail("lantern_scene", "version " + std::to_string(version) +
                                      " is not supported; this build reads version " +
                                      std::to_string(supported_version));
}

// Everything but the map import, in a fixed order; the first problem is kept.
// "bake.density": regions of chunks baked at their own resolution (BakeDensity).
void read_bake_density(Reader& reader, const json::Value& list, std::vector<BakeDensity>& out) {
    if (!reader.expect(list, "bake.density", json::Type::array)) return;
    if (list.as_array().size() > std::size_t(max_bake_density_regions)) {
        reader.fail(list.position(), "bake.density",
                    "has " + std::to_string(list.as_array().size()) + " regions, above the limit of " +
                        std::to_string(max_bake_density_regions));
        return;
    }
    constexpr int max_chunk = max_origin / 32;
    for (std::size_t i = 0; i < list.as_array().size() && reader.ok(); ++i) {
        BakeDensity region;
        Fields fields(reader, list.as_array()[i], reading::index_path("bake.density", i), {"min", "max", "resolution"});
        fields.required("min", region.min, IntRange{-max_chunk, max_chunk})
            .required("max", region.max, IntRange{-max_chunk, max_chunk})
            .required("resolution", region.resolution, IntRange{1, 16});
        if (!reader.ok()) return;
        if (region.max.x < region.min.x || region.max.y < region.min.y) {
            fields.fail("max", "must not be below min in x or z");
            return;
        }
        out.push_back(region);
    }
}

// "bake": the world's bake settings, in bake::validate_settings' ranges.
void read_bake_settings(Reader& reader, const json::Value& value, BakeSettings& b) {
    Fields fields(reader, value, "bake",
                  {"resolution", "margin", "rays", "face_rays", "solver", "falloff", "ambient", "directional", "sun_keys",
                   "eps", "max_level", "density"});
    fields.optional("resolution", b.resolution, IntRange{1, 16})
        .optional("margin", b.margin, IntRange{0, 64})
        .optional("rays", b.rays, IntRange{1, 1024})
        .optional("face_rays", b.face_rays, IntRange{1, 1024})
        .optional("solver", b.solver, bake_solvers)
        .optional("falloff", b.falloff, between(1.0 / 64.0, 4096.0))
        .optional("ambient", b.ambient, between(0.0, 1000.0))
        .optional("directional", b.directional)
        .optional("sun_keys", b.sun_keys, IntRange{0, 32})
        .optional("eps", b.eps, between(0.0, 1000.0))
        .optional("max_level", b.max_level, IntRange{0, 3});
    if (fields.ok() && b.sun_keys == 1) fields.fail("sun_keys", "must be 0 or an integer in [2, 32] (one key cannot blend), got 1");
    if (const json::Value* density = fields.find("density"); density && reader.ok())
        read_bake_density(reader, *density, b.density);
}

void read_scene(Reader& reader, const json::Value& root, Scene& scene, MapSpec& map,
                std::vector<MaterialRegion>& regions) {
    Fields top(reader, root, "",
               {"lantern_scene", "world", "view", "camera", "gi", "point_lights", "emissive_lights",
                "directional_lights", "shadow_proxies", "materials", "material_regions", "bake"});
    read_version(reader, top);
    std::vector<char> symbols;
    read_materials(reader, top, scene.materials, symbols);
    read_material_regions(reader, top, scene.materials, regions);
    if (const json::Value* world = top.find_required("world"))
        if (reader.ok()) read_world(reader, *world, row_legend(scene.materials, symbols), scene, map);
    read_view(reader, top, scene.view);
    if (const json::Value* gi = top.find("gi")) reading::read_gi_settings(reader, *gi, scene.gi);
    if (const json::Value* bake = top.find("bake")) {
        read_bake_settings(reader, *bake, scene.bake);
        scene.bake_given = true;
    }
    check_gi_window(reader, top, scene);
    read_list<PointLight>(reader, top, "point_lights", read_point_light, scene.point_lights);
    read_list<EmissiveLight>(reader, top, "emissive_lights", read_emissive_light,
                             scene.emissive_lights);
    read_list<DirectionalLight>(reader, top, "directional_lights", read_directional_light,
                                scene.directional_lights);
    read_list<ShadowProxy>(reader, top, "shadow_proxies", read_shadow_proxy, scene.shadow_proxies);
}

ShadowProxy tree_proxy(glm::ivec2 tile) {
    ShadowProxy proxy;
    proxy.position = glm::vec2(tile) + 0.5f;
    proxy.shape = ProxyShape::circle;
    proxy.size = glm::vec2(tree_proxy_radius);
    proxy.max_length = tree_proxy_max_length;
    return proxy;
}

// Reads the map file into scene.walls (keeping the origin the scene set) and, for
// "trees": "proxy", appends a shadow proxy per tree.
Result<void> import_map(const MapSpec& spec, const std::string& scene_file,
                        const std::string& base_dir, Scene& scene) {
    const std::string path = (std::filesystem::path(base_dir) / spec.path).string();
    scene.inputs.push_back(path);
    auto text = read_text_file(path, max_map_file_bytes);
    if (!text) return file_error(scene_file, {spec.position, "world.map", text.error().message});
    auto map = parse_moving_ai_map(*text, path, spec.options);
    if (!map) return map.error();
    const glm::ivec2 origin = scene.walls.origin;
    scene.walls = std::move(map->walls);
    scene.walls.origin = origin;
    if (spec.options.trees == TreeMode::proxy) {
        scene.shadow_proxies.reserve(scene.shadow_proxies.size() + map->trees.size());
        for (glm::ivec2 cell : map->trees)
            scene.shadow_proxies.push_back(tree_proxy(origin + cell));
    }
    return {};
}

bool is_bare_word(std::string_view text) {
    auto is_letter = [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
    };
    auto is_digit = [](char c) { return c >= '0' && c <= '9'; };
    if (text.empty() || !is_letter(text[0])) return false;
    return std::all_of(text.begin(), text.end(),
                       [&](char c) { return is_letter(c) || is_digit(c); });
}

// VALUE of --set: a JSON value, or a bare word taken as a string.
std::optional<json::Value> parse_override_value(std::string_view text) {
    if (auto value = json::parse(text, "--set")) return std::move(*value);
    if (is_bare_word(text)) return json::Value(std::string(text), {});
    return std::nullopt;
}

} // namespace

namespace reading {

namespace {

// A light's optional "temperature" (kelvin): its colour (white unless given) times the
// black-body colour at that temperature, at the same luminance (lantern/scene/color.hpp).
void apply_temperature(Fields& fields, glm::vec3& color) {
    constexpr Range kelvin_range{.min = min_color_temperature,
                                 .max = max_color_temperature,
                                 .note = "the range of the black-body colour approximation"};
    float kelvin = 0.0f;
    fields.optional("temperature", kelvin, kelvin_range);
    if (fields.ok() && fields.find("temperature")) color *= blackbody_rgb(kelvin);
}

// Seed 004's indirect multiplier scales what the bake holds of a light's bounce; a light whose
// bounce is live (realtime) cannot take one.
void check_indirect(Fields& fields, LightMode mode, float indirect) {
    if (fields.ok() && indirect != 1.0f && mode == LightMode::realtime)
        fields.fail("indirect", "only a light whose bounce is baked takes an indirect multiplier (\"mode\": \"mixed\" "
                                "or \"baked\"): the live methods' bounce is not per light");
}

} // namespace

void read_point_light(Reader& reader, const json::Value& value, const std::string& path,
                      PointLight& light) {
    Fields fields(reader, value, path,
                  {"position", "height", "color", "temperature", "intensity", "radius", "mode", "indirect"});
    fields.required("position", light.position, world_coordinate)
        .optional("height", light.height, at_least(0.0))
        .optional("color", light.color, at_least(0.0))
        .optional("intensity", light.intensity, at_least(0.0))
        .optional("radius", light.radius, greater_than(0.0))
        .optional("mode", light.mode, light_modes)
        .optional("indirect", light.indirect, between(0.0, 1000.0));
    apply_temperature(fields, light.color);
    check_indirect(fields, light.mode, light.indirect);
}

void read_emissive_light(Reader& reader, const json::Value& value, const std::string& path,
                         EmissiveLight& light) {
    Fields fields(reader, value, path, {"position", "color", "temperature", "intensity", "radius", "mode", "indirect"});
    fields.required("position", light.position, world_coordinate)
        .optional("color", light.color, at_least(0.0))
        .optional("intensity", light.intensity, at_least(0.0))
        .optional("radius", light.radius, greater_than(0.0))
        .optional("mode", light.mode, light_modes)
        .optional("indirect", light.indirect, between(0.0, 1000.0));
    apply_temperature(fields, light.color);
    check_indirect(fields, light.mode, light.indirect);
}

void read_directional_light(Reader& reader, const json::Value& value, const std::string& path,
                            DirectionalLight& light) {
    Fields fields(reader, value, path,
                  {"direction", "color", "temperature", "intensity", "base_shadow_distance", "bounce_intensity", "mode",
                   "indirect"});
    fields.required("direction", light.direction, any_number)
        .optional("color", light.color, at_least(0.0))
        .optional("intensity", light.intensity, at_least(0.0))
        .optional("base_shadow_distance", light.base_shadow_distance, at_least(0.0))
        .optional("bounce_intensity", light.bounce_intensity, at_least(0.0))
        .optional("mode", light.mode, light_modes)
        .optional("indirect", light.indirect, between(0.0, 1000.0));
    apply_temperature(fields, light.color);
    check_indirect(fields, light.mode, light.indirect);
    if (!fields.ok()) return;
    // In double: the squares of tiny float components would underflow to 0 in float.
    const glm::dvec3 direction(light.direction);
    const double length = glm::length(direction);
    if (length == 0.0)
        fields.fail("direction", "must not be zero");
    else if (std::abs(length - 1.0) > 1e-6) // a unit direction stays as written, bit for bit
        light.direction = glm::vec3(direction / length);
}

void read_shadow_proxy(Reader& reader, const json::Value& value, const std::string& path,
                       ShadowProxy& proxy) {
    Fields(reader, value, path,
           {"position", "shape", "size", "max_length", "end_cap_blend", "penumbra_width",
            "penumbra_length", "penumbra_power", "width_mode", "penumbra_mode", "static"})
        .required("position", proxy.position, world_coordinate)
        .optional("shape", proxy.shape, proxy_shapes)
        .optional("size", proxy.size, greater_than(0.0))
        .optional("max_length", proxy.max_length, at_least(0.0))
        .optional("end_cap_blend", proxy.end_cap_blend, between(0.0, 1.0))
        .optional("penumbra_width", proxy.penumbra_width, at_least(0.0))
        .optional("penumbra_length", proxy.penumbra_length, at_least(0.0))
        .optional("penumbra_power", proxy.penumbra_power, greater_than(0.0))
        .optional("width_mode", proxy.width_mode, width_modes)
        .optional("penumbra_mode", proxy.penumbra_mode, penumbra_modes)
        .optional("static", proxy.is_static);
}

} // namespace reading

Result<Scene> parse_scene(std::string_view json_text, const std::string& file_name_for_messages,
                          const std::string& base_dir) {
    const std::string& file = file_name_for_messages;
    auto root = json::parse(json_text, file);
    if (!root) return root.error();
    Scene scene;
    scene.source = file;
    MapSpec map;
    std::vector<MaterialRegion> regions;
    Reader reader;
    read_scene(reader, *root, scene, map, regions);
    if (!reader.ok()) return file_error(file, reader.issue());
    if (!map.path.empty())
        if (auto imported = import_map(map, file, base_dir, scene); !imported)
            return imported.error();
    apply_material_regions(regions, scene.walls);
    return scene;
}

Result<Scene> load_scene(const std::string& path) {
    auto text = read_text_file(path, max_scene_file_bytes);
    if (!text) return make_error(text.error().message); // exit code 2: a bad input path
    return parse_scene(*text, path, std::filesystem::path(path).parent_path().string());
}

Result<void> apply_override(Scene& scene, std::string_view assignment) {
    const std::size_t equals = assignment.find('=');
    const std::string name(assignment.substr(0, equals));
    const std::string prefix = "--set " + name + ": ";
    if (!name.starts_with("gi."))
        return make_error(prefix + "only gi keys can be set (--set gi.KEY=VALUE)");
    if (equals == std::string_view::npos) return make_error(prefix + "expected gi.KEY=VALUE");
    const std::string_view text = assignment.substr(equals + 1);
    const std::optional<json::Value> value = parse_override_value(text);
    if (!value)
        return make_error(prefix + "'" + reading::shorten(text) +
                          "' is neither a JSON value nor a bare word (such as aces)");
    GiSettings gi = scene.gi;
    Reader reader;
    if (!reading::read_gi_key(reader, std::string_view(name).substr(3), *value, gi))
        return make_error(prefix + reader.issue().what);
    if (auto problem = gi_window_problem(scene.view, gi)) return make_error(prefix + *problem);
    scene.gi = gi;
    return {};
}

} // namespace lantern::scene

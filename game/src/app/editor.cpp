#include "app/editor.hpp"

#include "lantern/core/file.hpp"
#include "lantern/scene/loader.hpp"

#include <imgui.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <filesystem>

namespace lantern::game {
namespace {

constexpr float panel_width = 340.0f;
constexpr float row_height = 26.0f;
constexpr std::uint64_t max_scene_bytes = 64ull << 20;

glm::vec2 snapped(glm::vec2 p) { return glm::round(p / edit_snap) * edit_snap; }

} // namespace

std::string target_name(EditTarget t) {
    return t.valid() ? std::string(edit_kind_names[int(t.kind)]) + " " + std::to_string(t.index) : std::string();
}

Result<void> SceneEditor::open(const std::string& path) {
    auto text = read_text_file(path, max_scene_bytes);
    if (!text) return make_error(text.error().message);
    auto scene = scene::parse_scene(*text, path, std::filesystem::path(path).parent_path().string());
    if (!scene) return scene.error();
    auto lists = scene::scene_lists(*text, path, *scene);
    if (!lists) return lists.error();
    path_ = path;
    text_ = std::move(*text);
    base_ = std::move(*scene);
    lists_ = std::move(*lists);
    own_proxies_ = lists_.shadow_proxies.size();
    selected_ = {};
    unsaved_ = false;
    open_ = true;
    frames_open_ = 0;
    return {};
}

scene::Scene SceneEditor::scene() const { return scene::with_lists(base_, own_proxies_, lists_); }

int SceneEditor::count(EditKind kind) const {
    switch (kind) {
    case EditKind::point_light: return int(lists_.point_lights.size());
    case EditKind::emissive_light: return int(lists_.emissive_lights.size());
    case EditKind::proxy: return int(lists_.shadow_proxies.size());
    }
    return 0;
}

bool SceneEditor::exists(EditTarget t) const { return t.valid() && t.index < count(t.kind); }

std::optional<glm::vec2> SceneEditor::position_of(EditTarget t) const {
    if (!exists(t)) return std::nullopt;
    const auto i = std::size_t(t.index);
    switch (t.kind) {
    case EditKind::point_light: return lists_.point_lights[i].value.position;
    case EditKind::emissive_light: return lists_.emissive_lights[i].value.position;
    case EditKind::proxy: return lists_.shadow_proxies[i].value.position;
    }
    return std::nullopt;
}

bool SceneEditor::realtime(EditTarget t) const {
    if (!exists(t)) return false;
    const auto i = std::size_t(t.index);
    if (t.kind == EditKind::point_light) return lists_.point_lights[i].value.mode == scene::LightMode::realtime;
    if (t.kind == EditKind::emissive_light) return lists_.emissive_lights[i].value.mode == scene::LightMode::realtime;
    return false; // every shadow proxy goes into the bake
}

EditTarget SceneEditor::select_near(glm::vec2 world) {
    EditTarget best;
    float best_d = edit_pick_distance;
    for (EditKind kind : {EditKind::point_light, EditKind::emissive_light, EditKind::proxy})
        for (int i = 0; i < count(kind); ++i) {
            const float d = glm::distance(*position_of({kind, i}), world);
            if (d <= best_d) {
                best_d = d;
                best = {kind, i};
            }
        }
    selected_ = best;
    return best;
}

EditResult SceneEditor::changed(EditTarget t) {
    unsaved_ = true;
    EditResult r;
    const auto i = std::size_t(t.index);
    switch (t.kind) {
    case EditKind::point_light: lists_.point_lights[i].original = -1; break;
    case EditKind::emissive_light: lists_.emissive_lights[i].original = -1; break;
    case EditKind::proxy: lists_.shadow_proxies[i].original = -1; break;
    }
    // A realtime light changes in place; a baked or mixed light and a proxy (both in the bake)
    // rebuild the world, whose baker then bakes what they reach again.
    if (realtime(t)) r.changed = t;
    else r.rebuild = true;
    return r;
}

EditResult SceneEditor::move_selected(glm::vec2 world) {
    if (!exists(selected_)) return {};
    const glm::vec2 p = snapped(world);
    const auto i = std::size_t(selected_.index);
    switch (selected_.kind) {
    case EditKind::point_light: lists_.point_lights[i].value.position = p; break;
    case EditKind::emissive_light: lists_.emissive_lights[i].value.position = p; break;
    case EditKind::proxy: lists_.shadow_proxies[i].value.position = p; break;
    }
    return changed(selected_);
}

EditResult SceneEditor::recolor_selected(glm::vec3 color) {
    if (!exists(selected_) || selected_.kind == EditKind::proxy) return {};
    const auto i = std::size_t(selected_.index);
    if (selected_.kind == EditKind::point_light) lists_.point_lights[i].value.color = color;
    else lists_.emissive_lights[i].value.color = color;
    return changed(selected_);
}

EditResult SceneEditor::add(EditKind kind, glm::vec2 world) {
    const glm::vec2 p = snapped(world);
    switch (kind) {
    case EditKind::point_light: {
        scene::PointLight l;
        l.position = p;
        l.color = editor_colors[0].rgb;
        l.intensity = 2.0f;
        l.radius = 8.0f;
        lists_.point_lights.push_back({l, -1});
        break;
    }
    case EditKind::emissive_light: {
        scene::EmissiveLight l;
        l.position = p;
        l.color = editor_colors[4].rgb;
        lists_.emissive_lights.push_back({l, -1});
        break;
    }
    case EditKind::proxy: {
        scene::ShadowProxy proxy;
        proxy.position = p;
        proxy.size = glm::vec2(0.35f);
        proxy.max_length = 3.0f;
        lists_.shadow_proxies.push_back({proxy, -1});
        break;
    }
    }
    selected_ = {kind, count(kind) - 1};
    unsaved_ = true;
    EditResult r;
    r.rebuild = true;
    return r;
}

EditResult SceneEditor::remove_selected() {
    if (!exists(selected_)) return {};
    const auto i = std::ptrdiff_t(selected_.index);
    switch (selected_.kind) {
    case EditKind::point_light: lists_.point_lights.erase(lists_.point_lights.begin() + i); break;
    case EditKind::emissive_light: lists_.emissive_lights.erase(lists_.emissive_lights.begin() + i); break;
    case EditKind::proxy: lists_.shadow_proxies.erase(lists_.shadow_proxies.begin() + i); break;
    }
    selected_ = {};
    unsaved_ = true;
    EditResult r;
    r.rebuild = true;
    return r;
}

Result<void> SceneEditor::save() {
    if (!open_) return make_error("the scene editor is not open");
    auto now = read_text_file(path_, max_scene_bytes);
    if (!now) return make_error(now.error().message);
    if (*now != text_)
        return make_error(path_ + ": the file changed on disk since the editor read it; not overwritten (close and "
                                  "open the editor to edit the new file)");
    auto text = scene::rewrite_scene_lists(text_, path_, lists_);
    if (!text) return text.error();
    // Checked before it replaces the file: what is written must load as the edited scene.
    auto back = scene::parse_scene(*text, path_, std::filesystem::path(path_).parent_path().string());
    if (!back) return make_error("the scene editor wrote a scene that does not load (a bug): " + back.error().message);
    auto lists = scene::scene_lists(*text, path_, *back);
    if (!lists) return lists.error();
    if (auto ok = write_file_atomic(path_, *text); !ok) return ok;
    text_ = std::move(*text);
    base_ = std::move(*back);
    lists_ = std::move(*lists); // every entry now as the file has it
    own_proxies_ = lists_.shadow_proxies.size();
    unsaved_ = false;
    ++saves_;
    return {};
}

bool SceneEditor::button(const char* label, float width) {
    const bool clicked = ImGui::Button(label, ImVec2(width, row_height));
    const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
    // The label up to "##" (ImGui's id suffix) names it for scripts.
    const std::string name(label);
    buttons_.push_back({name.substr(0, name.find("##")), lo.x, lo.y, hi.x - lo.x, hi.y - lo.y});
    return clicked;
}

void SceneEditor::draw_selection(EditResult& out) {
    if (!exists(selected_)) {
        ImGui::TextDisabled("nothing selected: left-click near a light or proxy");
        return;
    }
    const auto i = std::size_t(selected_.index);
    const glm::vec2 at = *position_of(selected_);
    ImGui::Text("%s at (%.2f, %.2f)", target_name(selected_).c_str(), double(at.x), double(at.y));
    // A drag applies as it goes to a realtime light; to the rest (which rebuild the world) when
    // it ends.
    auto edited = [&](bool changed_now) {
        const bool done = ImGui::IsItemDeactivatedAfterEdit();
        if ((changed_now && realtime(selected_)) || done) {
            const EditResult r = changed(selected_);
            out.changed = r.changed;
            out.rebuild = out.rebuild || r.rebuild;
        } else if (changed_now) {
            unsaved_ = true; // applied to the world when the drag ends
        }
    };
    auto light_fields = [&](glm::vec3& color, float& intensity, float& radius) {
        edited(ImGui::ColorEdit3("colour", &color.x, ImGuiColorEditFlags_Float));
        const float w = (panel_width - 2.0f * ImGui::GetStyle().WindowPadding.x - 5.0f * ImGui::GetStyle().ItemSpacing.x) / 6.0f;
        for (std::size_t k = 0; k < std::size(editor_colors); ++k) {
            if (k) ImGui::SameLine();
            const glm::vec3 c = editor_colors[k].rgb;
            ImGui::PushStyleColor(ImGuiCol_Button, ImVec4(c.x * 0.8f, c.y * 0.8f, c.z * 0.8f, 1.0f));
            // Shown as "warm", listed for scripts as "colour warm".
            const std::string label = std::string("colour ") + editor_colors[k].name;
            const bool clicked = ImGui::Button((std::string(editor_colors[k].name) + "##" + label).c_str(), ImVec2(w, row_height));
            const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
            buttons_.push_back({label, lo.x, lo.y, hi.x - lo.x, hi.y - lo.y});
            ImGui::PopStyleColor();
            if (clicked) {
                color = c;
                const EditResult r = changed(selected_);
                out.changed = r.changed;
                out.rebuild = out.rebuild || r.rebuild;
            }
        }
        edited(ImGui::DragFloat("intensity", &intensity, 0.02f, 0.0f, 64.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp));
        edited(ImGui::DragFloat("radius", &radius, 0.05f, 0.5f, 120.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp));
    };
    switch (selected_.kind) {
    case EditKind::point_light: {
        scene::PointLight& l = lists_.point_lights[i].value;
        light_fields(l.color, l.intensity, l.radius);
        edited(ImGui::DragFloat("height", &l.height, 0.02f, 0.0f, 16.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp));
        break;
    }
    case EditKind::emissive_light: {
        scene::EmissiveLight& l = lists_.emissive_lights[i].value;
        light_fields(l.color, l.intensity, l.radius);
        break;
    }
    case EditKind::proxy: {
        scene::ShadowProxy& p = lists_.shadow_proxies[i].value;
        int shape = int(p.shape);
        bool shape_changed = ImGui::RadioButton("box", &shape, int(scene::ProxyShape::box));
        ImGui::SameLine();
        shape_changed = ImGui::RadioButton("circle", &shape, int(scene::ProxyShape::circle)) || shape_changed;
        if (shape_changed) {
            p.shape = scene::ProxyShape(shape);
            const EditResult r = changed(selected_);
            out.rebuild = out.rebuild || r.rebuild;
        }
        edited(ImGui::DragFloat2("size", &p.size.x, 0.01f, 0.05f, 8.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp));
        edited(ImGui::DragFloat("shadow length", &p.max_length, 0.05f, 0.0f, 32.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp));
        break;
    }
    }
    if (button("Remove", 120.0f)) {
        const EditResult r = remove_selected();
        out.rebuild = out.rebuild || r.rebuild;
    }
}

EditResult SceneEditor::draw(glm::vec2 player, const std::string& message) {
    buttons_.clear();
    EditResult out;
    if (!open_) {
        frames_open_ = 0;
        return out;
    }
    ++frames_open_;
    const ImGuiViewport* view = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(view->WorkPos.x + view->WorkSize.x - 8.0f, view->WorkPos.y + 8.0f), ImGuiCond_Always,
                            ImVec2(1.0f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(panel_width, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowBgAlpha(0.9f);
    const std::string title = "Scene editor: " + std::filesystem::path(path_).filename().string() +
                              (unsaved_ ? " *" : "") + "###scene_editor";
    ImGui::Begin(title.c_str(), nullptr, ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
    ImGui::TextWrapped("left click: select; right click: move the selection there; Delete: remove; Ctrl+S: save");
    const float third = (panel_width - 2.0f * ImGui::GetStyle().WindowPadding.x - 2.0f * ImGui::GetStyle().ItemSpacing.x) / 3.0f;
    if (button("Add light", third)) out = add(EditKind::point_light, player);
    ImGui::SameLine();
    if (button("Add glow", third)) out = add(EditKind::emissive_light, player);
    ImGui::SameLine();
    if (button("Add proxy", third)) out = add(EditKind::proxy, player);
    ImGui::Separator();
    draw_selection(out);
    ImGui::Separator();
    ImGui::Text("%d point, %d emissive, %d proxies", count(EditKind::point_light), count(EditKind::emissive_light),
                count(EditKind::proxy));
    // The entries, each a button that selects it (up to 24 shown; clicking in the world
    // reaches the rest).
    int shown = 0;
    for (EditKind kind : {EditKind::point_light, EditKind::emissive_light, EditKind::proxy})
        for (int k = 0; k < count(kind) && shown < 24; ++k, ++shown) {
            const EditTarget t{kind, k};
            const std::string label = target_name(t);
            if (shown % 4) ImGui::SameLine();
            ImGui::PushStyleColor(ImGuiCol_Button, t == selected_ ? ImVec4(0.85f, 0.6f, 0.2f, 0.9f)
                                                                  : ImGui::GetStyle().Colors[ImGuiCol_Button]);
            if (button(label.c_str(), (panel_width - 2.0f * ImGui::GetStyle().WindowPadding.x -
                                       3.0f * ImGui::GetStyle().ItemSpacing.x) / 4.0f))
                selected_ = t;
            ImGui::PopStyleColor();
        }
    ImGui::Separator();
    if (button("Save", third)) out.save = true;
    ImGui::SameLine();
    if (button("Close", third)) out.close = true;
    if (!message.empty()) ImGui::TextWrapped("%s", message.c_str());
    ImGui::End();
    return out;
}

} // namespace lantern::game

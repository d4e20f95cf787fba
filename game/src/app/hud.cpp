#include "app/hud.hpp"

#include "lantern/game/baking.hpp"
#include "lantern/gi/pass_table.hpp"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <map>

namespace lantern::game {
namespace {

constexpr const char* tone_maps[] = {"none", "reinhard", "reinhard_white", "aces"};
constexpr const char* heat_scales[] = {"full", "half", "quarter"};
constexpr const char* noise_shifts[] = {"rotate", "golden", "off"}; // scene::NoiseShift order

void stat_row(const profile::ScopeStats& s) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(s.name);
    ImGui::TableNextColumn();
    ImGui::Text("%.2f", s.last_ms);
    ImGui::TableNextColumn();
    ImGui::Text("%.2f", s.p50_ms);
    ImGui::TableNextColumn();
    ImGui::Text("%.2f", s.p95_ms);
    ImGui::TableNextColumn();
    ImGui::Text("%.2f", s.p99_ms);
    ImGui::TableNextColumn();
    ImGui::Text("%.2f", s.max_ms);
}

// Rows of checkboxes and buttons: the next item goes on the same line only while it fits the
// HUD's width, so a narrow HUD wraps the row instead of hiding its end past the right edge.
void same_line_if_fits(float next_width) {
    const float right = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x;
    if (ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + next_width <= right) ImGui::SameLine();
}
float checkbox_width(const char* label) {
    return ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x + ImGui::CalcTextSize(label, nullptr, true).x;
}
float button_width(const char* label) {
    return ImGui::CalcTextSize(label, nullptr, true).x + 2.0f * ImGui::GetStyle().FramePadding.x;
}
bool next_checkbox(const char* label, bool* value) {
    same_line_if_fits(checkbox_width(label));
    return ImGui::Checkbox(label, value);
}
bool next_button(const char* label) {
    same_line_if_fits(button_width(label));
    return ImGui::Button(label);
}
// Coloured text that wraps at the HUD's edge (ImGui::TextColored does not wrap).
void text_colored_wrapped(const ImVec4& colour, const char* text) {
    ImGui::PushStyleColor(ImGuiCol_Text, colour);
    ImGui::TextWrapped("%s", text);
    ImGui::PopStyleColor();
}

bool begin_stat_table(const char* id, const char* first) {
    if (!ImGui::BeginTable(id, 6, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_SizingFixedFit))
        return false;
    ImGui::TableSetupColumn(first);
    for (const char* c : {"last", "p50", "p95", "p99", "max"}) ImGui::TableSetupColumn(c);
    ImGui::TableHeadersRow();
    return true;
}

} // namespace

void Hud::refresh_stats() {
    // Percentiles over the history: recomputed a few times a second, not every frame.
    const std::uint64_t now = profile::frame_index();
    if (!stats_.empty() && now - stats_frame_ < 10) return;
    stats_frame_ = now;
    stats_ = profile::stats();
    frame_ms_ = profile::frame_time_ms();
}

HudActions Hud::draw(const HudInputs& in) {
    HudActions actions;
    if (!visible) return actions;
    refresh_stats();

    // Frame-time graph from the history (the frames that ended).
    const auto history = profile::history();
    graph_.clear();
    const std::size_t first = history.size() > std::size_t(graph_frames) ? history.size() - std::size_t(graph_frames) : 0;
    for (std::size_t i = first; i < history.size(); ++i)
        graph_.push_back(float(double(history[i]->end_ns - history[i]->start_ns) * 1e-6));

    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(470, 680), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.82f);
    if (!ImGui::Begin("Lantern timer HUD  (F1 hides, F2 exports a trace)")) {
        ImGui::End();
        return actions;
    }
    ImGui::Text("%s", in.world.c_str());
    ImGui::Text("%s   vsync %s", in.device.c_str(), in.vsync ? "on" : "off");
    const float last = graph_.empty() ? 0.0f : graph_.back();
    char overlay[96];
    std::snprintf(overlay, sizeof(overlay), "%.1f ms (%.0f fps)", last, last > 0.0f ? 1000.0f / last : 0.0f);
    float top = 50.0f;
    for (float v : graph_) top = std::max(top, v * 1.1f);
    // An explicit width: ImGui 1.86 (Debian 12's) drew a 1-pixel graph for the "to the right
    // edge" width -1, and the trace button fell outside the window after the long line.
    ImGui::PlotLines("##frames", graph_.data(), int(graph_.size()), 0, overlay, 0.0f, top,
                     ImVec2(std::max(ImGui::GetContentRegionAvail().x, 64.0f), 70));
    if (ImGui::SmallButton("trace")) actions.export_trace = true;
    ImGui::SameLine();
    ImGui::TextWrapped("frame ms  p50 %.1f  p95 %.1f  p99 %.1f  max %.1f  (%u frames)", frame_ms_.p50, frame_ms_.p95,
                       frame_ms_.p99, frame_ms_.max, frame_ms_.count);

    if (ImGui::CollapsingHeader("Systems (this frame, by worker lane)", ImGuiTreeNodeFlags_DefaultOpen)) {
        // The last ended frame's job spans, with the lane each ran on.
        if (!history.empty()) {
            const auto lanes = profile::lanes();
            const profile::Frame& f = *history.back();
            std::vector<const profile::Event*> jobs;
            for (const profile::Event& e : f.events)
                if (e.kind == profile::EventKind::job) jobs.push_back(&e);
            std::sort(jobs.begin(), jobs.end(), [](auto* a, auto* b) { return a->start_ns < b->start_ns; });
            if (ImGui::BeginTable("jobs", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
                for (const char* c : {"system", "lane", "start ms", "ms"}) ImGui::TableSetupColumn(c);
                ImGui::TableHeadersRow();
                for (const profile::Event* e : jobs) {
                    ImGui::TableNextRow();
                    ImGui::TableNextColumn();
                    ImGui::TextUnformatted(e->name);
                    ImGui::TableNextColumn();
                    ImGui::TextUnformatted(e->lane < lanes.size() ? lanes[e->lane].name.c_str() : "?");
                    ImGui::TableNextColumn();
                    ImGui::Text("%.2f", double(e->start_ns - f.start_ns) * 1e-6);
                    ImGui::TableNextColumn();
                    ImGui::Text("%.2f", double(e->end_ns - e->start_ns) * 1e-6);
                }
                ImGui::EndTable();
            }
        }
    }
    if (ImGui::CollapsingHeader("CPU percentiles (ms)")) {
        if (begin_stat_table("cpu", "scope")) {
            for (const auto& s : stats_)
                if (s.kind == profile::LaneKind::cpu) stat_row(s);
            ImGui::EndTable();
        }
    }
    if (ImGui::CollapsingHeader("GPU passes (timestamps, ms)", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (begin_stat_table("gpu", "pass")) {
            for (const auto& s : stats_)
                if (s.kind == profile::LaneKind::gpu) stat_row(s);
            ImGui::EndTable();
        }
    }
    if (in.report && ImGui::CollapsingHeader("GI passes this frame", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (int p = 0; p < gi::registered_pass_count(); ++p) {
            const bool ran = in.report->ran.has(gi::Pass(p));
            const std::string& why = in.report->reason[std::size_t(p)];
            char line[256];
            std::snprintf(line, sizeof(line), "%-14s %s", gi::pass_name(gi::Pass(p)),
                          ran ? "ran" : (why.empty() ? "left out" : why.c_str()));
            text_colored_wrapped(ran ? ImVec4(0.5f, 1.0f, 0.5f, 1.0f) : ImVec4(0.7f, 0.7f, 0.7f, 1.0f), line);
        }
        if (!in.report->window) ImGui::TextColored(ImVec4(1, 0.5f, 0.4f, 1), "no GI window this frame");
    }
    if (ImGui::CollapsingHeader("Lights and proxies", ImGuiTreeNodeFlags_DefaultOpen)) {
        if (in.lights)
            ImGui::TextWrapped("point lights %zu kept of %u reaching (cap %d)   emissives %zu   suns %zu", in.lights->points.size(),
                        in.lights->point_candidates, in.config ? in.config->settings.max_lights : 0,
                        in.lights->emissives.size(), in.lights->suns.size());
        if (in.proxies)
            ImGui::TextWrapped("shadow proxies %zu (cap %d)", in.proxies->proxies.size(),
                        in.config ? in.config->settings.max_shadow_proxies : 0);
        ImGui::TextWrapped("entities %u   chunks resident %u, loading %u   edited chunks kept %llu", in.entities,
                    in.streaming.resident_chunks, in.streaming.loading_chunks,
                    static_cast<unsigned long long>(in.streaming.edited_chunks_stored));
        if (in.bake)
            ImGui::TextWrapped("baked light: %d chunks, %d baking   %llu baked, %llu from the cache (last %.0f ms)", in.bake->chunks,
                        in.bake->pending, static_cast<unsigned long long>(in.bake->baked),
                        static_cast<unsigned long long>(in.bake->reused), in.bake->last_chunk_ms);
        if (in.report && in.report->window)
            ImGui::TextWrapped("GI window %dx%d texels at %d/tile", in.report->window->width, in.report->window->height,
                        in.report->window->resolution);
    }
    if (in.config && ImGui::CollapsingHeader("GI settings (live)", ImGuiTreeNodeFlags_DefaultOpen)) {
        scene::GiSettings& g = in.config->settings;
        // gi.method: the rows of the pass table a frame runs (docs/gi.md, "The pass table").
        const std::vector<const gi::Method*> methods = gi::methods();
        if (ImGui::BeginCombo("method", gi::method(g.method).name.data())) {
            for (const gi::Method* m : methods)
                if (ImGui::Selectable(m->name.data(), m->id == g.method)) g.method = m->id;
            ImGui::EndCombo();
        }
        ImGui::SliderInt("resolution", &g.resolution, 1, 16);
        const auto scale_combo = [](const char* label, scene::HeatScale& value) {
            int scale = value == scene::HeatScale::full ? 0 : value == scene::HeatScale::half ? 1 : 2;
            if (ImGui::Combo(label, &scale, heat_scales, 3))
                value = scale == 0 ? scene::HeatScale::full : scale == 1 ? scene::HeatScale::half : scene::HeatScale::quarter;
        };
        if (g.method == scene::GiMethod::radiosity) {
            // gi.radiosity.*: seed 003's raymarch (docs/gi.md, "The radiosity method").
            scene::RadiositySettings& r = g.radiosity;
            scale_combo("radiosity scale", r.scale);
            ImGui::SliderInt("rays", &r.rays, 1, 64);
            ImGui::SliderInt("steps", &r.steps, 1, 128);
            ImGui::SliderFloat("bounce feedback", &r.feedback, 0.0f, 0.95f);
            ImGui::SliderFloat("epsilon", &r.epsilon, 0.05f, 4.0f);
            ImGui::SliderInt("accumulate frames", &r.accumulate, 1, 64);
            int noise = int(r.noise);
            if (ImGui::Combo("noise", &noise, noise_shifts, 3)) r.noise = scene::NoiseShift(noise);
        } else if (g.method == scene::GiMethod::gather) {
            // gi.gather.*: physical bounce light (docs/gi.md, "The gather method").
            scene::GatherSettings& r = g.gather;
            scale_combo("gather scale", r.scale);
            ImGui::SliderInt("rays", &r.rays, 1, 256);
            ImGui::SliderInt("face rays", &r.face_rays, 1, 256);
            ImGui::SliderInt("bounces a frame", &r.bounces, 1, 16);
            ImGui::SliderInt("margin (tiles)", &r.margin, 0, 16);
            ImGui::SliderFloat("wall albedo", &g.wall_albedo, 0.0f, 1.0f);
            ImGui::SliderFloat("albedo boost", &g.albedo_boost, 1.0f, 10.0f);
        }
        ImGui::SliderFloat("baked light", &g.baked_intensity, 0.0f, 4.0f); // seed 002's intensity
        ImGui::SliderInt("live probe rays", &g.probe_rays, 0, 64); // gi.probe_rays (0: none)
        if (g.method != scene::GiMethod::heat) {
            // The bounce stepper (systems::ConvergeControl): radiosity adds a bounce a frame,
            // gather gi.gather.bounces; held, one frame's worth per click.
            systems::ConvergeControl& c = in.config->converge;
            ImGui::Checkbox("hold bounces", &c.hold);
            if (next_button("next bounce")) ++c.steps;
            if (next_button("restart")) ++c.restarts;
            const int per_frame = g.method == scene::GiMethod::gather ? g.gather.bounces : 1;
            char bounce[32];
            std::snprintf(bounce, sizeof(bounce), "bounce %d", (in.converge_history + 1) * per_frame);
            same_line_if_fits(ImGui::CalcTextSize(bounce).x);
            ImGui::TextUnformatted(bounce);
        } else {
            ImGui::SliderInt("heat rounds", &g.heat_rounds, 0, 64);
            scale_combo("heat scale", g.heat_scale);
        }
        ImGui::Checkbox("blur", &g.blur);
        next_checkbox("AO", &g.ao.enabled);
        next_checkbox("AO on walls", &g.ao.walls);
        next_checkbox("per channel", &g.per_channel);
        // gi.wall_lighting: off leaves out every wall-face pass and texture (walls go dark).
        ImGui::Checkbox("wall lighting", &g.wall_lighting);
        // gi.window_snap: the window follows the camera by texels instead of whole tiles.
        bool texel_snap = g.window_snap == scene::WindowSnap::texel;
        if (next_checkbox("window by texels", &texel_snap))
            g.window_snap = texel_snap ? scene::WindowSnap::texel : scene::WindowSnap::tile;
        // gi.proxy_wall_shadows: proxy shadows fold up the walls as far as they reach.
        bool unfold = g.proxy_wall_shadows == scene::ProxyWallShadows::unfold;
        if (ImGui::Checkbox("unfold proxy shadows", &unfold))
            g.proxy_wall_shadows = unfold ? scene::ProxyWallShadows::unfold : scene::ProxyWallShadows::full;
        // gi.shadow_method: point lights' shadows by their angular maps (same image, other cost).
        bool point_maps = g.shadow_method == scene::ShadowMethod::shadow_map;
        if (next_checkbox("light shadow maps", &point_maps))
            g.shadow_method = point_maps ? scene::ShadowMethod::shadow_map : scene::ShadowMethod::dda;
        // gi.sun_shadow_method: the sun's shadows by the 1D shadow map (same image, other cost).
        bool sun_map = g.sun_shadow_method == scene::SunShadowMethod::shadow_map;
        if (next_checkbox("sun shadow map", &sun_map))
            g.sun_shadow_method = sun_map ? scene::SunShadowMethod::shadow_map : scene::SunShadowMethod::dda;
        int tone = int(g.tone_map);
        if (ImGui::Combo("tone map", &tone, tone_maps, 4)) g.tone_map = scene::ToneMap(tone);
        ImGui::SliderFloat("emission", &g.emission_strength, 0.0f, 4.0f);
        // gi.wall_face_exponent: above 1, softer turns of light round wall corners.
        ImGui::SliderFloat("wall face k", &g.wall_face_exponent, 0.25f, 8.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
        ImGui::SliderInt("max lights", &g.max_lights, 1, 256);
        ImGui::SliderInt("max proxies", &g.max_shadow_proxies, 0, 256);
    }
    if (in.gi_view && ImGui::CollapsingHeader("GI views", ImGuiTreeNodeFlags_DefaultOpen)) {
        // A GI texture over the world from above (WorldView::gi_view; docs/game.md, "GI views").
        const auto names = gi_debug_view_names();
        int view = int(*in.gi_view);
        if (ImGui::Combo("view", &view, names.data(), int(names.size()))) *in.gi_view = GiDebugView(view);
        if (*in.gi_view != GiDebugView::lit && in.gi_view_drawn != *in.gi_view)
            text_colored_wrapped(ImVec4(1, 0.7f, 0.4f, 1), "not in this frame (gi.method = radiosity has it)");
    }
    if (in.schedule && ImGui::CollapsingHeader("Schedule (systems, access, order)")) {
        // The frame's job graph as declared: what each system waits for and why (the types
        // that order it, or after()), and the pairs only the add order orders.
        const ecs::ScheduleInfo& sched = *in.schedule;
        if (ImGui::BeginTable("schedule", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
            for (const char* c : {"system", "waits for", "writes"}) ImGui::TableSetupColumn(c);
            ImGui::TableHeadersRow();
            for (std::uint32_t i = 0; i < sched.systems.size(); ++i) {
                const ecs::ScheduleInfo::System& sys = sched.systems[i];
                std::string waits, writes;
                for (const ecs::ScheduleInfo::Edge& e : sched.edges) {
                    if (e.after != i || e.redundant) continue;
                    if (!waits.empty()) waits += "\n";
                    waits += sched.systems[e.before].name + " (";
                    waits += e.declared ? "after" : e.conflicts.empty() ? "" : e.conflicts.front().type.c_str();
                    if (!e.declared && e.conflicts.size() > 1) waits += ", ...";
                    waits += ")";
                }
                for (const ecs::ScheduleInfo::Access& a : sys.writes) writes += (writes.empty() ? "" : ", ") + a.type;
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::Text("%s%s", sys.name.c_str(), sys.main_thread ? " (main)" : "");
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(waits.empty() ? "-" : waits.c_str());
                ImGui::TableNextColumn();
                ImGui::TextWrapped("%s", writes.c_str());
            }
            ImGui::EndTable();
        }
        if (sched.ambiguities.empty()) ImGui::TextUnformatted("no ambiguities");
        for (const ecs::ScheduleInfo::Ambiguity& a : sched.ambiguities) {
            const std::string line = sched.systems[a.first].name + " / " + sched.systems[a.second].name + " both write " +
                                     a.types.front().type + " (add order only)";
            text_colored_wrapped(ImVec4(1, 0.7f, 0.4f, 1), line.c_str());
        }
    }
    if (in.art && ImGui::CollapsingHeader("Art")) {
        ImGui::SliderInt("posterize", &in.art->posterize, 0, 32);
        ImGui::Checkbox("dither", &in.art->dither);
        ImGui::Checkbox("pixel pattern", &in.art->texture_pattern);
        const auto palettes = builtin_palettes();
        std::vector<const char*> names;
        for (const Palette& p : palettes) names.push_back(p.name);
        ImGui::Combo("palette", &in.art->palette, names.data(), int(names.size()));
        if (in.world_bounce && in.character_bounce) {
            // Seed 002's runtime knobs on the bounce light (docs/baked.md, "Bounce knobs").
            ImGui::SliderFloat("world self", &in.world_bounce->self, 0.0f, 1.0f);
            ImGui::SliderFloat("world bleed", &in.world_bounce->bleed, 0.0f, 1.0f);
            ImGui::SliderFloat("character self", &in.character_bounce->self, 0.0f, 1.0f);
            ImGui::SliderFloat("character bleed", &in.character_bounce->bleed, 0.0f, 1.0f);
        }
    }
    if (in.day && ImGui::CollapsingHeader("World", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::TextWrapped("placing: %s   (keys 1-5; the hotbar shows what is left)", in.item);
        ImGui::SliderFloat("time of day", &in.day->time_of_day, 0.0f, 0.999f);
        ImGui::Checkbox("day cycle (N)", &in.day->running);
        if (ImGui::Button("save (F5)")) actions.save = true;
        if (next_button("load (F9)")) actions.load = true;
        if (next_button(in.vsync ? "vsync off" : "vsync on")) actions.toggle_vsync = true;
        if (!in.message.empty()) ImGui::TextWrapped("%s", in.message.c_str());
    }
    ImGui::End();
    return actions;
}

void draw_hotbar(const Inventory& inventory, int selected) {
    const ImGuiViewport* view = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(ImVec2(view->WorkPos.x + view->WorkSize.x * 0.5f, view->WorkPos.y + view->WorkSize.y - 6.0f),
                            ImGuiCond_Always, ImVec2(0.5f, 1.0f));
    ImGui::SetNextWindowBgAlpha(0.6f);
    constexpr ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                       ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                       ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoMove;
    if (ImGui::Begin("##hotbar", nullptr, flags)) {
        for (int i = 0; i < item_count; ++i) {
            if (i) ImGui::SameLine();
            const int count = inventory.counts[std::size_t(i)];
            const bool chosen = i == selected;
            const ImVec4 fill = chosen ? ImVec4(0.85f, 0.6f, 0.2f, 0.9f) : ImVec4(0.15f, 0.15f, 0.18f, 0.9f);
            ImGui::PushStyleColor(ImGuiCol_Button, fill);
            ImGui::PushStyleColor(ImGuiCol_Text, count > 0 ? ImVec4(1, 1, 1, 1) : ImVec4(0.5f, 0.5f, 0.5f, 1));
            char label[48];
            std::snprintf(label, sizeof(label), "%d %s\n%d##slot%d", i + 1, item_names[i], count, i);
            ImGui::Button(label, ImVec2(86, 40));
            ImGui::PopStyleColor(2);
        }
    }
    ImGui::End();
}

} // namespace lantern::game

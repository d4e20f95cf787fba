#include "app/sound.hpp"

#include "lantern/game/game_components.hpp"

#include <glm/geometric.hpp>

#include <algorithm>

namespace lantern::game {
namespace {

glm::vec3 on_ground(glm::vec2 p) {
    return {p.x, 0.0f, p.y};
}

} // namespace

GameSound::GameSound(std::unique_ptr<audio::Mixer> mixer) : mixer_(std::move(mixer)) {
    for (std::size_t i = 0; i < steps_.size(); ++i) steps_[i] = mixer_->add(audio::footstep(std::uint32_t(i + 1)));
    dig_ = mixer_->add(audio::dig(7));
    place_ = mixer_->add(audio::place(11));
    pick_up_ = mixer_->add(audio::place(23)); // a lighter knock than placing
    crackle_ = mixer_->add(audio::crackle(5));
}

GameSound::~GameSound() {
    for (const TorchVoice& t : torches_) mixer_->stop(t.loop);
}

void GameSound::update(ecs::World& w) {
    std::optional<glm::vec2> player;
    w.view<Player, Transform>().each([&](const Player&, const Transform& t) {
        if (!player) player = glm::vec2(t.position.x, t.position.z);
    });
    if (!player) return;
    mixer_->set_listener({{player->x, listener_height, player->y}});

    // Footsteps: one per step_length walked (a jump, as after a load, resets the count).
    if (has_last_) {
        const float moved = glm::distance(*player, last_player_);
        walked_ = moved > 2.0f ? 0.0f : walked_ + moved;
        if (walked_ >= step_length) {
            walked_ -= step_length;
            mixer_->play(steps_[std::size_t(step_++) % steps_.size()], on_ground(*player), 0.6f);
            ++played_;
        }
    }
    has_last_ = true;
    last_player_ = *player;

    // This frame's edits, where they happened.
    if (w.has_resource<SoundCues>()) {
        std::vector<SoundCues::Entry>& cues = w.resource<SoundCues>().entries;
        for (const SoundCues::Entry& c : cues) {
            const audio::Mixer::SoundId id = c.cue == SoundCue::dig ? dig_ : c.cue == SoundCue::place ? place_ : pick_up_;
            mixer_->play(id, on_ground(c.at), c.cue == SoundCue::pick_up ? 0.6f : 0.9f);
            ++played_;
        }
        cues.clear();
    }

    // The nearest torches crackle (the rest are too far to hear over them).
    struct Near {
        ecs::Entity e;
        glm::vec2 at;
        float d;
    };
    std::vector<Near> near;
    w.view<Torch, PointLight>().each([&](ecs::Entity e, const Torch&, const PointLight& l) {
        near.push_back({e, l.position, glm::distance(l.position, *player)});
    });
    const std::size_t keep = std::min<std::size_t>(near.size(), crackling_torches);
    std::partial_sort(near.begin(), near.begin() + std::ptrdiff_t(keep), near.end(),
                      [](const Near& a, const Near& b) { return a.d < b.d || (a.d == b.d && a.e < b.e); });
    near.resize(keep);
    std::erase_if(torches_, [&](const TorchVoice& t) {
        const bool kept = std::any_of(near.begin(), near.end(), [&](const Near& n) { return n.e == t.torch; });
        if (!kept) mixer_->stop(t.loop);
        return !kept;
    });
    for (const Near& n : near) {
        auto it = std::find_if(torches_.begin(), torches_.end(), [&](const TorchVoice& t) { return t.torch == n.e; });
        if (it == torches_.end()) torches_.push_back({n.e, mixer_->loop(crackle_, on_ground(n.at), 0.5f)});
        else mixer_->move(it->loop, on_ground(n.at));
    }
}

} // namespace lantern::game

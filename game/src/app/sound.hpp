// The game's sound (docs/game.md, "Sound"): footsteps as the player walks, a dig, a knock or a
// pick-up for each edit `interact` reports (SoundCues), and the crackle of the torches
// nearest the player, each where it happens, heard from the player's position. The sounds
// are made at start-up (audio::footstep ...); no binary assets.
// Threads: the main thread (the sound system is a main-thread system).
#pragma once

#include "lantern/audio/mixer.hpp"
#include "lantern/ecs/world.hpp"

#include <glm/vec2.hpp>

#include <array>
#include <memory>
#include <vector>

namespace lantern::game {

class GameSound {
  public:
    static constexpr float step_length = 0.8f;     // tiles walked per footstep
    static constexpr int crackling_torches = 4;    // the nearest torches that crackle
    static constexpr float listener_height = 2.0f; // tiles above the player's feet

    explicit GameSound(std::unique_ptr<audio::Mixer> mixer);
    ~GameSound();

    // Once a frame, after the simulation: reads Player/Transform, Torch/PointLight and
    // SoundCues (which it empties).
    void update(ecs::World& world);

    audio::Mixer& mixer() { return *mixer_; }
    std::uint64_t sounds_played() const { return played_; } // footsteps and cues

  private:
    std::unique_ptr<audio::Mixer> mixer_;
    std::array<audio::Mixer::SoundId, 4> steps_{};
    audio::Mixer::SoundId dig_ = 0, place_ = 0, pick_up_ = 0, crackle_ = 0;
    bool has_last_ = false;
    glm::vec2 last_player_{0.0f};
    float walked_ = 0.0f;
    int step_ = 0;
    std::uint64_t played_ = 0;
    struct TorchVoice {
        ecs::Entity torch;
        audio::Mixer::LoopId loop = 0;
    };
    std::vector<TorchVoice> torches_;
};

} // namespace lantern::game

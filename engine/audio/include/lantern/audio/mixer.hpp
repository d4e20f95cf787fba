// Positional sound through OpenAL Soft (Debian's libopenal). A Mixer owns one OpenAL device
// and context: the default output device for the game, or a loopback device
// (ALC_SOFT_loopback) that plays nothing and mixes into memory on request, which is how the
// tests hear it on machines without sound hardware (CI).
//
// World units are tiles; loudness falls linearly from `reference_distance` (full loudness
// nearer) to `max_distance` (silent there and beyond; OpenAL's linear clamped model). A mono
// sound at a position is panned by its direction from the listener: with the listener's
// forward -z and up +y (the game's top-down camera), +x is to the right.
//
// One-shots (play) take a voice from a pool of `voice_count`; when all are busy the one
// started longest ago is cut. Loops (loop/move/stop) have voices of their own.
//
// Threads: one thread (the game's main thread). Each call makes the Mixer's context current,
// so several Mixers may live side by side (tests). open_device() redirects the process's
// stderr while it probes: call it before other threads write there (start-up).
#pragma once

#include "lantern/audio/sounds.hpp"
#include "lantern/core/result.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace lantern::audio {

struct Listener {
    glm::vec3 position{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
};

struct MixerOptions {
    int voice_count = 16;
    float reference_distance = 2.0f; // tiles: full loudness within
    float max_distance = 16.0f;      // tiles: silent beyond
    // open_device: the backends' complaints while probing (ALSA's "cannot find card '0'" on
    // a machine without sound) are not printed; LANTERN_AUDIO_DEBUG=1 shows them.
    bool quiet_probe = true;
};

class Mixer {
  public:
    using SoundId = std::uint32_t;
    using LoopId = std::uint32_t;

    // The system's default output device. An error when there is none (the game then runs
    // silent and says so once).
    static Result<std::unique_ptr<Mixer>> open_device(const MixerOptions& options = {});
    // A loopback device mixing stereo float at `sample_rate` into render()'s buffer (float:
    // no 16-bit dither noise, so silence reads as 0). An error when OpenAL lacks
    // ALC_SOFT_loopback.
    static Result<std::unique_ptr<Mixer>> open_loopback(int sample_rate = default_sample_rate,
                                                        const MixerOptions& options = {});
    ~Mixer();
    Mixer(const Mixer&) = delete;
    Mixer& operator=(const Mixer&) = delete;

    // Uploads a sound once; play and loop refer to it by id.
    SoundId add(const Sound& sound);
    void play(SoundId sound, glm::vec3 position, float gain = 1.0f);
    LoopId loop(SoundId sound, glm::vec3 position, float gain = 1.0f);
    void move(LoopId loop, glm::vec3 position);
    void stop(LoopId loop);
    void set_listener(const Listener& listener);
    // The master volume, multiplying everything (1: as played; 0: silent). Clamped to [0, 1].
    void set_volume(float volume);

    // Loopback only: mixes the next `frames` stereo frames (interleaved left, right, in
    // [-1, 1]). A stopped voice fades out over the first few milliseconds (no click).
    std::vector<float> render(int frames);
    bool is_loopback() const;
    std::string device_name() const;
    int playing_voices() const; // one-shots and loops playing now

  private:
    struct State;
    explicit Mixer(std::unique_ptr<State> state);
    // Creates the context on the state's device (`attributes`: ALC attributes, 0-terminated,
    // or null) and the voice pool.
    static Result<std::unique_ptr<Mixer>> start(std::unique_ptr<State> state, const int* attributes);
    std::unique_ptr<State> s_;
};

} // namespace lantern::audio

// Procedural sounds (no binary assets): the game's footsteps, digging, placing and a torch's
// crackle, synthesised at start-up from seeded noise (an integer xorshift) and decaying
// tones. Mono 16-bit PCM; the same seed gives the same sound.
// Threads: pure functions.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace lantern::audio {

inline constexpr int default_sample_rate = 44100;

// Mono 16-bit PCM.
struct Sound {
    int sample_rate = default_sample_rate;
    std::vector<std::int16_t> samples;
    double seconds() const { return sample_rate > 0 ? double(samples.size()) / double(sample_rate) : 0.0; }
};

// ~90 ms: a soft thud (low-passed noise and a low tone, fast decay).
Sound footstep(std::uint32_t seed, int sample_rate = default_sample_rate);
// ~220 ms: three gritty bursts of bright noise (a pick biting rock).
Sound dig(std::uint32_t seed, int sample_rate = default_sample_rate);
// ~140 ms: a knock (a falling tone and a click).
Sound place(std::uint32_t seed, int sample_rate = default_sample_rate);
// 1.5 s to loop: a low rumble with random pops (a torch's crackle).
Sound crackle(std::uint32_t seed, int sample_rate = default_sample_rate);

// Root mean square of samples, in [0, 1] (int16 / 32768); 0 for none.
double rms(std::span<const std::int16_t> samples);
double rms(std::span<const float> samples);
// Of one channel of interleaved stereo (channel 0 left, 1 right).
double rms_channel(std::span<const float> stereo, int channel);

} // namespace lantern::audio

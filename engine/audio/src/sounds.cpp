#include "lantern/audio/sounds.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lantern::audio {
namespace {

// xorshift32: white noise in [-1, 1], the same on every machine.
struct Noise {
    std::uint32_t state;
    explicit Noise(std::uint32_t seed) : state(seed * 2654435761u + 0x9E3779B9u) {
        if (state == 0) state = 1;
    }
    double next() {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        return double(state) / 2147483648.0 - 1.0;
    }
};

std::int16_t to_pcm(double v) {
    return std::int16_t(std::lround(std::clamp(v, -1.0, 1.0) * 32767.0));
}

// `seconds` of samples from f(t, noise).
template <typename F>
Sound synthesise(int sample_rate, double seconds, std::uint32_t seed, F&& f) {
    Sound s;
    s.sample_rate = sample_rate;
    const int n = std::max(1, int(seconds * sample_rate));
    s.samples.resize(std::size_t(n));
    Noise noise(seed);
    for (int i = 0; i < n; ++i) s.samples[std::size_t(i)] = to_pcm(f(double(i) / sample_rate, noise));
    return s;
}

// A 2 ms rise, so no sound starts with a click.
double attack(double t) {
    return std::min(1.0, t / 0.002);
}

constexpr double two_pi = 2.0 * std::numbers::pi;

} // namespace

Sound footstep(std::uint32_t seed, int sample_rate) {
    double low = 0.0;
    const double pitch = 80.0 + double(seed % 5) * 6.0; // steps differ a little
    return synthesise(sample_rate, 0.09, seed, [&](double t, Noise& noise) {
        low += 0.12 * (noise.next() - low); // one-pole low-pass: a thud, not a hiss
        const double body = std::sin(two_pi * pitch * t) * std::exp(-t / 0.03);
        return attack(t) * (2.2 * low * std::exp(-t / 0.02) + 0.45 * body);
    });
}

Sound dig(std::uint32_t seed, int sample_rate) {
    double previous = 0.0;
    return synthesise(sample_rate, 0.22, seed, [&](double t, Noise& noise) {
        const double n = noise.next();
        const double bright = n - previous; // a first difference: high-passed grit
        previous = n;
        double env = 0.0;
        for (double start : {0.0, 0.065, 0.13})
            if (t >= start) env += std::exp(-(t - start) / 0.022) * attack(t - start);
        return 0.45 * bright * env;
    });
}

Sound place(std::uint32_t seed, int sample_rate) {
    double phase = 0.0;
    return synthesise(sample_rate, 0.14, seed, [&](double t, Noise& noise) {
        const double f = 170.0 * (1.0 + 0.6 * std::exp(-t / 0.01)); // a knock falls in pitch
        phase += two_pi * f / double(sample_rate);
        const double tone = std::sin(phase) * std::exp(-t / 0.035);
        const double click = noise.next() * std::exp(-t / 0.004);
        return attack(t) * (0.7 * tone + 0.35 * click);
    });
}

Sound crackle(std::uint32_t seed, int sample_rate) {
    double rumble = 0.0;
    double pop = 0.0, pop_decay = 0.0;
    Noise timing(seed ^ 0xC0FFEEu);
    return synthesise(sample_rate, 1.5, seed, [&](double t, Noise& noise) {
        rumble += 0.04 * (noise.next() - rumble);
        // About 14 pops a second, each a few milliseconds of noise at its own loudness.
        if ((timing.next() + 1.0) * 0.5 < 14.0 / double(sample_rate)) {
            pop = 0.35 + 0.45 * (timing.next() + 1.0) * 0.5;
            pop_decay = std::exp(-1.0 / (double(sample_rate) * (0.002 + 0.004 * (timing.next() + 1.0) * 0.5)));
        }
        const double out = 0.9 * rumble + pop * noise.next();
        pop *= pop_decay;
        return attack(t) * out;
    });
}

double rms(std::span<const std::int16_t> samples) {
    if (samples.empty()) return 0.0;
    double sum = 0.0;
    for (std::int16_t s : samples) sum += double(s) * double(s);
    return std::sqrt(sum / double(samples.size())) / 32768.0;
}

double rms(std::span<const float> samples) {
    if (samples.empty()) return 0.0;
    double sum = 0.0;
    for (float s : samples) sum += double(s) * double(s);
    return std::sqrt(sum / double(samples.size()));
}

double rms_channel(std::span<const float> stereo, int channel) {
    const std::size_t frames = stereo.size() / 2;
    if (frames == 0) return 0.0;
    double sum = 0.0;
    for (std::size_t i = 0; i < frames; ++i) {
        const double s = stereo[2 * i + std::size_t(channel)];
        sum += s * s;
    }
    return std::sqrt(sum / double(frames));
}

} // namespace lantern::audio

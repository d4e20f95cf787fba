// Procedural sounds and positional playback (engine::audio), heard through OpenAL Soft's
// loopback device: what a player would hear, mixed into memory.
#include "lantern/audio/mixer.hpp"
#include "lantern/audio/sounds.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>

using namespace lantern;
using namespace lantern::audio;

namespace {

constexpr int rate = 44100;

std::unique_ptr<Mixer> loopback() {
    auto m = Mixer::open_loopback(rate);
    EXPECT_TRUE(m) << (m ? "" : m.error().message);
    return m ? std::move(*m) : nullptr;
}

} // namespace

TEST(Sounds, EachHasEnergyALengthAndNoClipping) {
    struct Case {
        const char* name;
        Sound sound;
        double min_s, max_s;
    };
    const Case cases[] = {{"footstep", footstep(1), 0.05, 0.15},
                          {"dig", dig(1), 0.15, 0.3},
                          {"place", place(1), 0.08, 0.2},
                          {"crackle", crackle(1), 1.0, 2.0}};
    for (const Case& c : cases) {
        EXPECT_EQ(c.sound.sample_rate, default_sample_rate) << c.name;
        EXPECT_GE(c.sound.seconds(), c.min_s) << c.name;
        EXPECT_LE(c.sound.seconds(), c.max_s) << c.name;
        const double level = rms(c.sound.samples);
        EXPECT_GT(level, 0.02) << c.name << " is (nearly) silent";
        EXPECT_LT(level, 0.7) << c.name;
        int clipped = 0;
        for (std::int16_t s : c.sound.samples) clipped += (s == 32767 || s == -32767) ? 1 : 0;
        EXPECT_LT(clipped, int(c.sound.samples.size() / 100)) << c.name << " clips";
        // No click at the start: it rises from silence.
        EXPECT_EQ(c.sound.samples.front(), 0) << c.name;
        EXPECT_LT(std::abs(int(c.sound.samples[8])), 32768 / 20) << c.name;
    }
}

TEST(Sounds, TheSameSeedGivesTheSameSoundAndAnotherADifferentOne) {
    for (auto make : {footstep, dig, place, crackle}) {
        const Sound a = make(3, rate), b = make(3, rate), c = make(4, rate);
        EXPECT_EQ(a.samples, b.samples);
        EXPECT_NE(a.samples, c.samples);
    }
    EXPECT_EQ(footstep(1, 22050).sample_rate, 22050);
    EXPECT_NEAR(footstep(1, 22050).seconds(), footstep(1, rate).seconds(), 1e-3);
}

TEST(Mixer, ASoundToTheLeftIsLouderInTheLeftChannel) {
    auto m = loopback();
    ASSERT_TRUE(m);
    EXPECT_TRUE(m->is_loopback());
    const Mixer::SoundId id = m->add(crackle(2));
    m->set_listener({{0.0f, 2.0f, 0.0f}}); // forward -z, up +y: +x is to the right
    const auto heard = [&](glm::vec3 at) {
        m->render(rate / 50); // the last loop's fade-out
        const Mixer::LoopId loop = m->loop(id, at);
        const std::vector<float> mix = m->render(rate / 2);
        m->stop(loop);
        return std::pair(rms_channel(mix, 0), rms_channel(mix, 1));
    };
    const auto [ll, lr] = heard({-4.0f, 0.0f, 0.0f});
    EXPECT_GT(ll, 0.01);
    EXPECT_GT(ll, 1.5 * lr) << "left " << ll << ", right " << lr;
    const auto [rl, rr] = heard({4.0f, 0.0f, 0.0f});
    EXPECT_GT(rr, 1.5 * rl) << "left " << rl << ", right " << rr;
    // Nearer is louder; beyond max_distance (16 tiles) nothing is heard.
    const auto [nl, nr] = heard({-2.5f, 0.0f, 0.0f});
    EXPECT_GT(nl + nr, ll + lr);
    const auto [fl, fr] = heard({-20.0f, 0.0f, 0.0f});
    EXPECT_LT(fl + fr, 1e-6);
    EXPECT_EQ(m->playing_voices(), 0) << "stopped loops are gone";
}

TEST(Mixer, OneShotsPlayOnceAndTheVoicePoolIsReused) {
    MixerOptions o;
    o.voice_count = 2;
    auto made = Mixer::open_loopback(rate, o);
    ASSERT_TRUE(made) << made.error().message;
    Mixer& m = **made;
    const Mixer::SoundId step = m.add(footstep(1));
    m.set_listener({});
    m.play(step, {0.0f, 0.0f, -1.0f});
    EXPECT_EQ(m.playing_voices(), 1);
    const std::vector<float> first = m.render(rate / 10); // 100 ms: the step
    EXPECT_GT(rms(first), 0.01) << "a footstep has energy";
    const std::vector<float> after = m.render(rate / 10);
    EXPECT_LT(rms(after), 1e-6) << "a one-shot does not loop";
    EXPECT_EQ(m.playing_voices(), 0);
    for (int i = 0; i < 5; ++i) m.play(step, {0.0f, 0.0f, -1.0f});
    EXPECT_EQ(m.playing_voices(), 2) << "five one-shots on two voices: the oldest are cut";
    m.play(0, {}); // an unknown sound is ignored
    m.play(99, {});
    EXPECT_EQ(m.loop(99, {}), 0u);
    m.stop(12345); // an unknown loop too
    m.move(12345, {});
}

TEST(Mixer, TheVolumeScalesEverything) {
    auto m = loopback();
    ASSERT_TRUE(m);
    m->set_listener({});
    const Sound loop = crackle(4);
    m->loop(m->add(loop), {0.0f, 0.0f, -1.0f});
    // Each measure spans exactly one turn of the loop, so the same sound is compared.
    const int turn = int(loop.samples.size());
    const auto measure = [&] {
        m->render(rate / 20); // the gain ramps over a few milliseconds
        return rms(m->render(turn));
    };
    const double full = measure();
    m->set_volume(0.5f);
    const double half = measure();
    m->set_volume(0.0f);
    const double none = measure();
    EXPECT_GT(full, 0.01);
    EXPECT_NEAR(half / full, 0.5, 0.02);
    EXPECT_LT(none, 1e-6);
    m->set_volume(7.0f); // clamped to 1
    EXPECT_NEAR(measure() / full, 1.0, 0.02);
}

TEST(Mixer, LoopsKeepPlayingAndMoveWithTheirSource) {
    auto m = loopback();
    ASSERT_TRUE(m);
    const Mixer::LoopId loop = m->loop(m->add(crackle(9)), {-3.0f, 0.0f, 0.0f});
    ASSERT_NE(loop, 0u);
    m->set_listener({});
    for (int i = 0; i < 3; ++i) EXPECT_GT(rms(m->render(rate)), 0.01) << "second " << i; // past its 1.5 s length
    m->move(loop, {3.0f, 0.0f, 0.0f});
    const std::vector<float> moved = m->render(rate / 2);
    EXPECT_GT(rms_channel(moved, 1), 1.5 * rms_channel(moved, 0)) << "moved to the right";
    EXPECT_EQ(m->playing_voices(), 1);
}

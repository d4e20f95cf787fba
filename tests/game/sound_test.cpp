// The game's sound (GameSound) heard through OpenAL Soft's loopback device: footsteps as the
// player walks, a torch to the player's left louder in the left channel, an edit's cue where
// it happened (issue 19, "Sound").
#include "app/sound.hpp"

#include "lantern/game/game_components.hpp"

#include <gtest/gtest.h>

using namespace lantern;
using namespace lantern::game;

namespace {

constexpr int rate = audio::default_sample_rate;

struct SoundWorld : ::testing::Test {
    ecs::World world;
    ecs::Entity player;
    std::unique_ptr<GameSound> sound;
    void SetUp() override {
        auto mixer = audio::Mixer::open_loopback(rate);
        ASSERT_TRUE(mixer) << mixer.error().message;
        sound = std::make_unique<GameSound>(std::move(*mixer));
        player = world.create();
        world.emplace<Player>(player);
        world.emplace<Transform>(player).position = {10.0f, 0.0f, 10.0f};
        world.set_resource<SoundCues>();
    }
    void walk_to(float x) { world.get<Transform>(player).position.x = x; }
    // One frame's update, then `seconds` of what the player hears.
    std::vector<float> frame(double seconds) {
        sound->update(world);
        return sound->mixer().render(int(seconds * rate));
    }
};

} // namespace

TEST_F(SoundWorld, FootstepsWhileWalkingAndSilenceStandingStill) {
    double still = 0.0;
    for (int i = 0; i < 10; ++i) still += audio::rms(frame(1.0 / 60.0));
    EXPECT_LT(still, 1e-6) << "standing still makes no sound";
    EXPECT_EQ(sound->sounds_played(), 0u);
    double walking = 0.0;
    for (int i = 1; i <= 60; ++i) { // 3 tiles in a second: about 4 steps
        walk_to(10.0f + 3.0f * float(i) / 60.0f);
        walking += audio::rms(frame(1.0 / 60.0));
    }
    EXPECT_GE(sound->sounds_played(), 3u);
    EXPECT_LE(sound->sounds_played(), 4u);
    EXPECT_GT(walking / 60.0, 0.005) << "footsteps have energy";
    walk_to(500.0f); // a jump (a load) is not a walk
    frame(0.01);
    EXPECT_LE(sound->sounds_played(), 4u);
}

TEST_F(SoundWorld, ATorchToThePlayersLeftIsLouderInTheLeftChannel) {
    const ecs::Entity torch = world.create();
    world.emplace<Torch>(torch);
    world.emplace<PointLight>(torch).position = {6.0f, 10.0f}; // 4 tiles west of the player
    const std::vector<float> left = frame(0.5);
    EXPECT_GT(audio::rms_channel(left, 0), 0.005);
    EXPECT_GT(audio::rms_channel(left, 0), 1.5 * audio::rms_channel(left, 1));
    world.get<PointLight>(torch).position = {14.0f, 10.0f}; // now east
    const std::vector<float> right = frame(0.5);
    EXPECT_GT(audio::rms_channel(right, 1), 1.5 * audio::rms_channel(right, 0));
    EXPECT_EQ(sound->mixer().playing_voices(), 1) << "one torch, one crackle";
    world.destroy(torch);
    frame(0.02); // its fade-out
    EXPECT_LT(audio::rms(frame(0.2)), 1e-6) << "a torch taken away stops crackling";
}

TEST_F(SoundWorld, OnlyTheNearestTorchesCrackle) {
    for (int i = 0; i < 10; ++i) {
        const ecs::Entity t = world.create();
        world.emplace<Torch>(t);
        world.emplace<PointLight>(t).position = {10.0f + float(i), 12.0f};
    }
    frame(0.05);
    EXPECT_EQ(sound->mixer().playing_voices(), GameSound::crackling_torches);
}

TEST_F(SoundWorld, AnEditIsHeardWhereItHappenedAndItsCueIsTakenOnce) {
    world.resource<SoundCues>().entries.push_back({SoundCue::dig, {13.5f, 10.5f}}); // to the right
    const std::vector<float> dig = frame(0.25);
    EXPECT_TRUE(world.resource<SoundCues>().entries.empty());
    EXPECT_EQ(sound->sounds_played(), 1u);
    EXPECT_GT(audio::rms_channel(dig, 1), 0.005) << "digging has energy";
    EXPECT_GT(audio::rms_channel(dig, 1), 1.5 * audio::rms_channel(dig, 0));
    EXPECT_LT(audio::rms(frame(0.1)), 1e-6) << "played once";
}

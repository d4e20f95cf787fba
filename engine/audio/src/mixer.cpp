#include "lantern/audio/mixer.hpp"

#include <al.h>
#include <alc.h>
#include <alext.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include <fcntl.h>
#include <unistd.h>

namespace lantern::audio {

struct Mixer::State {
    ALCdevice* device = nullptr;
    ALCcontext* context = nullptr;
    bool loopback = false;
    LPALCRENDERSAMPLESSOFT render_samples = nullptr;
    MixerOptions options;
    std::vector<ALuint> buffers;
    std::vector<ALuint> voices; // the one-shot pool
    std::size_t next_voice = 0;
    std::vector<ALuint> loops;  // LoopId - 1 -> source (0: stopped and deleted)

    void current() const { alcMakeContextCurrent(context); }
    ~State() {
        if (context) {
            alcMakeContextCurrent(context);
            for (ALuint v : voices) alSourceStop(v);
            if (!voices.empty()) alDeleteSources(ALsizei(voices.size()), voices.data());
            for (ALuint l : loops)
                if (l) {
                    alSourceStop(l);
                    alDeleteSources(1, &l);
                }
            if (!buffers.empty()) alDeleteBuffers(ALsizei(buffers.size()), buffers.data());
            alcMakeContextCurrent(nullptr);
            alcDestroyContext(context);
        }
        if (device) alcCloseDevice(device);
    }
};

namespace {

// Sends stderr to /dev/null while it lives (single-threaded start-up only).
class QuietStderr {
  public:
    explicit QuietStderr(bool on) {
        if (!on) return;
        std::fflush(stderr);
        saved_ = ::dup(STDERR_FILENO);
        const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (saved_ < 0 || null < 0 || ::dup2(null, STDERR_FILENO) < 0) {
            if (null >= 0) ::close(null);
            if (saved_ >= 0) ::close(saved_);
            saved_ = -1;
            return;
        }
        ::close(null);
    }
    ~QuietStderr() {
        if (saved_ < 0) return;
        std::fflush(stderr);
        ::dup2(saved_, STDERR_FILENO);
        ::close(saved_);
    }
    QuietStderr(const QuietStderr&) = delete;
    QuietStderr& operator=(const QuietStderr&) = delete;

  private:
    int saved_ = -1;
};

// Sets the distance falloff of a source (MixerOptions) at `position`.
void place_source(ALuint source, const MixerOptions& o, glm::vec3 position, float gain) {
    alSourcef(source, AL_REFERENCE_DISTANCE, o.reference_distance);
    alSourcef(source, AL_MAX_DISTANCE, o.max_distance);
    alSourcef(source, AL_ROLLOFF_FACTOR, 1.0f);
    alSourcef(source, AL_GAIN, gain);
    alSource3f(source, AL_POSITION, position.x, position.y, position.z);
}

} // namespace

Mixer::Mixer(std::unique_ptr<State> state) : s_(std::move(state)) {}
Mixer::~Mixer() = default;

Result<std::unique_ptr<Mixer>> Mixer::start(std::unique_ptr<State> s, const int* attributes) {
    s->context = alcCreateContext(s->device, attributes);
    if (!s->context || !alcMakeContextCurrent(s->context))
        return Error{"audio: cannot create an OpenAL context (ALC error " + std::to_string(alcGetError(s->device)) + ")", 1};
    // Linear falloff from the reference to the max distance, silent beyond (MixerOptions).
    alDistanceModel(AL_LINEAR_DISTANCE_CLAMPED);
    s->voices.resize(std::size_t(std::max(1, s->options.voice_count)));
    alGenSources(ALsizei(s->voices.size()), s->voices.data());
    if (alGetError() != AL_NO_ERROR) {
        s->voices.clear();
        return Error{"audio: cannot create " + std::to_string(s->options.voice_count) + " voices", 1};
    }
    return std::unique_ptr<Mixer>(new Mixer(std::move(s)));
}


Result<std::unique_ptr<Mixer>> Mixer::open_device(const MixerOptions& options) {
    auto s = std::make_unique<State>();
    s->options = options;
    {
        // Probing the backends on a machine without sound prints a screenful of ALSA and
        // OpenAL complaints to stderr; the one line the caller prints says it all.
        // LANTERN_AUDIO_DEBUG=1 lets them through.
        const char* debug = std::getenv("LANTERN_AUDIO_DEBUG");
        const bool quiet = options.quiet_probe && !(debug && *debug && std::string(debug) != "0");
        QuietStderr hush(quiet);
        s->device = alcOpenDevice(nullptr);
    }
    if (!s->device) return Error{"audio: no output device", 1};
    return start(std::move(s), nullptr);
}

Result<std::unique_ptr<Mixer>> Mixer::open_loopback(int sample_rate, const MixerOptions& options) {
    if (!alcIsExtensionPresent(nullptr, "ALC_SOFT_loopback"))
        return Error{"audio: this OpenAL has no loopback device (ALC_SOFT_loopback)", 1};
    auto open = reinterpret_cast<LPALCLOOPBACKOPENDEVICESOFT>(alcGetProcAddress(nullptr, "alcLoopbackOpenDeviceSOFT"));
    auto supported =
        reinterpret_cast<LPALCISRENDERFORMATSUPPORTEDSOFT>(alcGetProcAddress(nullptr, "alcIsRenderFormatSupportedSOFT"));
    auto s = std::make_unique<State>();
    s->options = options;
    s->loopback = true;
    s->render_samples = reinterpret_cast<LPALCRENDERSAMPLESSOFT>(alcGetProcAddress(nullptr, "alcRenderSamplesSOFT"));
    if (!open || !supported || !s->render_samples) return Error{"audio: the loopback functions are missing", 1};
    s->device = open(nullptr);
    if (!s->device) return Error{"audio: cannot open a loopback device", 1};
    if (!supported(s->device, sample_rate, ALC_STEREO_SOFT, ALC_FLOAT_SOFT))
        return Error{"audio: the loopback device cannot mix stereo float at " + std::to_string(sample_rate) + " Hz", 1};
    // Plain stereo panning, not HRTF: the channels' loudness then follows the direction.
    const ALCint attributes[] = {ALC_FORMAT_CHANNELS_SOFT, ALC_STEREO_SOFT, ALC_FORMAT_TYPE_SOFT, ALC_FLOAT_SOFT,
                                 ALC_FREQUENCY,            sample_rate,     ALC_HRTF_SOFT,        ALC_FALSE,
                                 0};
    return start(std::move(s), attributes);
}

Mixer::SoundId Mixer::add(const Sound& sound) {
    s_->current();
    ALuint buffer = 0;
    alGenBuffers(1, &buffer);
    alBufferData(buffer, AL_FORMAT_MONO16, sound.samples.data(), ALsizei(sound.samples.size() * sizeof(std::int16_t)),
                 sound.sample_rate);
    s_->buffers.push_back(buffer);
    return SoundId(s_->buffers.size()); // 1-based
}

void Mixer::play(SoundId sound, glm::vec3 position, float gain) {
    if (sound == 0 || sound > s_->buffers.size()) return;
    s_->current();
    // A free voice, else the one started longest ago (the pool is used round-robin).
    ALuint voice = 0;
    for (std::size_t k = 0; k < s_->voices.size() && !voice; ++k) {
        const ALuint v = s_->voices[(s_->next_voice + k) % s_->voices.size()];
        ALint state = AL_STOPPED;
        alGetSourcei(v, AL_SOURCE_STATE, &state);
        if (state != AL_PLAYING) voice = v;
    }
    if (!voice) voice = s_->voices[s_->next_voice % s_->voices.size()];
    s_->next_voice = (std::size_t(std::find(s_->voices.begin(), s_->voices.end(), voice) - s_->voices.begin()) + 1) %
                     s_->voices.size();
    alSourceStop(voice);
    alSourcei(voice, AL_BUFFER, ALint(s_->buffers[sound - 1]));
    alSourcei(voice, AL_LOOPING, AL_FALSE);
    place_source(voice, s_->options, position, gain);
    alSourcePlay(voice);
}

Mixer::LoopId Mixer::loop(SoundId sound, glm::vec3 position, float gain) {
    if (sound == 0 || sound > s_->buffers.size()) return 0;
    s_->current();
    ALuint source = 0;
    alGenSources(1, &source);
    if (alGetError() != AL_NO_ERROR) return 0;
    alSourcei(source, AL_BUFFER, ALint(s_->buffers[sound - 1]));
    alSourcei(source, AL_LOOPING, AL_TRUE);
    place_source(source, s_->options, position, gain);
    alSourcePlay(source);
    auto free_slot = std::find(s_->loops.begin(), s_->loops.end(), 0u);
    if (free_slot != s_->loops.end()) {
        *free_slot = source;
        return LoopId(free_slot - s_->loops.begin()) + 1;
    }
    s_->loops.push_back(source);
    return LoopId(s_->loops.size());
}

void Mixer::move(LoopId loop, glm::vec3 position) {
    if (loop == 0 || loop > s_->loops.size() || !s_->loops[loop - 1]) return;
    s_->current();
    alSource3f(s_->loops[loop - 1], AL_POSITION, position.x, position.y, position.z);
}

void Mixer::stop(LoopId loop) {
    if (loop == 0 || loop > s_->loops.size() || !s_->loops[loop - 1]) return;
    s_->current();
    ALuint& source = s_->loops[loop - 1];
    alSourceStop(source);
    alDeleteSources(1, &source);
    source = 0;
}

void Mixer::set_listener(const Listener& l) {
    s_->current();
    alListener3f(AL_POSITION, l.position.x, l.position.y, l.position.z);
    const ALfloat orientation[] = {l.forward.x, l.forward.y, l.forward.z, l.up.x, l.up.y, l.up.z};
    alListenerfv(AL_ORIENTATION, orientation);
}

void Mixer::set_volume(float volume) {
    s_->current();
    alListenerf(AL_GAIN, std::clamp(volume, 0.0f, 1.0f));
}

std::vector<float> Mixer::render(int frames) {
    std::vector<float> out(std::size_t(std::max(frames, 0)) * 2, 0.0f);
    if (!s_->loopback || frames <= 0) return out;
    s_->current();
    s_->render_samples(s_->device, out.data(), frames);
    return out;
}

bool Mixer::is_loopback() const {
    return s_->loopback;
}

std::string Mixer::device_name() const {
    const ALCchar* name = alcGetString(s_->device, ALC_DEVICE_SPECIFIER);
    return name ? name : "";
}

int Mixer::playing_voices() const {
    s_->current();
    int n = 0;
    const auto count = [&](ALuint v) {
        ALint state = AL_STOPPED;
        alGetSourcei(v, AL_SOURCE_STATE, &state);
        n += state == AL_PLAYING ? 1 : 0;
    };
    for (ALuint v : s_->voices) count(v);
    for (ALuint l : s_->loops)
        if (l) count(l);
    return n;
}

} // namespace lantern::audio

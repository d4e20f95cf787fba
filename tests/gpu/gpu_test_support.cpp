#include "gpu/gpu_test_support.hpp"

#include <bit>
#include <cstdlib>
#include <memory>

namespace lantern::test {

namespace {

struct SharedDevice {
    std::unique_ptr<gpu::Device> device;
    std::string error;
};

SharedDevice& shared() {
    // Destroyed at exit, after every test: tests hold no resources past TearDown.
    static SharedDevice instance = [] {
        gpu::DeviceOptions options;
        options.validation = true;
        options.application_name = "lantern tests";
        SharedDevice s;
        auto created = gpu::Device::create(options);
        if (created) s.device = std::move(created).value();
        else s.error = created.error().message;
        return s;
    }();
    return instance;
}

std::string join_messages(const std::vector<std::string>& messages) {
    std::string out;
    for (const auto& m : messages) out += "\n  " + m;
    return out;
}

} // namespace

gpu::Device* shared_gpu_device(std::string* why_not) {
    SharedDevice& s = shared();
    if (!s.device && why_not) *why_not = s.error;
    return s.device.get();
}

void GpuTest::SetUp() {
    std::string why;
    device_ = shared_gpu_device(&why);
    if (!device_) LANTERN_SKIP_NO_GPU(why);
    device_->clear_validation_messages();
}

void GpuTest::TearDown() {
    if (!device_) return;
    device_->wait_idle();
    EXPECT_EQ(device_->validation_message_count(), 0u)
        << "Vulkan validation messages:" << join_messages(device_->validation_messages());
}

ScopedEnv::ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) {
        had_old_ = true;
        old_ = old;
    }
    if (value) ::setenv(name, value, 1);
    else ::unsetenv(name);
}

ScopedEnv::~ScopedEnv() {
    if (had_old_) ::setenv(name_.c_str(), old_.c_str(), 1);
    else ::unsetenv(name_.c_str());
}

std::uint16_t float_to_half(float value) {
    const std::uint32_t f = std::bit_cast<std::uint32_t>(value);
    const std::uint32_t sign = (f >> 16) & 0x8000u;
    const std::uint32_t abs = f & 0x7fffffffu;
    if (abs >= 0x7f800000u) // Inf or NaN
        return static_cast<std::uint16_t>(sign | 0x7c00u | (abs > 0x7f800000u ? 0x200u : 0u));
    if (abs >= 0x477ff000u) return static_cast<std::uint16_t>(sign | 0x7c00u); // rounds past 65504
    if (abs < 0x38800000u) {
        // Subnormal half (or zero): shift the 24-bit significand, round to nearest even.
        if (abs < 0x33000000u) return static_cast<std::uint16_t>(sign); // below half of the smallest
        const std::uint32_t exponent = abs >> 23;
        const std::uint32_t significand = (abs & 0x7fffffu) | 0x800000u;
        const std::uint32_t shift = 126 - exponent; // in [14, 24]
        std::uint32_t half = significand >> shift;
        const std::uint32_t rest = significand & ((1u << shift) - 1);
        const std::uint32_t halfway = 1u << (shift - 1);
        if (rest > halfway || (rest == halfway && (half & 1u))) ++half;
        return static_cast<std::uint16_t>(sign | half);
    }
    // Normal: rebias the exponent (127 -> 15) and round the 23-bit significand to 10 bits.
    std::uint32_t half = ((abs - 0x38000000u) >> 13);
    const std::uint32_t rest = abs & 0x1fffu;
    if (rest > 0x1000u || (rest == 0x1000u && (half & 1u))) ++half; // may carry into the exponent: correct
    return static_cast<std::uint16_t>(sign | half);
}

float half_to_float(std::uint16_t half) {
    const std::uint32_t sign = static_cast<std::uint32_t>(half & 0x8000u) << 16;
    const std::uint32_t exponent = (half >> 10) & 0x1fu;
    std::uint32_t significand = half & 0x3ffu;
    if (exponent == 0x1f) return std::bit_cast<float>(sign | 0x7f800000u | (significand << 13));
    if (exponent != 0) return std::bit_cast<float>(sign | ((exponent + 112) << 23) | (significand << 13));
    if (significand == 0) return std::bit_cast<float>(sign);
    // Subnormal: normalise.
    int e = -1;
    do {
        ++e;
        significand <<= 1;
    } while (!(significand & 0x400u));
    return std::bit_cast<float>(sign | static_cast<std::uint32_t>(112 - e) << 23 | ((significand & 0x3ffu) << 13));
}

} // namespace lantern::test

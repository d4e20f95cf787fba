// Helpers for tests that need a Vulkan device (GPU layer and GI backend suites).
//
// One Device per test process, created on first use with validation on (and, where the
// layer is installed, every warning/error message counted). Where no Vulkan device exists
// the tests GTEST_SKIP with Device::create's reason, so CTest reports them as skipped, never
// as silently passed.
//
//   class MyGpuTest : public lantern::test::GpuTest {};
//   TEST_F(MyGpuTest, Something) { auto& dev = device(); ... }
//
// GpuTest::TearDown waits for the GPU, frees deferred deletions and fails the test if any
// validation message arrived during it (the messages are printed). Resources held in
// fixture members should be reset in the fixture's TearDown before GpuTest::TearDown, so
// messages their destruction causes are caught too.
#pragma once

#include "common/test_support.hpp"
#include "lantern/gpu/device.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace lantern::test {

// The process-wide test Device, or nullptr with the reason in *why_not.
gpu::Device* shared_gpu_device(std::string* why_not = nullptr);

class GpuTest : public ::testing::Test {
  protected:
    void SetUp() override;
    void TearDown() override;
    gpu::Device& device() { return *device_; }

  private:
    gpu::Device* device_ = nullptr;
};

// Sets an environment variable for the scope and restores the previous value (or unsets).
class ScopedEnv {
  public:
    ScopedEnv(const char* name, const char* value);
    ~ScopedEnv();
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

  private:
    std::string name_;
    std::string old_;
    bool had_old_ = false;
};

template <typename T>
std::span<const std::byte> bytes_of(const std::vector<T>& values) {
    return std::as_bytes(std::span<const T>(values));
}

// Reads back a whole buffer as values of T (size must be a multiple of sizeof(T)).
template <typename T>
std::vector<T> read_back_as(gpu::Device& device, const gpu::Buffer& buffer) {
    const std::vector<std::byte> bytes = device.read_back(buffer);
    std::vector<T> out(bytes.size() / sizeof(T));
    std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
    return out;
}

// IEEE 754 binary16 conversions, round to nearest even (the CPU reference for
// packHalf2x16 and RGBA16F texels). NaN stays NaN; overflow becomes infinity.
std::uint16_t float_to_half(float value);
float half_to_float(std::uint16_t half);

} // namespace lantern::test

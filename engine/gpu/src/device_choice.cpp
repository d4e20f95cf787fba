// The device choice rule (device_choice.hpp).
#include "lantern/gpu/device_choice.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace lantern::gpu {

namespace {

std::string lower(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

std::string describe(const DeviceCandidate& c) {
    return std::to_string(c.index) + " '" + c.name + "' (" + to_string(c.type) + ")";
}

std::string join(const std::vector<std::string>& parts, const char* separator) {
    std::string out;
    for (const auto& part : parts) {
        if (!out.empty()) out += separator;
        out += part;
    }
    return out;
}

bool matches(const DeviceCandidate& c, std::string_view selector) {
    std::uint32_t index = 0;
    const auto [end, ec] = std::from_chars(selector.data(), selector.data() + selector.size(), index);
    if (ec == std::errc() && end == selector.data() + selector.size()) return index == c.index;
    return lower(c.name).find(lower(selector)) != std::string::npos;
}

} // namespace

int device_type_rank(DeviceType type) {
    switch (type) {
    case DeviceType::discrete: return 0;
    case DeviceType::integrated: return 1;
    case DeviceType::virtual_gpu: return 2;
    case DeviceType::cpu: return 3;
    default: return 4;
    }
}

Result<std::size_t> choose_device(std::span<const DeviceCandidate> candidates,
                                  std::string_view selector, std::string_view selector_source) {
    std::vector<std::string> everything;
    for (const auto& c : candidates) everything.push_back(describe(c));
    if (candidates.empty())
        return make_error("no Vulkan device: the Vulkan loader found no physical device");

    std::size_t best = candidates.size();
    bool any_match = false;
    std::vector<std::string> rejected;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        const DeviceCandidate& c = candidates[i];
        if (!selector.empty() && !matches(c, selector)) continue;
        any_match = true;
        if (!c.problems.empty()) {
            rejected.push_back(describe(c) + ": " + join(c.problems, "; "));
            continue;
        }
        if (best == candidates.size() ||
            device_type_rank(c.type) < device_type_rank(candidates[best].type))
            best = i;
    }
    if (!any_match)
        return make_error("no Vulkan device: " + std::string(selector_source) + "='" +
                          std::string(selector) + "' matches none of: " + join(everything, ", "));
    if (best == candidates.size())
        return make_error("no Vulkan device: no suitable device: " + join(rejected, " | "));
    return best;
}

} // namespace lantern::gpu

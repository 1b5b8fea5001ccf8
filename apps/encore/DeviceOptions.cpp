#include "DeviceOptions.h"

#include <charconv>
#include <string>

namespace encore::app {

Result<std::size_t> parseDeviceIndex(std::string_view text) {
    std::size_t index = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), index);
    if (text.empty() || error != std::errc{} || end != text.data() + text.size()) {
        return makeError(ErrorCode::InvalidArgument,
                         "'" + std::string(text) +
                             "' is not a device index (0, 1, ...: `encore info` lists them).");
    }
    return index;
}

Result<std::vector<std::size_t>> parseDeviceList(
    std::string_view text,
    std::span<const gpu::AdapterDescription> adapters) {
    if (text == "all") {
        return gpu::adaptersLike(adapters);
    }
    std::vector<std::size_t> devices;
    while (true) {
        const std::size_t comma = text.find(',');
        ENCORE_TRY_ASSIGN(auto index, parseDeviceIndex(text.substr(0, comma)));
        if (index >= adapters.size()) {
            return makeError(ErrorCode::NoAdapter,
                             "there is no device " + std::to_string(index) + ": this machine has " +
                                 std::to_string(adapters.size()) + " adapter" +
                                 (adapters.size() == 1 ? "" : "s") +
                                 " (`encore info` lists them).");
        }
        devices.push_back(index);
        if (comma == std::string_view::npos) {
            return devices;
        }
        text.remove_prefix(comma + 1);
    }
}

}  // namespace encore::app

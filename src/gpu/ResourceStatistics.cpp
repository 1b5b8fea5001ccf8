#include "gpu/ResourceStatistics.h"

#include <dawn/native/DawnNative.h>

#include <cstdio>
#include <cstring>
#include <string_view>

namespace encore::gpu {

namespace {

// Dawn names each object "device_<address>/buffer_<address>" or ".../texture_<address>" and
// reports its size once, under MemoryDump::kNameSize.
class CountingDump : public dawn::native::MemoryDump {
  public:
    explicit CountingDump(ResourceStatistics& statistics) : mStatistics(statistics) {}

    void AddScalar(const char* name, const char* key, const char* units, uint64_t value) override {
        (void)units;
        if (std::strcmp(key, kNameSize) != 0) {
            return;
        }
        const std::string_view object(name);
        const auto slash = object.rfind('/');
        const std::string_view leaf =
            slash == std::string_view::npos ? object : object.substr(slash + 1);
        if (leaf.starts_with("buffer_")) {
            ++mStatistics.buffers;
            mStatistics.bufferBytes += value;
        } else if (leaf.starts_with("texture_")) {
            ++mStatistics.textures;
            mStatistics.textureBytes += value;
        }
    }
    void AddString(const char*, const char*, const std::string&) override {}

  private:
    ResourceStatistics& mStatistics;
};

}  // namespace

ResourceStatistics resourceStatistics(const wgpu::Device& device) {
    ResourceStatistics statistics;
    if (device) {
        CountingDump dump(statistics);
        dawn::native::DumpMemoryStatistics(device.Get(), &dump);
    }
    return statistics;
}

std::uint64_t processMemoryMappings() {
    std::uint64_t lines = 0;
    if (std::FILE* maps = std::fopen("/proc/self/maps", "r")) {
        for (int c = std::fgetc(maps); c != EOF; c = std::fgetc(maps)) {
            lines += c == '\n';
        }
        std::fclose(maps);
    }
    return lines;
}

}  // namespace encore::gpu

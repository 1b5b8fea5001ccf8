#include "core/ProcessMemory.h"

#include <malloc.h>

#include <cstdlib>
#include <string_view>

namespace encore {

bool keepFreedMemoryInProcess() {
    static const bool kept = [] {
        const char* setting = std::getenv("ENCORE_KEEP_FREED_MEMORY");
        if (setting && std::string_view(setting) == "0") {
            return false;
        }
        // 32 MiB is glibc's largest mmap threshold on 64-bit (half its arenas' heap size); a
        // fixed one also stops glibc from moving it. Larger blocks are still mapped per use.
        const bool mmapSet = mallopt(M_MMAP_THRESHOLD, 32 << 20) == 1;
        const bool trimSet = mallopt(M_TRIM_THRESHOLD, 1 << 30) == 1;
        return mmapSet && trimSet;
    }();
    return kept;
}

}  // namespace encore

#include "encore/batch/ViewImages.h"

#include <cstdio>

namespace encore::batch {

std::string viewStem(std::size_t index, ViewImage kind) {
    char stem[32];
    std::snprintf(stem, sizeof(stem), "%03zu", index);
    switch (kind) {
        case ViewImage::Normal:
            return std::string(stem) + "_normal";
        case ViewImage::Depth:
            return std::string(stem) + "_depth";
        case ViewImage::Color:
            break;
    }
    return stem;
}

}  // namespace encore::batch

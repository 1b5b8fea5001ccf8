#include "TestFiles.h"

#include <fstream>
#include <sstream>

namespace encore::test {

std::string readBytes(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream bytes;
    bytes << file.rdbuf();
    return bytes.str();
}

}  // namespace encore::test

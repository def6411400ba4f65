#include "Screenshot.h"

#include "Gl.h"

#include "model/Error.h"

#include <stb_image_write.h>

#include <cstdint>
#include <cstring>
#include <vector>

namespace netsculpt::studio {

void writeFramebufferPng(const std::filesystem::path& path, int width, int height) {
    std::vector<std::uint8_t> pixels(std::size_t(width) * std::size_t(height) * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
    // OpenGL's first row is the bottom one; PNG's is the top.
    const std::size_t stride = std::size_t(width) * 3;
    std::vector<std::uint8_t> row(stride);
    for (int y = 0; y < height / 2; ++y) {
        std::uint8_t* a = pixels.data() + std::size_t(y) * stride;
        std::uint8_t* b = pixels.data() + std::size_t(height - 1 - y) * stride;
        std::memcpy(row.data(), a, stride);
        std::memcpy(a, b, stride);
        std::memcpy(b, row.data(), stride);
    }
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    if (!stbi_write_png(path.string().c_str(), width, height, 3, pixels.data(), int(stride)))
        throw UserError("screenshot: cannot write \"" + path.string() + "\"");
}

} // namespace netsculpt::studio

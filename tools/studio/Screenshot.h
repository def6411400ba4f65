#pragma once
// Reads the current OpenGL framebuffer (the back buffer, after drawing and before the swap) and
// writes it as a PNG with stb_image_write.

#include <filesystem>

namespace netsculpt::studio {

/// Writes the width x height pixels of the bound framebuffer to `path` (RGB, top row first).
/// Throws UserError when the file cannot be written.
void writeFramebufferPng(const std::filesystem::path& path, int width, int height);

} // namespace netsculpt::studio

#include <string>

#include "raybudget/error.h"
#include "raybudget/image_io.h"

// Our own static copy of the stb writer: libtinygltf.so exports stb symbols of its own.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace raybudget {

void writePng(const std::filesystem::path& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8) {
  if (rgba8.size() != size_t(width) * height * 4) throw Error(path.string() + ": PNG data does not match " + std::to_string(width) + "x" + std::to_string(height));
  if (!stbi_write_png(path.string().c_str(), int(width), int(height), 4, rgba8.data(), int(width * 4)))
    throw Error(path.string() + ": could not write PNG");
}

}  // namespace raybudget

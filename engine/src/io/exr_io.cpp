#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfRgbaFile.h>

#include "raybudget/error.h"
#include "raybudget/image_io.h"

namespace raybudget {

void writeExr(const std::filesystem::path& path, uint32_t width, uint32_t height, const std::vector<uint16_t>& rgbaHalf) {
  if (rgbaHalf.size() != size_t(width) * height * 4) throw Error(path.string() + ": EXR data does not match the image size");
  try {
    std::vector<Imf::Rgba> pixels(size_t(width) * height);
    for (size_t i = 0; i < pixels.size(); ++i) {
      pixels[i].r.setBits(rgbaHalf[i * 4 + 0]);
      pixels[i].g.setBits(rgbaHalf[i * 4 + 1]);
      pixels[i].b.setBits(rgbaHalf[i * 4 + 2]);
      pixels[i].a.setBits(rgbaHalf[i * 4 + 3]);
    }
    Imf::RgbaOutputFile file(path.string().c_str(), int(width), int(height), Imf::WRITE_RGBA);
    file.setFrameBuffer(pixels.data(), 1, width);
    file.writePixels(int(height));
  } catch (const std::exception& e) {
    throw Error(path.string() + ": could not write EXR: " + e.what());
  }
}

std::vector<float> readExr(const std::filesystem::path& path, uint32_t& width, uint32_t& height) {
  try {
    Imf::RgbaInputFile file(path.string().c_str());
    const Imath::Box2i dw = file.dataWindow();
    width = uint32_t(dw.max.x - dw.min.x + 1);
    height = uint32_t(dw.max.y - dw.min.y + 1);
    std::vector<Imf::Rgba> pixels(size_t(width) * height);
    file.setFrameBuffer(pixels.data() - dw.min.x - dw.min.y * int(width), 1, width);
    file.readPixels(dw.min.y, dw.max.y);
    std::vector<float> out(pixels.size() * 4);
    for (size_t i = 0; i < pixels.size(); ++i) {
      out[i * 4 + 0] = pixels[i].r;
      out[i * 4 + 1] = pixels[i].g;
      out[i * 4 + 2] = pixels[i].b;
      out[i * 4 + 3] = pixels[i].a;
    }
    return out;
  } catch (const std::exception& e) {
    throw Error(path.string() + ": could not read EXR: " + e.what());
  }
}

}  // namespace raybudget

// Writing the frame's images: PNG for display, OpenEXR (half float) for linear HDR.
#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

namespace raybudget {

void writePng(const std::filesystem::path& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba8);
void writeExr(const std::filesystem::path& path, uint32_t width, uint32_t height, const std::vector<uint16_t>& rgbaHalf);

// Reads back an EXR written by writeExr (tests and tools): RGBA as floats.
std::vector<float> readExr(const std::filesystem::path& path, uint32_t& width, uint32_t& height);

}  // namespace raybudget

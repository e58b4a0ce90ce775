// libFuzzer harness for the glTF loader (.gltf and .glb alike: the loader tells them apart
// by their first bytes). Every input must load or be refused with raybudget::Error; any
// other exception, a crash, a sanitizer report, a hang or a huge allocation is a finding.
// Run by scripts/fuzz.sh, from a working directory holding the seeds' buffer files.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "raybudget/error.h"
#include "raybudget/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path path = std::filesystem::current_path() / ("fuzz-input-" + std::to_string(getpid()) + ".gltf");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  try {
    const raybudget::Scene scene = raybudget::loadScene(path);
    (void)scene;
  } catch (const raybudget::Error&) {
    // refused with a message: the expected outcome for malformed input
  }
  return 0;
}

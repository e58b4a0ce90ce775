// Command-line parsing for the `raybudget` tool: every value is checked, and a bad one is
// reported with the option's name.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "raybudget/renderer.h"

namespace raybudget::cli {

struct RenderCommand {
  std::string scene;
  uint32_t frames = 1;
  std::string out = "out";
  std::string camera = "static";  // static | orbit
  RenderSettings settings;
};

// Parses `render` arguments (after the word "render"). Throws raybudget::Error.
RenderCommand parseRender(const std::vector<std::string>& args);

extern const char* kUsage;

}  // namespace raybudget::cli

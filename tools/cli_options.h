// Command-line parsing for the `raybudget` tool: every value is checked, and a bad one is
// reported with the option's name.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "raybudget/camera.h"
#include "raybudget/renderer.h"

namespace raybudget::cli {

struct RenderCommand {
  std::string scene;
  uint32_t frames = 1;
  std::string out = "out";
  std::string camera = "static";  // static | orbit | flythrough
  bool itemStats = false;         // write items.csv: per object and effect, what its tracing cost and removed
  // --explain: print the pass plan; --explain=frames: also each frame's selected items
  enum class Explain { Off, Plan, Frames } explain = Explain::Off;
  LoadOptions load;  // --strict: refuse what the loader would repair
  RenderSettings settings;
};

// Parses `render` arguments (after the word "render"). Throws raybudget::Error.
RenderCommand parseRender(const std::vector<std::string>& args);

extern const char* kUsage;

// Frame `frame` of `frameCount` on the named camera path from `start`: "orbit",
// "flythrough" (shaped by `shape`: flythroughShape), or anything else the start itself (static).
Camera cameraOnPath(const std::string& path, const Camera& start, uint32_t frame, uint32_t frameCount, FlythroughShape shape = {});

// The camera `stepsBack` steps before frame `frame` of that path, a step a hundredth of the
// path's spacing between frames: a camera moving along it towards the frame at a steady
// speed (the benchmark's lead-in; an orbit wraps round, a fly-through stops at its start).
Camera cameraApproaching(const std::string& path, const Camera& start, uint32_t frame, uint32_t frameCount, uint32_t stepsBack,
                         FlythroughShape shape = {});

// The median (the mean of the two middle values for an even count); 0 when empty.
double median(std::vector<double> values);

// An argument no option took: the scene, once. An unknown option (named with `hint`, e.g.
// the command's usage) or a second scene throws raybudget::Error.
void sceneArgument(const std::string& arg, std::string& scene, const std::string& hint);

// `option`'s value as a whole number in lo..hi, a finite number in lo..hi, or a positive finite
// number; throws raybudget::Error naming the option otherwise.
uint32_t parseUint(const std::string& option, const std::string& value, uint32_t lo, uint32_t hi);
float parseWithin(const std::string& option, const std::string& value, float lo, float hi);
float parsePositive(const std::string& option, const std::string& value);

// The value after the option at args[i], moving i onto it; throws raybudget::Error naming the
// option when none follows.
const std::string& optionValue(const std::vector<std::string>& args, size_t& i);

// The image size and device options the sweep and the soak share, and the settings they
// start from.
struct RenderTarget {
  uint32_t width = 640, height = 360;
  std::string device;
  bool validation = false;
  // Takes --width, --height (16..16384), --device or --validation at args[i]; false for any
  // other argument.
  bool parse(const std::vector<std::string>& args, size_t& i);
  RenderSettings settings() const;      // size, device and validation; the rest default
  void applyTo(RenderSettings& s) const;  // sets size, device and validation in `s`
};

// The options `render` and `sweep` share that change what a frame shows (the fallbacks, the
// shadow maps' biases, the temporal fill): takes --no-screen-space-transmission,
// --no-reflection-probes, --no-screen-space-reflections, --no-temporal-fill,
// --shadow-normal-offset X or --shadow-slope-bias X (0..16) at args[i] into `s`; false for any
// other argument.
bool parseImageOption(const std::vector<std::string>& args, size_t& i, RenderSettings& s);

}  // namespace raybudget::cli

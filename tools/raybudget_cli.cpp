// The `raybudget` command: renders a glTF scene with the deferred renderer and writes the
// last frame (PNG + EXR) and per-pass GPU times for every frame (stats.csv).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "cli_options.h"
#include "explain.h"
#include "soak.h"
#include "sweep.h"
#include "raybudget/raybudget.h"

namespace {

void writeItemStats(const std::filesystem::path& path, const std::vector<raybudget::ObjectMetrics>& metrics) {
  std::FILE* f = std::fopen(path.string().c_str(), "w");
  if (!f) throw raybudget::Error("cannot write " + path.string());
  std::fprintf(f, "object,effect,pixels,traced,rate,error,ticks,work,benefit,cost_per_pixel,fill_per_pixel,traced_pixels,skipped_pixels,skipped_ticks,"
                 "tile_share\n");
  const char* effects[] = {"shadows", "reflections", "refractions"};
  for (size_t i = 0; i < metrics.size(); ++i) {
    const raybudget::ObjectMetrics& m = metrics[i];
    const uint32_t pixels[] = {m.pixels, m.reflectionPixels, m.refractionPixels};
    for (uint32_t e = 0; e < 3; ++e)
      if (pixels[e] > 0)
        std::fprintf(f, "%zu,%s,%u,%d,%s,%.6g,%llu,%u,%.6g,%.6g,%.6g,%u,%u,%llu,%.6g\n", i, effects[e], pixels[e], int((m.selectedItems >> e) & 1u),
                     raybudget::itemRateName(m.itemRate[e]), double(m.itemError[e]),
                     static_cast<unsigned long long>(m.itemTicks[e]), m.itemWork[e], double(m.itemBenefit[e]), double(m.itemCostPerPixel[e]),
                     double(m.itemFillPerPixel[e]), m.itemTracedPixels[e], m.itemSkippedPixels[e],
                     static_cast<unsigned long long>(m.itemSkippedTicks[e]), double(m.itemTileShare[e]));
  }
  std::fclose(f);
}

int render(const raybudget::cli::RenderCommand& c) {
  using namespace raybudget;
  const Scene scene = loadScene(c.scene, c.load);
  for (const std::string& w : scene.warnings) std::cerr << "warning: " << w << '\n';
  std::cout << c.scene << ": " << scene.objects.size() << " objects, " << scene.stats.triangles << " triangles, " << scene.lights.size()
            << " lights" << (scene.usesDefaultSun ? " (default sun)" : "") << ", " << scene.materials.size() << " materials\n";
  Renderer renderer(scene, c.settings);
  std::cout << "device: " << renderer.deviceName() << ", policy " << policyName(c.settings.policy) << ", tracer "
            << tracerName(c.settings.rayTracing.tracer) << '\n';
  const AccelStats accel = renderer.accelStats();
  std::printf("acceleration structure: built in %.1f ms, %zu triangles in %zu leaf entries (spatial splits in %zu meshes, %zu meshes "
              "sharing another's), %.1f bytes/triangle\n",
              accel.buildMs, accel.triangles, accel.references, accel.splitMeshes, accel.sharedMeshes,
              double(accel.bytes) / double(std::max<size_t>(1, accel.triangles)));
  std::filesystem::create_directories(c.out);
  StatsCsv stats(std::filesystem::path(c.out) / "stats.csv");
  std::vector<FrameTiming> all;
  const Camera start = c.camera == "static" ? defaultCamera(scene, renderer.aspect()) : pathStartCamera(scene, renderer.aspect());
  const FlythroughShape shape = flythroughShape(scene, start);
  auto collect = [&](const std::vector<FrameTiming>& done) {
    for (const FrameTiming& t : done) {
      stats.add(t);
      all.push_back(t);
    }
  };
  for (uint32_t f = 0; f < c.frames; ++f) {
    collect(renderer.render(cli::cameraOnPath(c.camera, start, f, c.frames, shape)));
    // Waits for the frame: explaining each frame serialises the frames in flight.
    if (c.explain == cli::RenderCommand::Explain::Frames) {
      const std::vector<ObjectMetrics> metrics = renderer.objectMetrics();
      cli::printFrameSelection(std::cout, f, metrics);
      if (c.itemStats) writeItemStats(std::filesystem::path(c.out) / ("items-" + std::to_string(f) + ".csv"), metrics);
    }
  }
  collect(renderer.finish());
  const FrameImages images = renderer.readback();
  writePng(std::filesystem::path(c.out) / "frame.png", images.width, images.height, images.ldrRgba8);
  writeExr(std::filesystem::path(c.out) / "frame.exr", images.width, images.height, images.hdrRgba16);

  if (c.itemStats) writeItemStats(std::filesystem::path(c.out) / "items.csv", renderer.objectMetrics());
  const PassSummary s = summarize(all);
  std::printf("GPU time per pass, median of %zu frames at %ux%u:\n", all.size(), images.width, images.height);
  for (size_t p = 0; p < kPassCount; ++p)
    if (s.frames[p] > 0) std::printf("  %-14s %8.3f ms  (%zu frames)\n", passName(Pass(p)), s.medianMs[p], s.frames[p]);
    else std::printf("  %-14s  skipped\n", passName(Pass(p)));
  std::printf("  %-14s %8.3f ms\n", "total", s.medianTotalMs);
  if (c.explain != cli::RenderCommand::Explain::Off) {
    std::cout << "(--explain adds the per-object metrics pass to coverage's time)\n";
    cli::printPassPlan(std::cout, renderer, all, renderer.objectMetrics());
  }
  std::cout << "wrote " << c.out << "/frame.png, frame.exr, stats.csv\n";
  const auto messages = renderer.validationMessages();
  for (const std::string& m : messages) std::cerr << m << '\n';
  return messages.empty() ? 0 : 3;
}

// `raybudget check SCENE [--strict]`: loads the scene only, prints what the loader repaired;
// exit 0 when it loads, 1 when it is refused.
int check(const std::vector<std::string>& args) {
  raybudget::LoadOptions options;
  std::string scene;
  for (const std::string& a : args) {
    if (a == "--strict") options.strict = true;
    else raybudget::cli::sceneArgument(a, scene, " (check takes SCENE and --strict)");
  }
  if (scene.empty()) throw raybudget::Error("check needs a scene file");
  const raybudget::Scene s = raybudget::loadScene(scene, options);
  for (const std::string& w : s.warnings) std::cout << "warning: " << w << '\n';
  std::cout << scene << ": loads: " << s.objects.size() << " objects, " << s.stats.triangles << " triangles, " << s.warnings.size()
            << " repairs\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
      std::cout << raybudget::cli::kUsage;
      return args.empty() ? 2 : 0;
    }
    if (args[0] == "devices") {
      for (const raybudget::core::DeviceReport& d : raybudget::core::availableDevices()) {
        std::cout << d.description << (d.missing.empty() ? ": can run raybudget" : ": cannot run raybudget") << '\n';
        for (const std::string& m : d.missing) std::cout << "  " << m << '\n';
      }
      return 0;
    }
    if (args[0] == "check") return check({args.begin() + 1, args.end()});
    if (args[0] == "render") return render(raybudget::cli::parseRender({args.begin() + 1, args.end()}));
    if (args[0] == "sweep" && args.size() > 1 && (args[1] == "--help" || args[1] == "-h")) {
      std::cout << raybudget::cli::kSweepUsage;
      return 0;
    }
    if (args[0] == "sweep") return raybudget::cli::runSweep(raybudget::cli::parseSweep({args.begin() + 1, args.end()}));
    if (args[0] == "soak" && args.size() > 1 && (args[1] == "--help" || args[1] == "-h")) {
      std::cout << raybudget::cli::kSoakUsage;
      return 0;
    }
    if (args[0] == "soak") return raybudget::cli::runSoak(raybudget::cli::parseSoak({args.begin() + 1, args.end()}));
    std::cerr << "raybudget: unknown command '" << args[0] << "'\n\n" << raybudget::cli::kUsage;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "raybudget: error: " << e.what() << '\n';
    return 1;
  }
}

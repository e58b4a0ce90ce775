#include "options.h"

#include "cli_options.h"
#include "object_rows.h"
#include "raybudget/error.h"

namespace raybudget::editor {

const char* kEditorUsage = R"(raybudget-editor SCENE.gltf|SCENE.glb [options]
Shows the hybrid frame as the budget renders it, lists the objects with the paper's
quantities and their items, and edits each object's K, Q and I live (saved into the glTF's
node extras.raybudget).
  --size WxH            window size (default 1280x720); the panels take 420 pixels of its
                        width, the viewport and the render the rest
  --policy NAME         none, all, paper, density, nearest, random, benefit, classified (default benefit)
  --budget-ms T         the ray-tracing stage's budget (default 100)
  --tracer NAME         compute or native (default compute)
  --rate R              full, half, quarter, sixteenth, or auto: benefit chooses a ray rate per
                        item and spends what its knapsack leaves on a share of the next item's
                        tiles (default full)
  --fixed-time-scale    keep the cost model's prior time scale: the selection is the same on
                        any machine (scripted tests)
  --overlay NAME        none, items, cost, benefit, ids, traced (default none)
  --validation          Khronos validation with synchronization validation; any message
                        makes the editor exit with status 3
  --device NAME         substring of the Vulkan device's name
  --script FILE         replay a session, one command a line (see editor/README.md), then quit
  --screenshot PATH     write the window's contents as PNG after the script or the first
                        frames, then quit
  --frames N            quit after N frames
Mouse: left drag orbits, right drag looks around, wheel dollies, a click picks; W A S D Q E fly.
Ctrl+Z undoes, Ctrl+Y redoes.
)";

EditorOptions parseEditorOptions(const std::vector<std::string>& args) {
  EditorOptions o;
  o.settings.policy = Policy::Benefit;
  o.settings.budgetMs = 100.0f;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw Error(a + " needs a value");
      return args[++i];
    };
    if (a == "--help" || a == "-h") o.help = true;
    else if (a == "--script") o.script = value();
    else if (a == "--screenshot") o.screenshot = value();
    else if (a == "--size") {
      const std::string v = value();
      const size_t x = v.find('x');
      if (x == std::string::npos) throw Error("--size must be WIDTHxHEIGHT, got '" + v + "'");
      o.windowWidth = cli::parseUint(a, v.substr(0, x), 640, 8192);
      o.windowHeight = cli::parseUint(a, v.substr(x + 1), 240, 8192);
    } else if (a == "--policy") o.settings.policy = parsePolicy(value());
    else if (a == "--budget-ms") o.settings.budgetMs = cli::parsePositive(a, value());
    else if (a == "--tracer") {
      const std::string t = value();
      if (t == "compute") o.settings.rayTracing.tracer = Tracer::Compute;
      else if (t == "native") o.settings.rayTracing.tracer = Tracer::Native;
      else throw Error("--tracer must be compute or native, got '" + t + "'");
    } else if (a == "--rate") o.settings.rayTracing.rate = parseItemRate(value());
    else if (a == "--fixed-time-scale") o.settings.learnTimeScale = false;
    else if (a == "--overlay") o.overlay = overlayName(parseOverlay(value()));
    else if (a == "--validation") o.settings.validation = true;
    else if (a == "--device") o.settings.device = value();
    else if (a == "--frames") o.frames = cli::parseUint(a, value(), 1, 10000000);
    else if (!a.empty() && a[0] == '-') throw Error("unknown option '" + a + "' (raybudget-editor --help)");
    else if (o.scene.empty()) o.scene = a;
    else throw Error("one scene only, got '" + o.scene + "' and '" + a + "'");
  }
  if (!o.help && o.scene.empty()) throw Error("no scene given (raybudget-editor SCENE.gltf, or --help)");
  o.settings.width = o.windowWidth - o.panelWidth;
  o.settings.height = o.windowHeight;
  validateSettings(o.settings);
  return o;
}

}  // namespace raybudget::editor

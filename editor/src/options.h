// raybudget-editor's command line.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "raybudget/settings.h"

namespace raybudget::editor {

struct EditorOptions {
  std::string scene;
  std::string script;      // --script FILE: replay a session, then quit
  std::string screenshot;  // --screenshot PATH: the window's contents after the script (or the first frames), then quit
  uint32_t windowWidth = 1280, windowHeight = 720;
  uint32_t panelWidth = 420;  // the panels' column; the viewport (and the render) is the rest
  uint32_t frames = 0;        // --frames N: quit after N frames (0: run until closed)
  std::string overlay = "none";
  RenderSettings settings;    // policy, budget, tracer, validation, device
  bool help = false;
};

extern const char* kEditorUsage;
// Throws raybudget::Error naming the bad option.
EditorOptions parseEditorOptions(const std::vector<std::string>& args);

}  // namespace raybudget::editor

// A scripted editor session (`raybudget-editor SCENE --script FILE`): one command a line,
// '#' starts a comment. Parsed whole before the window opens, so a typo fails at once with
// the file and line.
//   pick NAME | pick X Y          select an object by name, or at window pixel X Y
//   set K|Q|I VALUE               edit the picked object (validated as in the UI)
//   budget MS | policy NAME | tracer compute|native
//   overlay none|items|cost|benefit|ids|traced
//   camera orbit DEGREES | camera fly DISTANCE | camera reset
//   wait N                        render N frames
//   screenshot PATH | save PATH | dump PATH (the object list as CSV)
//   undo | redo | quit (at once, unsaved edits discarded)
//   close                         as the window's close button: quits, or with unsaved edits
//                                 opens the prompt
//   expect NAME selected|unselected    fails the session unless the object has (or has no)
//                                      item traced this frame
//   expect K|Q|I VALUE                 fails unless the picked object's value is VALUE
//   expect picked NAME|none            fails unless that object (or none) is picked
//   expect prompt                      fails unless the unsaved-changes prompt is open
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace raybudget::editor {

enum class CommandKind {
  PickName, PickPixel, Set, Budget, Policy, Tracer, Overlay, CameraOrbit, CameraFly, CameraReset, Wait, Screenshot,
  Save, Dump, Undo, Redo, Quit, Close, ExpectSelected, ExpectParam, ExpectPicked, ExpectPrompt
};

struct ScriptCommand {
  CommandKind kind = CommandKind::Quit;
  std::string text;    // a name, a path, a parameter letter, a policy, tracer or overlay
  double value = 0.0;  // the number (K/Q/I value, ms, degrees, distance, frames, X)
  double value2 = 0.0; // Y of pick X Y; 1 for `expect NAME selected`, 0 for unselected
  int line = 0;
};

// Throws raybudget::Error naming the file and line on an unknown command or a bad argument.
std::vector<ScriptCommand> parseScript(const std::string& text, const std::string& fileName);
std::vector<ScriptCommand> loadScript(const std::filesystem::path& path);

}  // namespace raybudget::editor

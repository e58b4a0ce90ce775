// raybudget-editor: the level editor (editor/README.md).
#include <cstdio>
#include <string>
#include <vector>

#include "editor_app.h"
#include "options.h"
#include "raybudget/error.h"

int main(int argc, char** argv) {
  using namespace raybudget::editor;
  try {
    const EditorOptions options = parseEditorOptions(std::vector<std::string>(argv + 1, argv + argc));
    if (options.help) {
      std::fputs(kEditorUsage, stdout);
      return 0;
    }
    EditorApp app(options);
    return app.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "raybudget-editor: %s\n", e.what());
    return 1;
  }
}

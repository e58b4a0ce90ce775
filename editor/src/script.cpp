#include "script.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "raybudget/error.h"

namespace raybudget::editor {
namespace {

struct LineParser {
  const std::string& file;
  int line;
  std::vector<std::string> words;

  [[noreturn]] void fail(const std::string& what) const { throw Error(file + ":" + std::to_string(line) + ": " + what); }

  void expectWords(size_t n, const char* usage) const {
    if (words.size() != n) fail(std::string("expected '") + usage + "'");
  }

  // NaN and infinities parse: `set` refuses them where the UI does, with the same message.
  double number(size_t i) const {
    try {
      size_t used = 0;
      const double v = std::stod(words[i], &used);
      if (used != words[i].size()) throw std::invalid_argument("");
      return v;
    } catch (const std::exception&) {
      fail("'" + words[i] + "' is not a number");
    }
  }

  ScriptCommand parse() const {
    ScriptCommand c;
    c.line = line;
    const std::string& w = words[0];
    auto textArg = [&](CommandKind kind, const char* usage) {
      expectWords(2, usage);
      c.kind = kind;
      c.text = words[1];
    };
    if (w == "pick") {
      if (words.size() == 3) {
        c.kind = CommandKind::PickPixel;
        c.value = number(1);
        c.value2 = number(2);
      } else {
        expectWords(2, "pick NAME' or 'pick X Y");
        c.kind = CommandKind::PickName;
        c.text = words[1];
      }
    } else if (w == "set") {
      expectWords(3, "set K|Q|I VALUE");
      if (words[1] != "K" && words[1] != "Q" && words[1] != "I") fail("set takes K, Q or I, got '" + words[1] + "'");
      c.kind = CommandKind::Set;
      c.text = words[1];
      c.value = number(2);  // range checks happen where the UI's do, with the same message
    } else if (w == "budget") {
      expectWords(2, "budget MS");
      c.kind = CommandKind::Budget;
      c.value = number(1);
    } else if (w == "policy") {
      textArg(CommandKind::Policy, "policy NAME");
    } else if (w == "tracer") {
      textArg(CommandKind::Tracer, "tracer compute|native");
    } else if (w == "overlay") {
      textArg(CommandKind::Overlay, "overlay none|items|cost|benefit|ids|traced");
    } else if (w == "camera") {
      if (words.size() == 2 && words[1] == "reset") {
        c.kind = CommandKind::CameraReset;
      } else {
        expectWords(3, "camera orbit DEGREES' or 'camera fly DISTANCE' or 'camera reset");
        if (words[1] == "orbit") c.kind = CommandKind::CameraOrbit;
        else if (words[1] == "fly") c.kind = CommandKind::CameraFly;
        else fail("camera takes orbit, fly or reset, got '" + words[1] + "'");
        c.value = number(2);
      }
    } else if (w == "wait") {
      expectWords(2, "wait FRAMES");
      c.kind = CommandKind::Wait;
      c.value = number(1);
      if (c.value < 0 || c.value > 100000 || c.value != std::floor(c.value)) fail("wait takes a whole number of frames (0..100000)");
    } else if (w == "screenshot") {
      textArg(CommandKind::Screenshot, "screenshot PATH");
    } else if (w == "save") {
      textArg(CommandKind::Save, "save PATH");
    } else if (w == "dump") {
      textArg(CommandKind::Dump, "dump PATH");
    } else if (w == "undo" || w == "redo" || w == "quit" || w == "close") {
      expectWords(1, w.c_str());
      c.kind = w == "undo" ? CommandKind::Undo : w == "redo" ? CommandKind::Redo : w == "quit" ? CommandKind::Quit : CommandKind::Close;
    } else if (w == "expect" && words.size() == 2 && words[1] == "prompt") {
      c.kind = CommandKind::ExpectPrompt;
    } else if (w == "expect") {
      expectWords(3, "expect NAME selected|unselected', 'expect K|Q|I VALUE', 'expect picked NAME' or 'expect prompt");
      if (words[1] == "picked") {
        c.kind = CommandKind::ExpectPicked;
        c.text = words[2];
      } else if (words[2] == "selected" || words[2] == "unselected") {
        c.kind = CommandKind::ExpectSelected;
        c.text = words[1];
        c.value2 = words[2] == "selected" ? 1.0 : 0.0;
      } else if (words[1] == "K" || words[1] == "Q" || words[1] == "I") {
        c.kind = CommandKind::ExpectParam;
        c.text = words[1];
        c.value = number(2);
      } else {
        fail("expect takes 'NAME selected|unselected', 'K|Q|I VALUE', 'picked NAME' or 'prompt'");
      }
    } else {
      fail("unknown command '" + w + "'");
    }
    return c;
  }
};

}  // namespace

std::vector<ScriptCommand> parseScript(const std::string& text, const std::string& fileName) {
  std::vector<ScriptCommand> commands;
  std::istringstream in(text);
  std::string raw;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    if (const size_t hash = raw.find('#'); hash != std::string::npos) raw.resize(hash);
    LineParser p{fileName, line, {}};
    std::istringstream words(raw);
    for (std::string w; words >> w;) p.words.push_back(w);
    if (!p.words.empty()) commands.push_back(p.parse());
  }
  return commands;
}

std::vector<ScriptCommand> loadScript(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot open the script");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parseScript(ss.str(), path.string());
}

}  // namespace raybudget::editor

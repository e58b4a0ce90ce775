// Writes extras.raybudget {K, Q, I} into a glTF's node JSON and leaves every other byte
// as it was: .gltf files are re-serialised JSON, .glb files keep their BIN chunk verbatim.
#include <cstring>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "raybudget/error.h"
#include "raybudget/scene.h"

namespace raybudget {
namespace {

std::string readFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw Error(p.string() + ": cannot open for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

uint32_t u32(const std::string& s, size_t at) {
  uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

void putU32(std::string& s, uint32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); }

}  // namespace

void saveRayBudgetParams(const std::filesystem::path& source, const std::filesystem::path& destination,
                         const std::vector<std::pair<int, RayBudgetParams>>& nodeParams) {
  const std::string file = source.string();
  const std::string bytes = readFile(source);
  const bool glb = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
  std::string jsonText, binChunk;
  if (glb) {
    if (bytes.size() < 20 || u32(bytes, 16) != 0x4E4F534Au) throw Error(file + ": GLB without a JSON chunk");
    const uint32_t jsonLength = u32(bytes, 12);
    if (20ull + jsonLength > bytes.size()) throw Error(file + ": GLB JSON chunk runs past the end of the file");
    jsonText = bytes.substr(20, jsonLength);
    binChunk = bytes.substr(20 + jsonLength);  // the remaining chunks, verbatim
  } else {
    jsonText = bytes;
  }
  nlohmann::json doc = nlohmann::json::parse(jsonText, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) throw Error(file + ": JSON could not be parsed");
  auto& nodes = doc["nodes"];
  for (const auto& [node, params] : nodeParams) {
    validateRayBudgetParams(params, file + ": node " + std::to_string(node));
    if (!nodes.is_array() || node < 0 || size_t(node) >= nodes.size()) throw Error(file + ": node " + std::to_string(node) + " does not exist");
    // K, Q and I are replaced; the object's other keys (reflectionProbe) stay.
    nlohmann::json& extras = nodes[size_t(node)]["extras"];
    if (!extras.is_object()) extras = nlohmann::json::object();
    nlohmann::json& rb = extras["raybudget"];
    if (!rb.is_object()) rb = nlohmann::json::object();
    for (const auto& [key, value] : {std::pair{"K", params.importanceK}, {"Q", params.raysQ}, {"I", params.hysteresisI}}) {
      if (value) rb[key] = *value;
      else rb.erase(key);
    }
  }
  std::string out = doc.dump(glb ? -1 : 2);
  if (glb) {
    while (out.size() % 4 != 0) out.push_back(' ');
    std::string container = "glTF";
    putU32(container, 2);
    putU32(container, uint32_t(12 + 8 + out.size() + binChunk.size()));
    putU32(container, uint32_t(out.size()));
    putU32(container, 0x4E4F534Au);
    container += out;
    container += binChunk;
    out.swap(container);
  }
  std::ofstream o(destination, std::ios::binary);
  if (!o) throw Error(destination.string() + ": cannot open for writing");
  o.write(out.data(), std::streamsize(out.size()));
  if (!o) throw Error(destination.string() + ": write failed");
}

}  // namespace raybudget

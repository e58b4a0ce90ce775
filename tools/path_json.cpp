#include "path_json.h"

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "raybudget/error.h"

namespace raybudget::cli {

void writePathJson(const std::filesystem::path& file, const std::string& name, const std::vector<Camera>& path) {
  std::ofstream out(file);
  auto vec = [](const glm::vec3& v) { return "[" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + "]"; };
  out << "{\n  \"path\": \"" << name << "\",\n  \"frames\": [\n";
  for (size_t i = 0; i < path.size(); ++i)
    out << "    {\"position\": " << vec(path[i].position) << ", \"target\": " << vec(path[i].target) << ", \"up\": " << vec(path[i].up)
        << ", \"yfov\": " << path[i].yfov << "}" << (i + 1 < path.size() ? "," : "") << "\n";
  out << "  ]\n}\n";
  if (!out) throw Error("cannot write " + file.string());
}

namespace {

float number(const nlohmann::json& v, const std::string& where) {
  if (!v.is_number() || !std::isfinite(v.get<double>())) throw Error(where + " is not a finite number");
  return v.get<float>();
}

glm::vec3 vec3(const nlohmann::json& frame, const char* key, const std::string& where) {
  const auto it = frame.find(key);
  const std::string at = where + "." + key;
  if (it == frame.end() || !it->is_array() || it->size() != 3) throw Error(at + " is not an array of 3 numbers");
  return {number((*it)[0], at + "[0]"), number((*it)[1], at + "[1]"), number((*it)[2], at + "[2]")};
}

}  // namespace

std::vector<Camera> readPathJson(const std::filesystem::path& file, const Camera& base) {
  std::ifstream in(file);
  if (!in) throw Error("cannot read the camera path " + file.string());
  nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
  if (doc.is_discarded()) throw Error(file.string() + ": not JSON");
  const auto frames = doc.is_object() ? doc.find("frames") : doc.end();
  if (frames == doc.end() || !frames->is_array() || frames->empty()) throw Error(file.string() + ": no \"frames\" array of cameras");
  std::vector<Camera> path;
  for (size_t i = 0; i < frames->size(); ++i) {
    const nlohmann::json& f = (*frames)[i];
    const std::string where = file.string() + ": frames[" + std::to_string(i) + "]";
    if (!f.is_object()) throw Error(where + " is not an object");
    Camera c = base;
    c.position = vec3(f, "position", where);
    c.target = vec3(f, "target", where);
    c.up = vec3(f, "up", where);
    if (!f.contains("yfov")) throw Error(where + " has no yfov");
    c.yfov = number(f["yfov"], where + ".yfov");
    validateCamera(c, where);
    path.push_back(c);
  }
  return path;
}

}  // namespace raybudget::cli

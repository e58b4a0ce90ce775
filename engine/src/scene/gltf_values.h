// Reading glTF JSON values the loader shares between its parts: a number with a fallback,
// a named extension, a float that must be finite.
#pragma once
#include <cmath>
#include <string>

#include <tiny_gltf.h>

#include "raybudget/error.h"

namespace raybudget::gltf {

inline double number(const tinygltf::Value& v, const char* key, double fallback) {
  if (!v.IsObject() || !v.Has(key)) return fallback;
  const tinygltf::Value& e = v.Get(key);
  return e.IsNumber() ? e.GetNumberAsDouble() : fallback;
}

inline const tinygltf::Value* extension(const tinygltf::ExtensionMap& m, const char* name) {
  const auto it = m.find(name);
  return it == m.end() ? nullptr : &it->second;
}

// `v` as a float; beyond float range counts as not finite (a light colour of 1e40 is infinite
// once it reaches the GPU).
inline float finiteOr(double v, const std::string& what) {
  if (!std::isfinite(v) || !std::isfinite(float(v))) throw Error(what + " is not finite (or beyond float range)");
  return float(v);
}

}  // namespace raybudget::gltf

// glTF images, samplers, textures (with KHR_texture_transform) and materials (metallic-
// roughness with KHR_materials_{transmission,ior,volume,emissive_strength,unlit,clearcoat,
// sheen,specular}) into a Scene, every reference range-checked.
#pragma once
#include <string>

#include "raybudget/scene.h"

namespace tinygltf {
class Model;
}

namespace raybudget::gltf {

// Decodes the images (an undecodable one is kept empty, with a warning: textures using it are
// dropped) and reads the samplers and textures.
void loadImagesAndTextures(const tinygltf::Model& model, const std::string& file, Scene& scene);

// The materials; a transformed texture reference appends a texture of its own.
void loadMaterials(const tinygltf::Model& model, const std::string& file, Scene& scene);

}  // namespace raybudget::gltf

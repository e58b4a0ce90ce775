// minimal_host: an application with a Vulkan device of its own that lends it to raybudget.
//   minimal_host SCENE.gltf [--validation]
// It checks that its device can host raybudget (core::missingRequirements), creates the
// device with the features raybudget asks for (core::deviceSetup), renders the scene with
// ray-traced shadows, reflections and refractions on that device, and writes
// minimal_host.png into the working directory. With --validation its instance runs the
// Khronos validation layer and the program fails on any message.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "raybudget/raybudget.h"

namespace {

std::vector<std::string> messages;

VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                         const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  messages.push_back(data->pMessage ? data->pMessage : "");
  return VK_FALSE;
}

void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS) throw raybudget::Error(std::string(call) + " failed with VkResult " + std::to_string(int(result)));
}

// The host's own instance, messenger and device: what an engine has before raybudget.
struct HostVulkan {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  raybudget::core::DeviceSetup setup;

  explicit HostVulkan(bool validation) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "minimal_host";
    app.apiVersion = VK_API_VERSION_1_3;
    VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    dbg.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    dbg.pfnUserCallback = onMessage;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ici.pApplicationInfo = &app;
    if (validation) {
      ici.pNext = &dbg;
      ici.enabledLayerCount = 1;
      ici.ppEnabledLayerNames = &layer;
      ici.enabledExtensionCount = 1;
      ici.ppEnabledExtensionNames = &extension;
    }
    check(vkCreateInstance(&ici, nullptr, &instance), "vkCreateInstance");
    if (validation) {
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
      check(create(instance, &dbg, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
    }

    // The first device raybudget can run on; say why the others cannot.
    uint32_t count = 0;
    check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(count);
    check(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "vkEnumeratePhysicalDevices");
    for (VkPhysicalDevice d : devices) {
      const std::vector<std::string> missing = raybudget::core::missingRequirements(d);
      for (const std::string& m : missing) std::fprintf(stderr, "skipping a device: %s\n", m.c_str());
      if (missing.empty() && !physicalDevice) physicalDevice = d;
    }
    if (!physicalDevice) throw raybudget::Error("no Vulkan device can host raybudget");

    // raybudget's features and extensions; an engine would chain its own after them.
    setup = raybudget::core::deviceSetup(physicalDevice);
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    qci.queueFamilyIndex = setup.queueFamily;
    qci.queueCount = 1;
    qci.pQueuePriorities = &priority;
    VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    dci.pNext = setup.chain();
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.enabledExtensionCount = uint32_t(setup.extensions.size());
    dci.ppEnabledExtensionNames = setup.extensions.data();
    check(vkCreateDevice(physicalDevice, &dci, nullptr, &device), "vkCreateDevice");
    vkGetDeviceQueue(device, setup.queueFamily, 0, &queue);
  }

  ~HostVulkan() {
    if (device) vkDestroyDevice(device, nullptr);
    if (messenger) {
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
      destroy(instance, messenger, nullptr);
    }
    if (instance) vkDestroyInstance(instance, nullptr);
  }

  raybudget::core::HostDevice lend() const {
    raybudget::core::HostDevice h;
    h.instance = instance;
    h.physicalDevice = physicalDevice;
    h.device = device;
    h.queueFamily = setup.queueFamily;
    h.queue = queue;
    h.getDeviceProcAddr = vkGetDeviceProcAddr;
    h.rayQueryEnabled = setup.rayQueryEnabled;
    h.shaderFloat64Enabled = setup.shaderFloat64Enabled;
    return h;
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: minimal_host SCENE.gltf [--validation]\n");
    return 2;
  }
  const bool validation = argc > 2 && std::strcmp(argv[2], "--validation") == 0;
  try {
    HostVulkan host(validation);
    const raybudget::Scene scene = raybudget::loadScene(argv[1]);
    raybudget::RenderSettings settings;
    settings.width = 320;
    settings.height = 180;
    settings.policy = raybudget::Policy::All;  // every object's shadows, reflections, refractions traced
    {
      // The renderer borrows the device: it must be gone before the device is destroyed.
      raybudget::Renderer renderer(scene, settings, host.lend());
      renderer.render(raybudget::defaultCamera(scene, renderer.aspect()));
      const raybudget::FrameImages images = renderer.readback();
      raybudget::writePng("minimal_host.png", images.width, images.height, images.ldrRgba8);
    }
    vkDeviceWaitIdle(host.device);
    for (const std::string& m : messages) std::fprintf(stderr, "validation: %s\n", m.c_str());
    if (!messages.empty()) return 1;
    std::printf("wrote minimal_host.png (%s)\n", validation ? "validation clean" : "validation off");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "minimal_host: %s\n", e.what());
    return 1;
  }
}

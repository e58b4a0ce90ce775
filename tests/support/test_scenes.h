// Where the tests find scenes: ../shared/scenes beside the checkout (skipped when absent)
// and the project's own data/.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "raybudget/scene.h"

namespace raybudget::test {

std::filesystem::path sharedScenesDir();
// Every scene path listed in ../shared/scenes/MANIFEST.json for `set` ("ci" or "bench");
// empty when the folder is absent.
std::vector<std::filesystem::path> manifestScenes(const std::string& set);
std::filesystem::path defaultScenePath();
// The ID of the scene's object called `name`; kNoObjectNamed when there is none.
inline constexpr uint32_t kNoObjectNamed = ~0u;
uint32_t objectNamed(const Scene& scene, const std::string& name);
// A fresh empty temporary folder for one test process.
std::filesystem::path freshTempDir(const std::string& name);

}  // namespace raybudget::test

// Skips the current test with a clear message when ../shared/scenes is missing.
#define RB_REQUIRE_SHARED_SCENES()                                                                               \
  do {                                                                                                           \
    if (!std::filesystem::exists(::raybudget::test::sharedScenesDir() / "MANIFEST.json"))                       \
      GTEST_SKIP() << "../shared/scenes is absent (a fresh clone without the shared folder): scene test skipped"; \
  } while (0)

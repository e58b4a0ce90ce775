// The editor's model without a window: the script parser, the undo history, the camera
// moves, the object list and its overlays, and the session editing K/Q/I through the core
// on a host device with validation on (saving into the glTF and reloading).
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "camera_control.h"
#include "edit_history.h"
#include "object_rows.h"
#include "raybudget/error.h"
#include "script.h"
#include "quad_pairs.h"
#include "session.h"
#include "stage_plot.h"
#include "support/test_host.h"
#include "support/test_scenes.h"

namespace raybudget::editor {
namespace {

std::string errorOf(const std::string& text) {
  try {
    parseScript(text, "s.txt");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(EditorScript, ParsesEveryCommand) {
  const auto c = parseScript(
      "# a comment\n\npick mirror\npick 10 20\nset K 2.5  # trailing\nbudget 40\npolicy paper\ntracer native\noverlay items\n"
      "camera orbit 30\ncamera fly -2\ncamera reset\nwait 5\nscreenshot a.png\nsave b.gltf\ndump c.csv\nundo\nredo\n"
      "expect mirror selected\nexpect floor unselected\nexpect Q 4\nset I nan\nquit\nclose\nexpect picked floor\nexpect prompt\n",
      "s.txt");
  ASSERT_EQ(c.size(), 24u);
  EXPECT_EQ(c[0].kind, CommandKind::PickName);
  EXPECT_EQ(c[0].text, "mirror");
  EXPECT_EQ(c[0].line, 3);
  EXPECT_EQ(c[1].kind, CommandKind::PickPixel);
  EXPECT_EQ(c[1].value, 10.0);
  EXPECT_EQ(c[1].value2, 20.0);
  EXPECT_EQ(c[2].kind, CommandKind::Set);
  EXPECT_EQ(c[2].text, "K");
  EXPECT_EQ(c[2].value, 2.5);
  EXPECT_EQ(c[8].kind, CommandKind::CameraFly);
  EXPECT_EQ(c[8].value, -2.0);
  EXPECT_EQ(c[9].kind, CommandKind::CameraReset);
  EXPECT_EQ(c[10].value, 5.0);
  EXPECT_EQ(c[16].kind, CommandKind::ExpectSelected);
  EXPECT_EQ(c[16].value2, 1.0);
  EXPECT_EQ(c[17].value2, 0.0);
  EXPECT_EQ(c[18].kind, CommandKind::ExpectParam);
  EXPECT_TRUE(std::isnan(c[19].value));  // refused later, where the UI refuses it
  EXPECT_EQ(c[20].kind, CommandKind::Quit);
  EXPECT_EQ(c[21].kind, CommandKind::Close);
  EXPECT_EQ(c[22].kind, CommandKind::ExpectPicked);
  EXPECT_EQ(c[22].text, "floor");
  EXPECT_EQ(c[23].kind, CommandKind::ExpectPrompt);
}

TEST(EditorScript, ErrorsNameTheFileAndLine) {
  EXPECT_EQ(errorOf("pick a\nteleport 3\n"), "s.txt:2: unknown command 'teleport'");
  EXPECT_NE(errorOf("set X 1").find("s.txt:1: set takes K, Q or I"), std::string::npos);
  EXPECT_NE(errorOf("\nset K lots").find("s.txt:2: 'lots' is not a number"), std::string::npos);
  EXPECT_NE(errorOf("wait 2.5").find("whole number"), std::string::npos);
  EXPECT_NE(errorOf("budget").find("expected 'budget MS'"), std::string::npos);
  EXPECT_NE(errorOf("camera spin 3").find("camera takes orbit, fly or reset"), std::string::npos);
  EXPECT_NE(errorOf("expect mirror maybe").find("expect takes"), std::string::npos);
  EXPECT_THROW(loadScript("/no/such/script.txt"), Error);
}

ParamEdit edit(uint32_t id, float before, float after) {
  ParamEdit e;
  e.objectId = id;
  e.before.importanceK = before;
  e.after.importanceK = after;
  return e;
}

TEST(EditorHistory, UndoRedoOfParametersAndSettings) {
  EditHistory h;
  EXPECT_FALSE(h.canUndo());
  EXPECT_FALSE(h.undo());
  h.record(edit(1, 1.0f, 2.0f));
  h.record(SettingsEdit{{Policy::Density, 10.0f, Tracer::Compute}, {Policy::Benefit, 10.0f, Tracer::Compute}});
  auto u = h.undo();
  ASSERT_TRUE(u);
  ASSERT_TRUE(std::holds_alternative<SettingsEdit>(*u));
  EXPECT_EQ(std::get<SettingsEdit>(*u).before.policy, Policy::Density);
  u = h.undo();
  ASSERT_TRUE(u);
  EXPECT_EQ(std::get<ParamEdit>(*u).objectId, 1u);
  EXPECT_EQ(*std::get<ParamEdit>(*u).before.importanceK, 1.0f);
  EXPECT_FALSE(h.undo());
  EXPECT_TRUE(h.canRedo());
  auto r = h.redo();
  ASSERT_TRUE(r);
  EXPECT_EQ(*std::get<ParamEdit>(*r).after.importanceK, 2.0f);
  // A new edit drops what could be redone.
  h.record(edit(3, 1.0f, 4.0f));
  EXPECT_FALSE(h.canRedo());
  EXPECT_EQ(std::get<ParamEdit>(*h.undo()).objectId, 3u);
  EXPECT_EQ(std::get<ParamEdit>(*h.undo()).objectId, 1u);
  EXPECT_FALSE(h.canUndo());
}

TEST(EditorCamera, OrbitKeepsTheTargetAndDistance) {
  Camera c;
  c.position = {3.0f, 2.0f, 5.0f};
  c.target = {1.0f, 0.5f, -1.0f};
  const float distance = glm::length(c.position - c.target);
  const Camera o = orbit(c, 0.7f, 0.2f);
  EXPECT_EQ(o.target, c.target);
  EXPECT_NEAR(glm::length(o.position - o.target), distance, 1e-4f);
  EXPECT_GT(glm::length(o.position - c.position), 0.5f);
  Camera around = c;
  for (int i = 0; i < 8; ++i) around = orbit(around, glm::radians(45.0f), 0.0f);
  EXPECT_NEAR(glm::length(around.position - c.position), 0.0f, 1e-3f);
  // Pitch stops short of the pole: the view never looks straight along up.
  const Camera top = orbit(c, 0.0f, 10.0f);
  const glm::vec3 dir = glm::normalize(top.position - top.target);
  EXPECT_LT(dir.y, std::cos(glm::radians(0.9f)));
  EXPECT_GT(dir.y, std::cos(glm::radians(1.5f)));
}

TEST(EditorCamera, LookFlyAndDolly) {
  Camera c;
  c.position = {0.0f, 1.0f, 5.0f};
  c.target = {0.0f, 1.0f, 0.0f};
  const Camera l = look(c, glm::radians(90.0f), 0.0f);
  EXPECT_EQ(l.position, c.position);
  EXPECT_NEAR(glm::length(l.target - l.position), 5.0f, 1e-4f);
  EXPECT_NEAR(l.target.z, 5.0f, 1e-3f);  // a quarter turn: now looking along x
  const Camera f = fly(c, 2.0f, 1.0f, 0.0f);
  EXPECT_NEAR(f.position.z, 3.0f, 1e-5f);  // forward is -z here
  EXPECT_NEAR(glm::length((f.target - f.position) - (c.target - c.position)), 0.0f, 1e-5f);
  const Camera d = dolly(c, 0.5f);
  EXPECT_NEAR(glm::length(d.position - d.target), 2.5f, 1e-5f);
  EXPECT_NEAR(glm::length(dolly(c, 5.0f).position - c.target), 0.05f, 1e-5f);  // never through the target
}

std::vector<ObjectRow> sampleRows() {
  Scene scene;
  for (const char* name : {"Mirror", "floor", "glass_mirror"}) {
    Object o;
    o.id = uint32_t(scene.objects.size());
    o.name = name;
    scene.objects.push_back(o);
  }
  std::vector<RayBudgetParams> params(3);
  for (uint32_t i = 0; i < 3; ++i) params[i] = {float(i + 1), 4.0f, 0.5f};
  std::vector<ObjectMetrics> metrics(3), previous(3);
  metrics[0].selectedItems = 2u;  // reflections
  metrics[0].pixels = 100;
  metrics[0].reflectionPixels = 80;
  metrics[0].itemCostPerPixel = {0.0f, 10.0f, 0.0f};
  metrics[0].itemTicks = {0, 300, 0};
  metrics[2].selectedItems = 5u;  // shadows and refractions
  metrics[2].itemTicks = {100, 0, 0};
  metrics[1].R = 9.0f;
  previous[1].selected = true;
  FrameTiming timing;
  timing.measuredTraceMs = 8.0;
  CostModel model;
  model.msPerWorkUnit = 0.001;
  return buildRows(scene, params, metrics, previous, model, timing, 64, 64);
}

TEST(EditorPlot, RunPeaksKeepEveryFrameOverTheBudget) {
  std::deque<float> history;
  for (int f = 0; f < 300; ++f) history.push_back(1.0f + 0.001f * float(f));
  history[7] = 9.0f;    // a frame over T early on
  history[299] = 8.0f;  // and the last one
  const std::vector<float> peaks = runPeaks(history, 150);
  ASSERT_EQ(peaks.size(), 150u);
  EXPECT_EQ(peaks[3], 9.0f) << "frames 6 and 7";
  EXPECT_EQ(peaks[149], 8.0f);
  for (size_t p = 0; p < peaks.size(); ++p)
    if (p != 3 && p != 149) {
      EXPECT_FLOAT_EQ(peaks[p], 1.0f + 0.001f * float(2 * p + 1)) << "the later frame of pair " << p;
    }
  // Runs as even as the counts allow: 7 frames in 3 points take 2, 2 and 3.
  EXPECT_EQ(runPeaks(std::deque<float>{5, 1, 2, 6, 3, 1, 4}, 3), (std::vector<float>{5, 6, 4}));
  // Short histories are drawn as they are.
  EXPECT_EQ(runPeaks(std::deque<float>{3, 1, 2}, 150), (std::vector<float>{3, 1, 2}));
  EXPECT_TRUE(runPeaks({}, 150).empty());
}

TEST(EditorUi, QuadsArePairedInOrder) {
  // A lone triangle (an arrow), a quad (a glyph), two lone triangles, a quad; then a quad
  // and a triangle.
  const std::vector<uint16_t> in{0, 1, 2, 3, 4, 5, 3, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 13, 15, 16};
  const std::vector<uint16_t> in2{20, 21, 22, 20, 22, 23, 30, 31, 32};
  std::vector<uint16_t> out{99, 99, 99};  // an earlier command's share: commands align on their own start
  appendPairedQuads(in.data(), uint32_t(in.size()), out);
  const size_t second = out.size();
  appendPairedQuads(in2.data(), uint32_t(in2.size()), out);
  ASSERT_EQ((second - 3) % 6, 0u);
  ASSERT_EQ((out.size() - second) % 6, 0u);
  // Dropping the degenerate triangles gives back each command's triangles in order.
  std::vector<uint16_t> kept;
  for (size_t t = 3; t < out.size(); t += 3)
    if (!(out[t] == out[t + 1] && out[t + 1] == out[t + 2])) kept.insert(kept.end(), out.begin() + long(t), out.begin() + long(t) + 3);
  std::vector<uint16_t> expected = in;
  expected.insert(expected.end(), in2.begin(), in2.end());
  EXPECT_EQ(kept, expected);
  // Every quad starts at a multiple of 6 from its command's start.
  for (const auto& [begin, end] : {std::pair{size_t(3), second}, std::pair{second, out.size()}})
    for (size_t t = begin; t + 6 <= end; t += 3)
      if (out[t] == out[t + 3] && out[t + 2] == out[t + 4] && out[t] != out[t + 1]) {
        EXPECT_EQ((t - begin) % 6, 0u) << "quad at index " << t;
      }
  // Exactly the padding needed: one before the first quad, none before the second (the two
  // triangles realign it); one at the end of the second command.
  EXPECT_EQ(second - 3, in.size() + 3);
  EXPECT_EQ(out.size() - second, in2.size() + 3);
}

TEST(EditorRows, QuantitiesFilterSortAndCsv) {
  const std::vector<ObjectRow> rows = sampleRows();
  EXPECT_EQ(rows[1].K, 2.0f);
  EXPECT_TRUE(rows[1].selectedLastFrame);
  EXPECT_FALSE(rows[0].selectedLastFrame);
  EXPECT_NEAR(rows[0].predictedMs[1], 10.0 * 80 * 0.001, 1e-9);
  // The frame's measured trace time shared by the items' clock ticks.
  EXPECT_NEAR(rows[0].measuredMs[1], 6.0, 1e-9);
  EXPECT_NEAR(rows[2].measuredMs[0], 2.0, 1e-9);

  const auto mirrors = visibleRows(rows, "MIRROR", Column::K, false);
  ASSERT_EQ(mirrors.size(), 2u);
  EXPECT_EQ(mirrors[0]->name, "glass_mirror");  // K 3 before K 1
  const auto byR = visibleRows(rows, "", Column::R, false);
  EXPECT_EQ(byR[0]->name, "floor");
  const auto byName = visibleRows(rows, "", Column::Name, true);
  EXPECT_EQ(byName[0]->name, "Mirror");

  const std::string csv = rowsCsv(rows);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  EXPECT_NE(csv.find("0,Mirror,1,4,0.5,100,"), std::string::npos);
}

TEST(EditorRows, OverlayTints) {
  const std::vector<ObjectRow> rows = sampleRows();
  const auto items = overlayTints(Overlay::Items, rows);
  EXPECT_EQ(items[1].a, 0.0f);  // nothing traced: the frame shows through
  EXPECT_GT(items[0].a, 0.0f);
  EXPECT_EQ(glm::vec3(items[0]), effectColour(2u));
  EXPECT_GT(items[0].r, items[0].b);  // reflections are red
  EXPECT_EQ(glm::vec3(items[2]), effectColour(5u));
  const auto cost = overlayTints(Overlay::Cost, rows);
  EXPECT_GT(cost[0].a, 0.0f);
  EXPECT_EQ(cost[1].a, 0.0f);  // no predicted cost, and C = 0
  for (const glm::vec4& t : overlayTints(Overlay::None, rows)) EXPECT_EQ(t.a, 0.0f);
  const auto ids = overlayTints(Overlay::Ids, rows);
  EXPECT_NE(glm::vec3(ids[0]), glm::vec3(ids[1]));
  EXPECT_THROW(parseOverlay("heat"), Error);
  EXPECT_EQ(parseOverlay("benefit"), Overlay::Benefit);
  // A partial item (benefit's, on a share of its tiles) alone: its tint weighs by that share;
  // beside a whole item the object is tinted in full.
  std::vector<ObjectRow> partial = rows;
  partial[0].metrics.itemTileShare[1] = 0.25f;
  partial[2].metrics.itemTileShare[2] = 0.5f;
  const auto shared = overlayTints(Overlay::Items, partial);
  EXPECT_FLOAT_EQ(shared[0].a, 0.25f * items[0].a);
  EXPECT_EQ(shared[2].a, items[2].a);
}

// The list's items column: upper case for an item traced whole, lower case for the partial
// item, '-' for one left out.
TEST(EditorRows, ItemsColumnMarksThePartialItem) {
  ObjectMetrics m;
  EXPECT_EQ(itemsText(m), "---");
  m.selectedItems = 7u;
  EXPECT_EQ(itemsText(m), "SRT");
  m.itemTileShare[1] = 0.4f;
  EXPECT_EQ(itemsText(m), "SrT");
  m.selectedItems = 2u;
  EXPECT_EQ(itemsText(m), "-r-");
}

TEST(EditorSession, EditsAreValidatedUndoneAndSavedIntoTheGltf) {
  test::TestHost host;
  Scene scene = loadScene(test::defaultScenePath());
  RenderSettings settings;
  settings.width = 96;
  settings.height = 64;
  settings.policy = Policy::Density;
  Session session(host.device(), scene, settings);
  const int mirror = session.findObject("mirror_panel");
  ASSERT_GE(mirror, 0);
  EXPECT_EQ(session.findObject("no such object"), -1);
  const uint32_t id = uint32_t(mirror);
  const RayBudgetParams before = session.core().objectParams(id);
  std::string message;

  for (double bad : {-1.0, double(NAN), double(INFINITY), 1e30}) {
    EXPECT_FALSE(session.setParam(id, Param::K, bad, message)) << bad;
    EXPECT_NE(message.find("nothing changed"), std::string::npos) << message;
  }
  EXPECT_FALSE(session.modified());
  EXPECT_EQ(session.core().objectParams(id).importanceK, before.importanceK);
  EXPECT_FALSE(session.setParam(9999, Param::K, 1.0, message));

  ASSERT_TRUE(session.setParam(id, Param::K, 7.5, message)) << message;
  ASSERT_TRUE(session.setParam(id, Param::I, 0.25, message)) << message;
  EXPECT_TRUE(session.modified());
  EXPECT_EQ(*session.core().objectParams(id).importanceK, 7.5f);
  EXPECT_EQ(*session.core().objectParams(id).hysteresisI, 0.25f);
  ASSERT_TRUE(session.undo(message));
  EXPECT_EQ(session.core().objectParams(id).hysteresisI, before.hysteresisI);
  ASSERT_TRUE(session.redo(message));
  EXPECT_FALSE(session.redo(message));
  // Modified means the K/Q/I differ from the file's: setting a value back clears it.
  ASSERT_TRUE(session.setParam(id, Param::K, *before.importanceK, message));
  ASSERT_TRUE(session.setParam(id, Param::I, *before.hysteresisI, message));
  const bool fileSetsKAndI = scene.objects[id].params.importanceK && scene.objects[id].params.hysteresisI;
  EXPECT_EQ(session.modified(), !fileSetsKAndI);  // values the file left out are now written
  ASSERT_TRUE(session.undo(message));
  ASSERT_TRUE(session.undo(message));
  EXPECT_TRUE(session.modified());

  const std::filesystem::path out = std::filesystem::temp_directory_path() / "raybudget_editor_session_test";
  std::filesystem::create_directories(out);
  std::filesystem::copy_file(test::defaultScenePath().parent_path() / "court.bin", out / "court.bin",
                             std::filesystem::copy_options::overwrite_existing);
  session.save(out / "court.gltf");
  EXPECT_FALSE(session.modified());
  const Scene reloaded = loadScene(out / "court.gltf");
  const Object& o = reloaded.objects[id];
  EXPECT_EQ(o.name, "mirror_panel");
  EXPECT_EQ(o.params.importanceK, std::optional<float>(7.5f));
  EXPECT_EQ(o.params.hysteresisI, std::optional<float>(0.25f));
  for (size_t i = 0; i < reloaded.objects.size(); ++i) {
    if (i == id) continue;
    EXPECT_EQ(reloaded.objects[i].params.importanceK, scene.objects[i].params.importanceK) << reloaded.objects[i].name;
  }

  // Budget and policy changes are undone like edits, and do not touch the document.
  std::string budgetMessage;
  EXPECT_FALSE(session.setBudget(-3.0, budgetMessage));
  EXPECT_FALSE(session.setBudget(NAN, budgetMessage));
  EXPECT_TRUE(session.setBudget(12.0, budgetMessage)) << budgetMessage;
  EXPECT_TRUE(session.setPolicy(Policy::Benefit, budgetMessage)) << budgetMessage;
  EXPECT_EQ(session.settings().budgetMs, 12.0f);
  EXPECT_EQ(session.settings().policy, Policy::Benefit);
  EXPECT_FALSE(session.modified());
  ASSERT_TRUE(session.undo(budgetMessage));
  EXPECT_EQ(session.settings().policy, Policy::Density);
  ASSERT_TRUE(session.undo(budgetMessage));
  EXPECT_EQ(session.settings().budgetMs, settings.budgetMs);
  ASSERT_TRUE(session.redo(budgetMessage));
  EXPECT_EQ(session.settings().budgetMs, 12.0f);
  EXPECT_FALSE(session.modified());
  EXPECT_TRUE(host.validationMessages().empty());
}

}  // namespace
}  // namespace raybudget::editor

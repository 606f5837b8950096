// A scene is read and its formula compiled once per load: the sweep keys its
// reference cache on the text the load kept, and make_problem reuses the
// model the load checked the start with (tests count both).
#include <gtest/gtest.h>

#include "bench/lib/sweep.hpp"

namespace rb {
namespace {

TEST(SceneLoad, PreparingASceneReadsItsFileAndCompilesItsFormulaOnce) {
  SweepSpec spec = preset("quick");
  spec.scenes = {"valley-sideways"};
  const SceneLoadCounts before = scene_load_counts();
  const std::vector<SweepScene> scenes = prepare_scenes(spec, false);
  const SceneLoadCounts after = scene_load_counts();
  EXPECT_EQ(after.files_read - before.files_read, 1);
  EXPECT_EQ(after.models_built - before.models_built, 1);
  ASSERT_EQ(scenes.size(), 1u);
  // the cache key is the file's text as loaded, with the run's t_end
  EXPECT_EQ(scenes[0].content.rfind(scenes[0].scene.text, 0), 0u);
  EXPECT_NE(scenes[0].scene.text.find("\"valley-sideways\""), std::string::npos);
}

TEST(SceneLoad, MakeProblemReusesTheLoadedModelUntilTheSceneChanges) {
  Scene scene = load_scene("valley-sideways");
  const long built = scene_load_counts().models_built;
  const Problem first = make_problem(scene);
  const Problem second = make_problem(scene);
  EXPECT_EQ(scene_load_counts().models_built, built);
  EXPECT_EQ(first.model().landscape().text(), scene.landscape);
  EXPECT_FALSE(second.model().anisotropic());
  // a scene changed after its load gets a model of its own, as it now is
  scene.ball.inertia = Vec3(1e-3, 2e-3, 3e-3);
  const Problem changed = make_problem(scene);
  EXPECT_EQ(scene_load_counts().models_built, built + 1);
  EXPECT_TRUE(changed.model().anisotropic());
}

TEST(SceneLoad, MakeProblemReusesTheClosedFormTheLoadChecked) {
  Scene scene = load_scene("plane");
  ASSERT_NE(scene.exact, "none");
  const long built = scene_load_counts().exacts_built;
  const Problem first = make_problem(scene);
  ASSERT_NE(first.exact(), nullptr);
  EXPECT_EQ(scene_load_counts().exacts_built, built);
  // another start is another closed form, built and checked anew
  scene.start.contact.x() += 0.25;
  const Problem moved = make_problem(scene);
  EXPECT_EQ(scene_load_counts().exacts_built, built + 1);
  EXPECT_NE(moved.exact()->at(0.0).alpha, first.exact()->at(0.0).alpha);
}

TEST(SceneLoad, ReadingAShippedSceneForItsDescriptionCompilesNothing) {
  const SceneLoadCounts before = scene_load_counts();
  const Scene read = read_shipped_scene("chaplygin-valley");
  const SceneLoadCounts after = scene_load_counts();
  EXPECT_EQ(after.files_read - before.files_read, 1);
  EXPECT_EQ(after.models_built, before.models_built);
  EXPECT_EQ(after.exacts_built, before.exacts_built);
  EXPECT_EQ(read.description, load_scene("chaplygin-valley").description);
  EXPECT_FALSE(read.description.empty());
}

}  // namespace
}  // namespace rb

// The viewers' session (platform/Viewer, shared by obscura-view and the web page) gives each scene it loads its
// default AO radius (scene/SceneScale.h), unless a state text (the URL, --state) gave one.
#include <gtest/gtest.h>

#include "TestSupport.h"
#include "base/Error.h"
#include "platform/Viewer.h"

using namespace obscura;

TEST(ViewerRadius, EachSceneLoadedGetsItsDefaultRadiusUnlessTheStateGaveOne) {
  const std::string engine = test::assimpModels() + "/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  const std::string bad = test::assimpModels() + "/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb";
  Viewer viewer(test::context().caps());
  EXPECT_EQ(viewer.state().settings.get("ao.radius"), "1") << "the built-in scene's";
  EXPECT_EQ(viewer.sceneDefaultRadius(), 1.0f);

  viewer.loadGltfFile(engine);
  EXPECT_EQ(viewer.state().settings.get("ao.radius"), "42") << "5 % of the engine's 836 cm bounding-sphere diameter";
  EXPECT_EQ(viewer.sceneDefaultRadius(), 42.0f);
  EXPECT_EQ(viewer.state().toQuery().find("radius"), std::string::npos) << "the scene's default is not written";
  EXPECT_THROW(viewer.loadGltfFile(bad), InputError);
  EXPECT_EQ(viewer.state().settings.get("ao.radius"), "42") << "a refused file changes nothing";

  // A key changes it for this scene; the next scene gets its own again.
  viewer.handleKey("]");
  EXPECT_EQ(viewer.state().settings.get("ao.radius"), "52.5");
  viewer.loadBuiltinScene();
  EXPECT_EQ(viewer.state().settings.get("ao.radius"), "1");

  // Given by the state text: kept when a scene is loaded.
  viewer.state().applyQuery("view=ao&radius=3");
  viewer.loadGltfFile(engine);
  EXPECT_EQ(viewer.state().settings.get("ao.radius"), "3");
  EXPECT_EQ(viewer.sceneDefaultRadius(), 42.0f);
  EXPECT_NE(viewer.state().toQuery().find("ao.radius=3&"), std::string::npos) << viewer.state().toQuery();
}

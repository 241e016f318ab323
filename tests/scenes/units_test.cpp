// Scene units (sao/scenes/units.h): the words, their factors, which unit wins, the bounding-box
// scale of `auto`, and the unit each kind of scene states for itself.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "sao/scenes/scene.h"
#include "sao/scenes/units.h"
#include "test_models.h"

namespace sao::scenes {
namespace {

using test::kCubeObj;
using test::TempDir;

// A mesh whose bounding box runs from (0, 0, 0) to (x, y, z).
Mesh boxMesh(float x, float y, float z) {
  Mesh m;
  m.positions = {{0, 0, 0}, {x, 0, 0}, {0, y, 0}, {0, 0, z}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TEST(Units, WordsAndFactors) {
  EXPECT_EQ(parseLengthUnit("m"), LengthUnit::Metre);
  EXPECT_EQ(parseLengthUnit("cm"), LengthUnit::Centimetre);
  EXPECT_EQ(parseLengthUnit("mm"), LengthUnit::Millimetre);
  EXPECT_EQ(parseLengthUnit("in"), LengthUnit::Inch);
  EXPECT_EQ(parseLengthUnit("ft"), LengthUnit::Foot);
  EXPECT_EQ(parseLengthUnit("auto"), LengthUnit::Auto);
  for (const char* bad : {"", "M", "km", "metre", "mm "}) EXPECT_FALSE(parseLengthUnit(bad).has_value()) << bad;
  for (LengthUnit u : {LengthUnit::Metre, LengthUnit::Centimetre, LengthUnit::Millimetre, LengthUnit::Inch,
                       LengthUnit::Foot, LengthUnit::Auto})
    EXPECT_EQ(parseLengthUnit(toString(u)), u);
  EXPECT_EQ(metersToViewUnits(LengthUnit::Metre), 1.0);
  EXPECT_EQ(metersToViewUnits(LengthUnit::Centimetre), 100.0);
  EXPECT_EQ(metersToViewUnits(LengthUnit::Millimetre), 1000.0);
  EXPECT_DOUBLE_EQ(metersToViewUnits(LengthUnit::Inch) * 0.0254, 1.0);
  EXPECT_DOUBLE_EQ(metersToViewUnits(LengthUnit::Foot) * 0.3048, 1.0);
}

TEST(Units, RequestedWinsThenDeclaredThenMetres) {
  const Mesh mesh = boxMesh(300, 400, 0);  // diagonal 500
  const DeclaredUnits mm{LengthUnit::Millimetre, "a.scene:2"};
  const DeclaredUnits metres{LengthUnit::Metre, "glTF: metres by its specification"};
  UnitChoice c = chooseUnits(mesh, std::nullopt, std::nullopt);
  EXPECT_EQ(c.unit, "m");
  EXPECT_EQ(c.metersToViewUnits, 1.0);
  EXPECT_EQ(c.note, "m (the default: the file states no unit, see --units)");
  c = chooseUnits(mesh, mm, std::nullopt);
  EXPECT_EQ(c.unit, "mm");
  EXPECT_EQ(c.metersToViewUnits, 1000.0);
  EXPECT_EQ(c.note, "mm (a.scene:2): 1 m = 1000 units");
  c = chooseUnits(mesh, metres, LengthUnit::Inch);
  EXPECT_EQ(c.unit, "in");
  EXPECT_DOUBLE_EQ(c.metersToViewUnits, 1.0 / 0.0254);
  EXPECT_EQ(c.note, "in (--units): 1 m = 39.3701 units");
  // auto keeps a unit the scene states (glTF is metres by its specification).
  c = chooseUnits(mesh, metres, LengthUnit::Auto);
  EXPECT_EQ(c.unit, "m");
  EXPECT_EQ(c.note, "m (--units auto keeps the unit of glTF: metres by its specification)");
}

TEST(Units, AutoScalesTheBoundingBoxDiagonalToFiveMetres) {
  UnitChoice c = chooseUnits(boxMesh(300, 400, 0), std::nullopt, LengthUnit::Auto);
  EXPECT_EQ(c.unit, "auto");
  EXPECT_EQ(c.metersToViewUnits, 100.0);
  EXPECT_EQ(c.note, "auto (--units auto): bounding-box diagonal 500 units taken as 5 m, 1 m = 100 units");
  // Rounded to 3 significant digits, so that the printed figure is the one used.
  c = chooseUnits(boxMesh(1, 1, 1), std::nullopt, LengthUnit::Auto);
  EXPECT_EQ(c.metersToViewUnits, 0.346);
  EXPECT_EQ(c.note, "auto (--units auto): bounding-box diagonal 1.732 units taken as 5.00593 m, 1 m = 0.346 units");
  // A scene file's `units auto` does the same without --units.
  c = chooseUnits(boxMesh(0, 0, 2000), DeclaredUnits{LengthUnit::Auto, "b.scene:1"}, std::nullopt);
  EXPECT_EQ(c.metersToViewUnits, 400.0);
  EXPECT_EQ(c.note, "auto (b.scene:1): bounding-box diagonal 2000 units taken as 5 m, 1 m = 400 units");
  // Within the camera's range [1e-6, 1e6] (backends/core/src/camera.cpp).
  c = chooseUnits(boxMesh(1e-9f, 0, 0), std::nullopt, LengthUnit::Auto);
  EXPECT_EQ(c.metersToViewUnits, 1e-6);
  EXPECT_NE(c.note.find("(the limit of [1e-6, 1e6])"), std::string::npos) << c.note;
  EXPECT_EQ(chooseUnits(boxMesh(1e30f, 0, 0), std::nullopt, LengthUnit::Auto).metersToViewUnits, 1e6);
}

TEST(Units, EachKindOfSceneStatesItsUnit) {
  Scene builtin;
  ASSERT_TRUE(loadScene("crease", builtin));
  ASSERT_TRUE(builtin.units.has_value());
  EXPECT_EQ(builtin.units->unit, LengthUnit::Metre);

  TempDir dir;
  const std::string obj = dir.write("cube.obj", kCubeObj);
  Scene plain;
  ASSERT_TRUE(loadScene(obj, plain));
  EXPECT_FALSE(plain.units.has_value()) << "OBJ carries no unit";

  const std::string withUnits = dir.write("mm.scene", "mesh cube.obj\nunits mm\n");
  Scene scene;
  const Status s = loadScene(withUnits, scene);
  ASSERT_TRUE(s) << s.message;
  ASSERT_TRUE(scene.units.has_value());
  EXPECT_EQ(scene.units->unit, LengthUnit::Millimetre);
  EXPECT_EQ(scene.units->source, withUnits + ":2");

  Scene noUnits;
  ASSERT_TRUE(loadScene(dir.write("none.scene", "mesh cube.obj\n"), noUnits));
  EXPECT_FALSE(noUnits.units.has_value());

  const std::filesystem::path engine = test::kAssimpModels / "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  if (!std::filesystem::exists(engine)) GTEST_SKIP() << engine << " missing (Debian's assimp-testmodels)";
  Scene gltf;
  ASSERT_TRUE(loadScene(engine.string(), gltf));
  ASSERT_TRUE(gltf.units.has_value());
  EXPECT_EQ(gltf.units->unit, LengthUnit::Metre);
  Scene gltfScene;
  ASSERT_TRUE(loadScene(dir.write("g.scene", "mesh \"" + engine.string() + "\"\n"), gltfScene));
  ASSERT_TRUE(gltfScene.units.has_value()) << "a scene file of glTF meshes only is in metres";
  EXPECT_EQ(gltfScene.units->unit, LengthUnit::Metre);
}

}  // namespace
}  // namespace sao::scenes

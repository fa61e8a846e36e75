// VRML nodes to the Scene: transforms, primitives, face sets, materials, lights, the bindable
// nodes, grouping nodes, Inline and the warnings for what is not drawn.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/loaders/vrml_mesh.h"
#include "tests/loaders/vrml_test_util.h"

namespace tessera::test {
namespace {

const SceneObject& only_object(const Scene& scene) {
  EXPECT_EQ(scene.objects.size(), 1u);
  return scene.objects.at(0);
}

TEST(VrmlScene, TransformAppliesScaleOrientationRotationCentreAndTranslation) {
  const Scene scene = load_world(
      "Transform { translation 1 2 3 rotation 0 0 1 1.5707963267948966 center 1 0 0\n"
      "            scale 2 1 1 children Shape { geometry Box { size 2 2 2 } } }\n");
  const Affine& m = only_object(scene).transform;
  // p -> (p - c), scaled by 2 along x, turned 90 degrees about z, + c + t.
  EXPECT_TRUE(near(m.apply_point({2, 0, 0}), Vec3{1, 2, 0} + Vec3{1, 2, 3}, 1e-12));
  EXPECT_TRUE(near(m.apply_point({1, 1, 0}), Vec3{0, 0, 0} + Vec3{1, 2, 3}, 1e-12));
}

TEST(VrmlScene, ScaleOrientationTurnsTheScaleAxes) {
  const Scene scene = load_world(
      "Transform { scale 2 1 1 scaleOrientation 0 0 1 1.5707963267948966\n"
      "            children Shape { geometry Box {} } }\n");
  const Affine& m = only_object(scene).transform;
  EXPECT_TRUE(near(m.apply_vector({0, 1, 0}), {0, 2, 0}, 1e-12));  // scaled along turned x
  EXPECT_TRUE(near(m.apply_vector({1, 0, 0}), {1, 0, 0}, 1e-12));
}

TEST(VrmlScene, PrimitivesMapOntoTheGenericShapes) {
  const Scene scene = load_world(
      "Shape { geometry Box { size 2 4 6 } }\n"
      "Shape { geometry Sphere { radius 3 } }\n"
      "Shape { geometry Cylinder { radius 2 height 4 } }\n"
      "Shape { geometry Cone { bottomRadius 1 height 2 } }\n");
  ASSERT_EQ(scene.objects.size(), 4u);
  EXPECT_TRUE(std::holds_alternative<Cube>(scene.objects[0].geometry));
  EXPECT_TRUE(near(scene.objects[0].transform.apply_point({1, 1, 1}), {1, 2, 3}));
  EXPECT_TRUE(std::holds_alternative<Sphere>(scene.objects[1].geometry));
  // Poles on y, the texture's s = 0 (the generic sphere's +x) at -z (§6.44).
  EXPECT_TRUE(near(scene.objects[1].transform.apply_point({1, 0, 0}), {0, 0, -3}, 1e-12));
  EXPECT_TRUE(near(scene.objects[1].transform.apply_point({0, 0, 1}), {0, 3, 0}, 1e-12));
  // The tapered cylinder's base (z = 0) goes to y = -h/2, its top (z = 1) to y = +h/2.
  const auto& cylinder = std::get<TaperedCylinder>(scene.objects[2].geometry);
  EXPECT_EQ(cylinder.top_radius, 1);
  EXPECT_TRUE(near(scene.objects[2].transform.apply_point({0, 0, 0}), {0, -2, 0}, 1e-12));
  EXPECT_TRUE(near(scene.objects[2].transform.apply_point({1, 0, 1}), {2, 2, 0}, 1e-12));
  EXPECT_EQ(std::get<TaperedCylinder>(scene.objects[3].geometry).top_radius, 0);
  EXPECT_TRUE(near(scene.objects[3].transform.apply_point({0, 0, 1}), {0, 1, 0}, 1e-12));
}

TEST(VrmlScene, ConeAndCylinderPartsLeftOutAreNotDrawn) {
  const Scene scene = load_world(
      "Shape { geometry Cylinder { side FALSE top FALSE } }\n"
      "Shape { geometry Cone { bottom FALSE } }\n"
      "Shape { geometry Cylinder {} }\n");
  ASSERT_EQ(scene.objects.size(), 3u);
  const auto& base = std::get<TaperedCylinder>(scene.objects[0].geometry);
  EXPECT_FALSE(base.wall);
  EXPECT_TRUE(base.base_cap);
  EXPECT_FALSE(base.top_cap);
  const auto& cone = std::get<TaperedCylinder>(scene.objects[1].geometry);
  EXPECT_TRUE(cone.wall);
  EXPECT_FALSE(cone.base_cap);
  // What is open shows its inside, lit; closed shapes keep one-sided lighting.
  EXPECT_TRUE(scene.objects[0].material.light_back_faces);
  EXPECT_TRUE(scene.objects[1].material.light_back_faces);
  EXPECT_FALSE(scene.objects[2].material.light_back_faces);
  EXPECT_EQ(scene.objects[2].geometry,
            ShapeGeometry(TaperedCylinder{1, false, true, true, true, /*vrml_texture=*/true}));
  EXPECT_TRUE(scene.warnings.empty());
}

TEST(VrmlScene, MaterialMapsOntoTheLightingModel) {
  const Scene scene = load_world(
      "Shape { appearance Appearance { material Material { diffuseColor 0.5 0.25 1\n"
      "  ambientIntensity 0.4 emissiveColor 0.1 0 0 specularColor 1 1 1 shininess 0.5\n"
      "  transparency 0.3 } } geometry Sphere {} }\n"
      "Shape { geometry Sphere {} }\n");
  ASSERT_EQ(scene.objects.size(), 2u);
  const Material& m = scene.objects[0].material;
  EXPECT_EQ(m.diffuse, (Rgb{0.5, 0.25, 1}));
  EXPECT_TRUE(near({m.ambient.r, m.ambient.g, m.ambient.b}, {0.2, 0.1, 0.4}, 1e-15));
  EXPECT_EQ(m.emissive, (Rgb{0.1, 0, 0}));
  EXPECT_EQ(m.specular, (Rgb{1, 1, 1}));
  EXPECT_EQ(m.specular_exponent, 64);
  EXPECT_EQ(m.transparency, 0.3);
  // No material: unlit white (§6.3).
  const Material& unlit = scene.objects[1].material;
  EXPECT_EQ(unlit.emissive, (Rgb{1, 1, 1}));
  EXPECT_TRUE(unlit.diffuse.is_zero() && unlit.ambient.is_zero() && unlit.specular.is_zero());
}

TEST(VrmlScene, ImageTextureTravelsWithTheSceneAndReplacesTheDiffuseColour) {
  const Files files{{"textures/wood.ppm", kTinyPpm}};
  const Scene scene = load_world(
      "Shape { appearance Appearance { texture ImageTexture { url \"textures/wood.ppm\" }\n"
      "  material Material { diffuseColor 1 0 0 ambientIntensity 0.5 } } geometry Box {} }\n"
      "Shape { appearance Appearance { texture ImageTexture { url \"textures/wood.ppm\" } }\n"
      "  geometry Sphere {} }\n",
      files);
  ASSERT_EQ(scene.images.size(), 1u);  // read once
  EXPECT_EQ(scene.images[0].path, "textures/wood.ppm");
  EXPECT_EQ(scene.images[0].bytes, kTinyPpm);
  ASSERT_EQ(scene.objects.size(), 2u);
  const Material& lit = scene.objects[0].material;
  EXPECT_EQ(lit.flat_texture.kind, FlatTexture::Kind::Image);
  EXPECT_FALSE(lit.flat_texture.decal);
  EXPECT_EQ(lit.diffuse, (Rgb{1, 1, 1}));
  EXPECT_EQ(lit.ambient, (Rgb{0.5, 0.5, 0.5}));
  const Material& unlit = scene.objects[1].material;
  EXPECT_TRUE(unlit.flat_texture.decal);
  EXPECT_TRUE(unlit.emissive.is_zero());
}

TEST(VrmlScene, AMissingOrUndecodableTextureLeavesTheShapeUntextured) {
  const std::string body =
      "Shape { appearance Appearance { texture ImageTexture { url [\"bad.png\" \"no.png\"] }\n"
      "  material Material { diffuseColor 1 0 0 } } geometry Box {} }\n"
      "Shape { appearance Appearance { texture ImageTexture { url \"bad.png\" } }"
      " geometry Box {} }\n";
  const Files files{{"bad.png", "not an image"}};
  const Scene scene = load_world(body, files);
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_TRUE(scene.images.empty());
  EXPECT_EQ(scene.objects[0].material.flat_texture.kind, FlatTexture::Kind::None);
  EXPECT_EQ(scene.objects[0].material.diffuse, (Rgb{1, 0, 0}));
  EXPECT_EQ(scene.warnings,
            (std::vector<std::string>{
                "world.wrl:2:41: ImageTexture: 'no.png' not found: the shape is drawn untextured",
                "world.wrl:4:41: ImageTexture: 'bad.png' is not an image this loader can decode: "
                "the shape is drawn untextured"}));
  try {
    load_world(body, files, strict_budget());
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(),
                 "world.wrl:2:41: ImageTexture: 'no.png' not found: the shape is drawn "
                 "untextured");
  }
}

TEST(VrmlScene, ConcavePolygonsAreEarClipped) {
  // An L of area 3 whose first corner is reflex: a fan from it would leave the polygon.
  const std::vector<Vec3> l_shape{{1, 1, 0}, {1, 2, 0}, {0, 2, 0}, {0, 0, 0}, {2, 0, 0}, {2, 1, 0}};
  const auto triangles = vrml::triangulate_polygon(l_shape);
  ASSERT_EQ(triangles.size(), 4u);
  double sum = 0;
  for (const auto& [a, b, c] : triangles) {
    const Vec3 n = cross(l_shape[b] - l_shape[a], l_shape[c] - l_shape[a]);
    EXPECT_GT(n.z, 0);  // orientation kept
    sum += n.z / 2;
  }
  EXPECT_DOUBLE_EQ(sum, 3);
}

TEST(VrmlScene, FaceSetBecomesAMeshWithItsWinding) {
  const std::string coords = "coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }";
  const Scene ccw =
      load_world("Shape { geometry IndexedFaceSet { " + coords + " coordIndex [0 1 2 3 -1] } }");
  const Scene cw = load_world("Shape { geometry IndexedFaceSet { " + coords +
                              " coordIndex [0 1 2 3] ccw FALSE solid FALSE } }");
  const Mesh& a = ccw.meshes.at(std::get<MeshShape>(only_object(ccw).geometry).mesh);
  const Mesh& b = cw.meshes.at(std::get<MeshShape>(only_object(cw).geometry).mesh);
  EXPECT_DOUBLE_EQ(mesh_area(a), 1);
  const auto normal = [](const Mesh& m) {
    const MeshTriangle& t = m.triangles.at(0);
    return cross(m.positions[t.v[1]] - m.positions[t.v[0]],
                 m.positions[t.v[2]] - m.positions[t.v[0]]);
  };
  EXPECT_GT(normal(a).z, 0);
  EXPECT_LT(normal(b).z, 0);
  EXPECT_FALSE(only_object(ccw).material.light_back_faces);
  EXPECT_TRUE(only_object(cw).material.light_back_faces);  // solid FALSE: both faces lit
  EXPECT_FALSE(std::get<MeshShape>(only_object(ccw).geometry).interpolate_normals);
}

TEST(VrmlScene, CreaseAngleSmoothsWithinItAndKeepsEdgesBeyondIt) {
  // Two faces meeting at 90 degrees along the edge x = 1.
  const std::string faces =
      "coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0, 1 0 -1, 1 1 -1] }\n"
      "coordIndex [0 1 2 3 -1, 1 4 5 2 -1]";
  const auto corner_normal = [](const Scene& scene) {
    const Mesh& m = scene.meshes.at(0);
    for (const MeshTriangle& t : m.triangles)
      for (int k = 0; k < 3; ++k)
        if (m.positions[t.v[k]] == Vec3{1, 0, 0} && t.n[k] != MeshTriangle::kNoNormal &&
            m.normals[t.n[k]].x >= 0 && m.normals[t.n[k]].z >= 0)
          return m.normals[t.n[k]];
    return Vec3{};
  };
  const Scene smooth =
      load_world("Shape { geometry IndexedFaceSet { " + faces + " creaseAngle 1.6 } }");
  const double h = std::sqrt(0.5);
  EXPECT_TRUE(near(corner_normal(smooth), {h, 0, h}, 1e-12));
  const Scene sharp =
      load_world("Shape { geometry IndexedFaceSet { " + faces + " creaseAngle 1.5 } }");
  EXPECT_TRUE(near(corner_normal(sharp), {0, 0, 1}, 1e-12));
}

TEST(VrmlScene, GivenNormalsPerVertexAndPerFace) {
  const std::string base =
      "coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] } coordIndex [0 1 2]\n"
      "normal Normal { vector [0 0 1, 0 1 0] } ";
  const Scene per_vertex =
      load_world("Shape { geometry IndexedFaceSet { " + base + "normalIndex [1 1 0] } }");
  const Mesh& a = per_vertex.meshes.at(0);
  EXPECT_EQ(a.normals[a.triangles[0].n[0]], (Vec3{0, 1, 0}));
  EXPECT_EQ(a.normals[a.triangles[0].n[2]], (Vec3{0, 0, 1}));
  const Scene per_face = load_world("Shape { geometry IndexedFaceSet { " + base +
                                    "normalPerVertex FALSE normalIndex [1] } }");
  const Mesh& b = per_face.meshes.at(0);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(b.normals[b.triangles[0].n[k]], (Vec3{0, 1, 0}));
  EXPECT_TRUE(
      world_fails_at("Shape { geometry IndexedFaceSet { coord Coordinate { point [0 0 0] }"
                     " coordIndex [0 0 7] } }",
                     2, 81, "coordIndex 7 is out of range: the Coordinate has 1 entries"));
}

// The signed volume enclosed by a mesh (divergence theorem): positive when every face points
// outwards.
double volume(const Mesh& mesh) {
  double sum = 0;
  for (const MeshTriangle& t : mesh.triangles)
    sum += dot(mesh.positions[t.v[0]], cross(mesh.positions[t.v[1]], mesh.positions[t.v[2]])) / 6;
  return sum;
}

TEST(VrmlScene, ElevationGridIsAMeshFacingUp) {
  const Scene scene = load_world(
      "Shape { geometry ElevationGrid { xDimension 3 zDimension 2 xSpacing 0.5 zSpacing 2\n"
      "  height [0 0 0, 0 0 0] } }");
  const Mesh& m = scene.meshes.at(0);
  EXPECT_EQ(m.positions.size(), 6u);
  EXPECT_DOUBLE_EQ(mesh_area(m), 1 * 2);
  for (const MeshTriangle& t : m.triangles)
    EXPECT_GT(
        cross(m.positions[t.v[1]] - m.positions[t.v[0]], m.positions[t.v[2]] - m.positions[t.v[0]])
            .y,
        0);
  EXPECT_TRUE(
      world_fails_at("Shape { geometry ElevationGrid { xDimension 2 zDimension 2 height [1] } }", 2,
                     18, "ElevationGrid: height has 1 values for 2 x 2 points"));
}

TEST(VrmlScene, ExtrusionIsAClosedOutwardFacingSolid) {
  // The default cross-section (a 2 x 2 square) along the default spine (0 0 0 to 0 1 0).
  const Scene prism = load_world("Shape { geometry Extrusion {} }");
  EXPECT_DOUBLE_EQ(mesh_area(prism.meshes.at(0)), 4 * 2 + 2 * 4);
  EXPECT_NEAR(volume(prism.meshes.at(0)), 4, 1e-12);
  // Scaled and bent: a quarter turn of spine still encloses positive volume.
  const Scene bent = load_world(
      "Shape { geometry Extrusion { spine [0 0 0, 0 1 0, 1 2 0] scale [1 1, 0.5 0.5, 0.5 0.5]\n"
      "  crossSection [0.2 0.2, 0.2 -0.2, -0.2 -0.2, -0.2 0.2, 0.2 0.2] } }");
  EXPECT_GT(volume(bent.meshes.at(0)), 0);
}

TEST(VrmlScene, ExtrusionEndsTakeTheirNeighboursPlanes) {
  // A right-angle bend at the middle point: its Z is (0, 0, -1), which the open spine's two
  // end points take too (§6.18.2), so that the section's x runs along -x at the start (X = Y x
  // Z with Y = +y) and along +y at the end (Y = +x).
  const Scene scene = load_world(
      "Shape { geometry Extrusion { spine [0 0 0, 0 1 0, 1 1 0] crossSection [1 0, 0 1, -1 0]\n"
      "  beginCap FALSE endCap FALSE } }");
  const Mesh& m = scene.meshes.at(0);
  ASSERT_EQ(m.positions.size(), 9u);
  EXPECT_TRUE(near(m.positions[0], {-1, 0, 0}));  // section (1, 0) at the first point
  EXPECT_TRUE(near(m.positions[1], {0, 0, -1}));  // section (0, 1): along Z
  EXPECT_TRUE(near(m.positions[6], {1, 2, 0}));   // section (1, 0) at the last point
}

TEST(VrmlScene, UseOfAFaceSetSharesOneMesh) {
  const Scene scene = load_world(
      "DEF F Shape { geometry IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] }"
      " coordIndex [0 1 2] } }\nTransform { translation 5 0 0 children USE F }\n");
  EXPECT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.meshes.size(), 1u);
}

TEST(VrmlScene, LightsTakeTheirTransformIntensityAndColour) {
  const Scene scene = load_world(
      "NavigationInfo { headlight FALSE }\n"
      "Transform { translation 0 5 0 children [\n"
      "  PointLight { location 1 0 0 intensity 0.5 color 1 0.5 0 attenuation 1 0.1 0 }\n"
      "  DirectionalLight { direction 0 0 -2 ambientIntensity 0.5 }\n"
      "  SpotLight { direction 0 -1 0 cutOffAngle 0.5 beamWidth 0.3 }\n"
      "  PointLight { on FALSE } ] }\n");
  ASSERT_EQ(scene.lights.size(), 3u);
  const Light& point = scene.lights[0];
  EXPECT_EQ(point.position, (Vec3{1, 5, 0}));
  EXPECT_EQ(point.color, (Rgb{0.5, 0.25, 0}));
  // Its own attenuation and reach (radius defaults to 100), not the scene's.
  EXPECT_EQ(point.attenuation, (LightAttenuation{1, 0.1, 0}));
  EXPECT_EQ(point.radius, 100);
  EXPECT_TRUE(scene.globals.light_attenuation.is_identity());
  const Light& directional = scene.lights[1];
  EXPECT_TRUE(directional.is_directional);
  EXPECT_EQ(directional.direction, (Vec3{0, 0, -1}));
  EXPECT_EQ(scene.globals.global_ambient, (Rgb{0.5, 0.5, 0.5}));
  const Light& spot = scene.lights[2];
  ASSERT_TRUE(spot.is_spot);
  EXPECT_NEAR(spot.spot.cutoff_degrees, 0.5 * 180 / std::numbers::pi, 1e-12);
  // Half intensity halfway between beamWidth and cutOffAngle.
  EXPECT_NEAR(std::pow(std::cos(0.4), spot.spot.exponent), 0.5, 1e-12);
}

TEST(VrmlScene, DirectionalLightsLightOnlyTheirGroupAndTheBillboardsInIt) {
  // Objects: 0 and 4 at the top level, 1 and 2 in the Transform, 3 in the inline; the
  // Billboard's box is laid down last, 5, once the camera is known.
  const Files files{
      {"lamp.wrl", std::string(kVrmlHeader) + "DirectionalLight {} Shape { geometry Sphere {} }"}};
  const Scene scene = load_world(
      "NavigationInfo { headlight FALSE }\n"
      "Shape { geometry Box {} }\n"
      "Transform { children [\n"
      "  Shape { geometry Box {} }\n"
      "  Billboard { children Shape { geometry Box {} } }\n"
      "  DirectionalLight { direction 1 0 0 }\n"
      "  Group { children Shape { geometry Box {} } } ] }\n"
      "Inline { url \"lamp.wrl\" }\n"
      "Switch { whichChoice 0 choice DirectionalLight {} }\n"
      "Shape { geometry Box {} }\n"
      "DirectionalLight { direction 0 -1 0 }\n",
      files);
  ASSERT_EQ(scene.objects.size(), 6u);
  ASSERT_EQ(scene.lights.size(), 4u);
  const auto lit = [&](const Light& light) {
    std::vector<std::uint32_t> objects;
    for (std::uint32_t i = 0; i < scene.objects.size(); ++i)
      if (light.lights(i)) objects.push_back(i);
    return objects;
  };
  using Objects = std::vector<std::uint32_t>;
  EXPECT_EQ(lit(scene.lights[0]), (Objects{1, 2, 5}));           // the Transform's, billboard too
  EXPECT_EQ(lit(scene.lights[1]), (Objects{3}));                 // the inline's roots
  EXPECT_EQ(lit(scene.lights[2]), (Objects{}));                  // alone in its Switch
  EXPECT_EQ(lit(scene.lights[3]), (Objects{0, 1, 2, 3, 4, 5}));  // the world's roots
}

TEST(VrmlScene, HeadlightIsOnUnlessNavigationInfoSaysOtherwise) {
  const Scene lit = load_world(
      "Viewpoint { position 0 0 4 orientation 0 1 0 1.5707963267948966 }\n"
      "Shape { geometry Sphere {} }");
  ASSERT_EQ(lit.lights.size(), 1u);
  EXPECT_TRUE(lit.lights[0].is_directional);
  EXPECT_TRUE(near(lit.lights[0].direction, {-1, 0, 0}, 1e-12));  // along the view
  EXPECT_TRUE(load_world("NavigationInfo { headlight FALSE }").lights.empty());
}

TEST(VrmlScene, FirstViewpointSetsTheCamera) {
  const Scene scene = load_world(
      "Transform { translation 0 1 0 children Viewpoint { position 0 0 4\n"
      "  orientation 0 1 0 1.5707963267948966 fieldOfView 0.5 } }\n"
      "Viewpoint { position 9 9 9 }\n");
  EXPECT_TRUE(near(scene.camera.eye, {0, 1, 4}));
  EXPECT_TRUE(near(view_direction(scene.camera), {-1, 0, 0}, 1e-12));
  EXPECT_TRUE(near(scene.camera.up, {0, 1, 0}, 1e-12));
  EXPECT_NEAR(scene.camera.view_angle, 0.5 * 180 / std::numbers::pi, 1e-12);
  EXPECT_TRUE(scene.camera.view_angle_on_smaller_side);
}

// Every Viewpoint of the world is offered by name (the page lists them); Inlined ones are not
// bound, so not offered either.
TEST(VrmlScene, ViewpointsAreListedInFileOrderByDescription) {
  const Scene scene = load_world(
      "Viewpoint { position 0 0 4 description \"Front\" }\n"
      "Transform { translation 1 0 0 children Viewpoint { position 0 0 9 fieldOfView 0.5 } }\n"
      "Transform { scale 1 1 0 children Viewpoint { orientation 1 0 0 1.5707963267948966 "
      "description \"no view\" } }\n");
  ASSERT_EQ(scene.viewpoints.size(), 2u);
  EXPECT_EQ(scene.viewpoints[0].name, "Front");
  EXPECT_EQ(scene.viewpoints[0].camera, scene.camera);
  EXPECT_EQ(scene.viewpoints[1].name, "world.wrl:3:40");
  EXPECT_EQ(scene.viewpoints[1].camera.eye, (Vec3{1, 0, 9}));
  EXPECT_EQ(scene.viewpoints[1].camera.view_angle, 0.5 * 180 / std::numbers::pi);
}

// A camera setting is bound in the Viewpoint's place: the headlight shines along it and
// Billboards turn to it, as they would for a Viewpoint there.
TEST(VrmlScene, ACameraSettingReplacesTheViewpointForHeadlightAndBillboards) {
  MemorySource source;
  source.add("world.wrl", std::string(kVrmlHeader) +
                              "Viewpoint { position 0 0 10 }\n"
                              "Billboard { children Shape { geometry Box {} } }\n");
  const Camera camera{{10, 0, 0}, {0, 0, 0}, {0, 1, 0}, 30};
  const Scene scene = load_vrml(source, "world.wrl", {}, camera);
  EXPECT_EQ(scene.camera.eye, camera.eye);
  EXPECT_EQ(scene.camera.view_angle, 30);
  EXPECT_TRUE(scene.camera.view_angle_on_smaller_side);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].direction, (Vec3{-1, 0, 0}));
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_TRUE(near(scene.objects[0].transform.apply_vector({0, 0, 1}), {1, 0, 0}, 1e-12));
  EXPECT_EQ(scene.viewpoints.size(), 1u);  // still offered
}

TEST(VrmlScene, BillboardTurnsItsChildrenTowardsTheViewer) {
  // The eye at +x: about the y axis, the children's +z turns to +x.
  const Scene scene = load_world(
      "Billboard { children Shape { geometry Box {} } }\n"
      "Viewpoint { position 10 0 0 orientation 0 1 0 1.5707963267948966 }\n"
      "Billboard { axisOfRotation 0 0 0 children Shape { geometry Box {} } }\n");
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_TRUE(near(scene.objects[0].transform.apply_vector({0, 0, 1}), {1, 0, 0}, 1e-12));
  EXPECT_TRUE(near(scene.objects[0].transform.apply_vector({0, 1, 0}), {0, 1, 0}, 1e-12));
  EXPECT_TRUE(near(scene.objects[1].transform.apply_vector({0, 0, 1}), {1, 0, 0}, 1e-12));
  EXPECT_TRUE(near(scene.objects[1].transform.apply_vector({0, 1, 0}), {0, 1, 0}, 1e-12));
}

TEST(VrmlScene, BackgroundAndFog) {
  const Scene scene = load_world(
      "Background { skyColor [0.1 0.2 0.3, 1 1 1] skyAngle 1 }\n"
      "Fog { color 0.5 0.5 0.5 visibilityRange 40 }\n");
  EXPECT_EQ(scene.globals.background, (Rgb{0.1, 0.2, 0.3}));
  ASSERT_TRUE(scene.globals.fog);
  EXPECT_EQ(*scene.globals.fog, (Fog{0, 40, {0.5, 0.5, 0.5}}));
  EXPECT_FALSE(load_world("Fog { visibilityRange 0 }").globals.fog);  // no fog
  EXPECT_TRUE(scene.globals.sky);                                     // a sky angle: a gradient
  EXPECT_FALSE(load_world("Background { skyColor 0.1 0.2 0.3 }").globals.sky);
}

TEST(VrmlScene, BackgroundAnglesMakeAGradientAboutItsUp) {
  const Scene scene = load_world(
      "Transform { rotation 0 0 1 1.5707963267948966 children Background {\n"
      "  skyColor [0 0 1, 1 1 1, 0.5 0.5 0.5, 9 9 9] skyAngle [1.2, 1.6, 2, 2.5]\n"
      "  groundColor [0.2 0.1 0, 0 0.6 0] groundAngle 1 } }\n");
  ASSERT_TRUE(scene.globals.sky);
  const SkyGradient& sky = *scene.globals.sky;
  EXPECT_TRUE(near(sky.up, {-1, 0, 0}, 1e-12));  // +y turned a quarter about z
  // One angle fewer than colours: the fourth sky angle has no colour after it and is ignored.
  EXPECT_EQ(sky.sky_angles, (std::vector<double>{1.2, 1.6, 2}));
  EXPECT_EQ(sky.sky_colours, (std::vector<Rgb>{{0, 0, 1}, {1, 1, 1}, {0.5, 0.5, 0.5}, {9, 9, 9}}));
  EXPECT_EQ(sky.ground_angles, (std::vector<double>{1}));
  EXPECT_EQ(sky.ground_colours.size(), 2u);
  EXPECT_EQ(scene.globals.background, (Rgb{0, 0, 1}));
  EXPECT_TRUE(scene.warnings.empty());
  // Panoramas are not drawn: said once.
  const Scene panorama = load_world("Background { skyColor 0 0 1 frontUrl \"sky.png\" }");
  ASSERT_EQ(panorama.warnings.size(), 1u);
  EXPECT_NE(panorama.warnings[0].find("not rendered (yet): Background panorama (1)"),
            std::string::npos)
      << panorama.warnings[0];
  EXPECT_TRUE(world_fails_at("Background { skyColor [0 0 1, 1 1 1, 0 0 0] skyAngle [1.5 1] }", 2,
                             54, "Background: skyAngle must increase from 0 to at most pi"));
}

TEST(VrmlScene, SwitchAndLodChooseOneChild) {
  const Scene scene = load_world(
      "Switch { whichChoice 1 choice [ Shape { geometry Box {} } Shape { geometry Sphere {} } ] }\n"
      "Switch { choice Shape { geometry Box {} } }\n"
      "LOD { range [10] level [ Shape { geometry Sphere {} } Shape { geometry Box {} } ] }\n");
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<Sphere>(scene.objects[0].geometry));
  EXPECT_TRUE(std::holds_alternative<Sphere>(scene.objects[1].geometry));
  // whichChoice counts every child, also those that are not drawn (§6.46).
  const Scene counted = load_world(
      "DEF T TimeSensor {}\n"
      "Switch { whichChoice 2 choice [ USE T Text {} Shape { geometry Sphere {} } ] }\n"
      "Switch { whichChoice 0 choice [ WorldInfo {} Shape { geometry Box {} } ] }\n"
      "LOD { level [ Transform { children [ Script {} Shape { geometry Sphere {} } ] } ] }\n");
  ASSERT_EQ(counted.objects.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<Sphere>(counted.objects[0].geometry));
  EXPECT_TRUE(std::holds_alternative<Sphere>(counted.objects[1].geometry));
}

TEST(VrmlScene, InlineReadsAFileOfTheSourceUnderTheTransform) {
  const Files files{{"parts/ball.wrl", std::string(kVrmlHeader) + "Shape { geometry Sphere {} }"}};
  const Scene scene = load_world(
      "Transform { translation 3 0 0 children Inline { url [\"missing.wrl\" \"parts/ball.wrl\"] } "
      "}",
      files);
  EXPECT_TRUE(near(only_object(scene).transform.apply_point({}), {3, 0, 0}));
  EXPECT_TRUE(world_fails_at("Inline { url \"../outside.wrl\" }", 2, 1,
                             "Inline: '../outside.wrl' is outside the scene's root: left out",
                             strict_budget()));
  EXPECT_TRUE(world_fails_at("Inline { url \"gone.wrl\" }", 2, 1,
                             "Inline: 'gone.wrl' not found: left out", strict_budget()));
  EXPECT_TRUE(world_fails_at("Inline { url \"https://example.org/a.wrl\" }", 2, 1,
                             "Inline: the url scheme of 'https://example.org/a.wrl' is not read "
                             "(the loader fetches nothing): left out",
                             strict_budget()));
  const Scene lenient = load_world("Inline { url \"gone.wrl\" }\nShape { geometry Box {} }");
  EXPECT_EQ(lenient.objects.size(), 1u);
  EXPECT_EQ(lenient.warnings,
            std::vector<std::string>{"world.wrl:2:1: Inline: 'gone.wrl' not found: left out"});
}

TEST(VrmlScene, ABundleWorldInAFolderReadsItsNeighboursThroughDotDot) {
  const Files files{
      {"textures/y.ppm", kTinyPpm},
      {"common/z.wrl", std::string(kVrmlHeader) + "Shape { geometry Sphere {} }"},
      {"world/x.wrl",
       std::string(kVrmlHeader) +
           "Shape { appearance Appearance { texture ImageTexture { url \"../textures/y.ppm\" } }\n"
           "  geometry Box {} }\nInline { url \"file:../common/z.wrl\" }\n"}};
  const Scene scene = load_vrml(MemorySource(files), "world/x.wrl", strict_budget());
  ASSERT_EQ(scene.objects.size(), 2u);
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_EQ(scene.images[0].path, "textures/y.ppm");
}

TEST(VrmlScene, ExternProtoReadsALocalFileLikeInline) {
  const Files files{
      {"protos/lib.wrl", std::string(kVrmlHeader) +
                             "PROTO First [ field SFFloat r 1 ] { Sphere { radius IS r } }\n"
                             "PROTO Crate [ field SFVec3f size 1 1 1 ] { Box { size IS size } }\n"},
      {"loop.wrl",
       std::string(kVrmlHeader) + "EXTERNPROTO L [ ] \"loop.wrl#L\"\nPROTO L [ ] { Box {} }\n"}};
  const Scene scene = load_world(
      "EXTERNPROTO Crate [ field SFVec3f size ] \"protos/lib.wrl#Crate\"\n"
      "EXTERNPROTO Ball [ field SFFloat r ] [ \"missing.wrl\" \"protos/lib.wrl\" ]\n"
      "EXTERNPROTO L [ ] \"loop.wrl#L\"\n"
      "Shape { geometry Crate { size 2 4 6 } }\nShape { geometry Ball { r 3 } }\n"
      "Inline { url \"loop.wrl\" }\n",
      files);
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_TRUE(std::holds_alternative<Cube>(scene.objects[0].geometry));
  EXPECT_TRUE(near(scene.objects[0].transform.apply_point({1, 1, 1}), {1, 2, 3}));
  EXPECT_TRUE(std::holds_alternative<Sphere>(scene.objects[1].geometry));
  EXPECT_TRUE(near(scene.objects[1].transform.apply_point({0, 0, 0}), {0, 0, 0}));
  EXPECT_NEAR(length(scene.objects[1].transform.apply_vector({1, 0, 0})), 3, 1e-12);
  // The file that names its own EXTERNPROTO: a warning, no endless read.
  ASSERT_FALSE(scene.warnings.empty());
  EXPECT_NE(scene.warnings[0].find("names its own file"), std::string::npos) << scene.warnings[0];
}

TEST(VrmlScene, BindableNodesOfInlinedFilesAreNotBound) {
  const Files files{
      {"part.wrl", std::string(kVrmlHeader) +
                       "Viewpoint { position 0 0 40 }\nBackground { skyColor 0 0 1 }\n"
                       "Fog { visibilityRange 5 }\nNavigationInfo { headlight FALSE }\n"
                       "Shape { geometry Sphere {} }\n"}};
  const Scene scene = load_world(
      "Inline { url \"part.wrl\" }\nViewpoint { position 0 0 6 }\n"
      "Background { skyColor 1 0 0 }\n",
      files);
  EXPECT_TRUE(near(scene.camera.eye, {0, 0, 6}));
  EXPECT_EQ(scene.globals.background, (Rgb{1, 0, 0}));
  EXPECT_FALSE(scene.globals.fog.has_value());
  ASSERT_EQ(scene.lights.size(), 1u);  // the main file's headlight, on by default
  EXPECT_TRUE(scene.lights[0].is_directional);
  // Without bindable nodes of its own, a world gets the defaults, not the Inline's.
  const Scene defaults = load_world("Inline { url \"part.wrl\" }\n", files);
  EXPECT_EQ(defaults.globals.background, (Rgb{}));
  EXPECT_EQ(defaults.lights.size(), 1u);
}

TEST(VrmlScene, TheHeadlightShinesAlongTheViewAndCastsNoShadow) {
  const Scene scene = load_world("Viewpoint { position 1 2 3 }\nShape { geometry Box {} }\n");
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_TRUE(scene.lights[0].is_directional);
  EXPECT_TRUE(near(scene.lights[0].direction, {0, 0, -1}));
  EXPECT_EQ(scene.lights[0].color, (Rgb{1, 1, 1}));
  EXPECT_FALSE(scene.lights[0].casts_shadows);
}

TEST(VrmlScene, BillboardsCountInTheFramingBounds) {
  // A lone Billboard holding a sphere of radius 2 at x = 10: the framed camera looks at it.
  const Scene scene = load_world(
      "Transform { translation 10 0 0 children Billboard { children Shape { geometry Sphere "
      "{ radius 2 } } } }\n");
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_TRUE(near(scene.camera.look_at, {10, 0, 0}));
  const double distance = 2 / std::sin(45 * std::numbers::pi / 360);
  EXPECT_TRUE(near(scene.camera.eye, {10, 0, distance}));
}

TEST(VrmlScene, OneWarningListsWhatIsIgnored) {
  const Scene scene = load_world(
      "DEF C TimeSensor {}\nDEF I PositionInterpolator {}\nROUTE C.fraction_changed TO "
      "I.set_fraction\nShape { geometry Text { string \"x\" } }\n");
  ASSERT_EQ(scene.warnings.size(), 2u);
  EXPECT_EQ(scene.warnings[0],
            "world.wrl: ignored (a still image has no animation, sensing or "
            "sound): PositionInterpolator (1), ROUTE (1), TimeSensor (1)");
  EXPECT_EQ(scene.warnings[1], "world.wrl: not rendered (yet): Text (1)");
  EXPECT_TRUE(world_fails_at("Box {}", 2, 1,
                             "'Box' is not a child node: it belongs in a field of a Shape, "
                             "Appearance or geometry node"));
}

}  // namespace
}  // namespace tessera::test

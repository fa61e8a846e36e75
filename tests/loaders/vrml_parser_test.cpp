// The VRML97 parser: header, comments, every field type with and without brackets, DEF/USE,
// PROTO with default, given and nested IS values, EXTERNPROTO, ROUTE, non-visual nodes,
// gzip, and located errors.
#include <gtest/gtest.h>
#include <zlib.h>

#include "tests/loaders/vrml_test_util.h"

namespace tessera::test {
namespace {

using vrml::FieldType;
using vrml::Node;

const Node& only_root(const vrml::ParsedWorld& world) {
  EXPECT_EQ(world.roots.size(), 1u);
  return *world.roots.at(0);
}

std::vector<double> numbers(const Node& n, const char* field) {
  const vrml::FieldValue* v = n.field(field);
  EXPECT_NE(v, nullptr) << field;
  return v ? v->numbers : std::vector<double>{};
}

// The radius of the Sphere a Shape draws.
double radius(const Node& shape) {
  return shape.field("geometry")->nodes.at(0)->field("radius")->numbers.at(0);
}

TEST(VrmlParser, RequiresTheHeader) {
  try {
    vrml::lex_vrml("#VRML V1.0 ascii\nSeparator {}", "old.wrl");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "old.wrl:1:1: expected the header '#VRML V2.0 utf8' (VRML 1.0 is not supported)");
  }
  EXPECT_THROW(vrml::lex_vrml("Group {}", "x.wrl"), SceneError);
}

TEST(VrmlParser, CommentsAndCommasAreWhitespace) {
  const vrml::ParsedWorld world =
      parse_world("# a comment\nTransform { # another\n translation 1, 2,3 }  # trailing\n");
  const Node& t = only_root(world);
  EXPECT_EQ(t.type, "Transform");
  EXPECT_EQ(numbers(t, "translation"), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(t.where.line, 3);
  EXPECT_EQ(t.where.column, 1);
}

TEST(VrmlParser, SingleValuedFieldTypes) {
  const vrml::ParsedWorld world = parse_world(
      "Cylinder { side FALSE top TRUE radius 2.5e-1 }\n"   // SFBool, SFFloat
      "Switch { whichChoice 0x1F }\n"                      // SFInt32 (hexadecimal)
      "TextureTransform { center -1 .5 }\n"                // SFVec2f
      "Transform { rotation 0 1 0 1.5708 scale 1 2 3 }\n"  // SFRotation, SFVec3f
      "Material { diffuseColor 1 0.5 0 }\n"                // SFColor
      "Fog { fogType \"EXPONENTIAL\" }\n"                  // SFString
      "Shape { geometry Sphere {} appearance NULL }\n");   // SFNode
  ASSERT_EQ(world.roots.size(), 7u);
  EXPECT_EQ(numbers(*world.roots[0], "side"), std::vector<double>{0});
  EXPECT_EQ(numbers(*world.roots[0], "top"), std::vector<double>{1});
  EXPECT_EQ(numbers(*world.roots[0], "radius"), std::vector<double>{0.25});
  EXPECT_EQ(numbers(*world.roots[1], "whichChoice"), std::vector<double>{31});
  EXPECT_EQ(numbers(*world.roots[2], "center"), (std::vector<double>{-1, 0.5}));
  EXPECT_EQ(numbers(*world.roots[3], "rotation"), (std::vector<double>{0, 1, 0, 1.5708}));
  EXPECT_EQ(numbers(*world.roots[3], "scale"), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(numbers(*world.roots[4], "diffuseColor"), (std::vector<double>{1, 0.5, 0}));
  EXPECT_EQ(world.roots[5]->field("fogType")->strings, std::vector<std::string>{"EXPONENTIAL"});
  const Node& shape = *world.roots[6];
  ASSERT_EQ(shape.field("geometry")->nodes.size(), 1u);
  EXPECT_EQ(shape.field("geometry")->nodes[0]->type, "Sphere");
  EXPECT_TRUE(shape.field("appearance")->nodes.empty());
}

TEST(VrmlParser, MultipleValuedFieldTypesWithAndWithoutBrackets) {
  const vrml::ParsedWorld world = parse_world(
      "IndexedFaceSet { coordIndex [0 1 2 -1, 2 3 0] coord Coordinate { point [0 0 0, 1 0 0] } }\n"
      "LOD { range 10 level [ Group {} Group {} ] }\n"           // MFFloat, MFNode
      "TextureCoordinate { point [ 0 0, 1 0, 1 1 ] }\n"          // MFVec2f
      "Color { color 1 0 0 }\n"                                  // MFColor, no brackets
      "Extrusion { orientation [0 0 1 0, 0 1 0 3.14] }\n"        // MFRotation
      "Inline { url [ \"a.wrl\" \"b \\\"quoted\\\".wrl\" ] }\n"  // MFString, escapes
      "NavigationInfo { type \"EXAMINE\" }\n");                  // MFString, no brackets
  ASSERT_EQ(world.roots.size(), 7u);
  EXPECT_EQ(numbers(*world.roots[0], "coordIndex"), (std::vector<double>{0, 1, 2, -1, 2, 3, 0}));
  EXPECT_EQ(world.roots[0]->field("coord")->nodes[0]->field("point")->size(), 2u);
  EXPECT_EQ(numbers(*world.roots[1], "range"), std::vector<double>{10});
  EXPECT_EQ(world.roots[1]->field("level")->nodes.size(), 2u);
  EXPECT_EQ(world.roots[2]->field("point")->size(), 3u);
  EXPECT_EQ(world.roots[3]->field("color")->size(), 1u);
  EXPECT_EQ(world.roots[4]->field("orientation")->size(), 2u);
  EXPECT_EQ(world.roots[5]->field("url")->strings,
            (std::vector<std::string>{"a.wrl", "b \"quoted\".wrl"}));
  EXPECT_EQ(world.roots[6]->field("type")->strings, std::vector<std::string>{"EXAMINE"});
}

TEST(VrmlParser, ProtoFieldsOfEveryOtherTypeParse) {
  // MFBool, SFTime and MFTime appear only in nodes that are not drawn; their values still parse.
  const vrml::ParsedWorld world = parse_world(
      "PROTO P [ field MFBool flags [TRUE FALSE] field SFTime t 1.5 field MFTime ts [0 1]\n"
      "          field MFInt32 ints [1 2] eventIn SFBool set_on ] { Group {} }\n"
      "P { flags TRUE ts 2 }\n");
  EXPECT_EQ(only_root(world).type, "Group");
  EXPECT_TRUE(world_fails_at("PROTO P [ field MFBool f [TRUE maybe] ] { Group {} }", 2, 32,
                             "expected TRUE or FALSE for 'f' of PROTO 'P', found 'maybe'"));
}

TEST(VrmlParser, DefAndUseShareOneNode) {
  const vrml::ParsedWorld world =
      parse_world("DEF Ball Shape { geometry Sphere {} }\nTransform { children USE Ball }\n");
  ASSERT_EQ(world.roots.size(), 2u);
  EXPECT_EQ(world.roots[1]->field("children")->nodes.at(0).get(), world.roots[0].get());
  EXPECT_TRUE(world_fails_at("USE Nothing", 2, 5, "node 'Nothing' is not DEFined"));
}

TEST(VrmlParser, ProtoInstancesTakeDefaultAndGivenValues) {
  const vrml::ParsedWorld world = parse_world(
      "PROTO Ball [ field SFFloat r 2 exposedField SFColor c 1 0 0 ] {\n"
      "  Shape { geometry Sphere { radius IS r }\n"
      "          appearance Appearance { material Material { diffuseColor IS c } } }\n"
      "  ROUTE a.b TO c.d\n"
      "}\n"
      "Ball {}\n"
      "Ball { r 5 }\n");
  ASSERT_EQ(world.roots.size(), 2u);
  EXPECT_EQ(world.roots[0]->type, "Shape");
  EXPECT_EQ(radius(*world.roots[0]), 2);
  EXPECT_EQ(radius(*world.roots[1]), 5);
  const Node& material =
      *world.roots[1]->field("appearance")->nodes.at(0)->field("material")->nodes.at(0);
  EXPECT_EQ(material.field("diffuseColor")->numbers, (std::vector<double>{1, 0, 0}));
  EXPECT_EQ(world.ignored.at("ROUTE"), 1);
}

TEST(VrmlParser, ProtoInsideProtoPassesIsValuesThrough) {
  const vrml::ParsedWorld world = parse_world(
      "PROTO Inner [ field SFFloat size 1 ] { Sphere { radius IS size } }\n"
      "PROTO Outer [ field SFFloat big 3 ] { Shape { geometry Inner { size IS big } } }\n"
      "Outer {}\nOuter { big 7 }\n");
  ASSERT_EQ(world.roots.size(), 2u);
  EXPECT_EQ(radius(*world.roots[0]), 3);
  EXPECT_EQ(radius(*world.roots[1]), 7);
}

TEST(VrmlParser, ExternProtoOfAnUnreadableUrlIsLeftOutWithAWarning) {
  const std::string text =
      "EXTERNPROTO Tree [ field SFFloat height ] [ \"trees.wrl#Tree\" \"http://x.org/t.wrl\" ]\n"
      "Tree { height 4 }\nGroup {}\n";
  const vrml::ParsedWorld world = parse_world(text);
  ASSERT_EQ(world.roots.size(), 1u);
  ASSERT_EQ(world.warnings.size(), 1u);
  EXPECT_EQ(world.warnings[0],
            "world.wrl:2:1: EXTERNPROTO 'Tree': the url scheme of 'http://x.org/t.wrl' is not "
            "read (the loader fetches nothing): its instances are left out");
  EXPECT_THROW(parse_world(text, strict_budget()), SceneError);
}

TEST(VrmlParser, ExternProtoOfABuiltInUrnIsThatNode) {
  const vrml::ParsedWorld world = parse_world(
      "EXTERNPROTO Ball [ field SFFloat radius ] \"urn:web3d:vrml97:node:Sphere\"\n"
      "Ball { radius 4 }\n");
  ASSERT_EQ(world.roots.size(), 1u);
  EXPECT_EQ(world.roots[0]->type, "Sphere");
  EXPECT_EQ(world.roots[0]->field("radius")->numbers, std::vector<double>{4});
  EXPECT_TRUE(world.warnings.empty());
}

TEST(VrmlParser, ExternProtoNamesAProtoOfTheSameFile) {
  const vrml::ParsedWorld world = parse_world(
      "PROTO Big [ field SFFloat r 9 ] { Sphere { radius IS r } }\n"
      "EXTERNPROTO Alias [ field SFFloat r ] \"#Big\"\nAlias {}\n");
  ASSERT_EQ(world.roots.size(), 1u);
  EXPECT_EQ(world.roots[0]->field("radius")->numbers, std::vector<double>{9});
}

TEST(VrmlParser, FieldsAndNodesOutsideVrml97AreLeftOutWithAWarning) {
  const vrml::ParsedWorld world = parse_world(
      "Shape { appearance Appearance { material Material { diffuseColor 1 0 0 } }\n"
      "  shadows TRUE blendMode BlendMode { srcFactor \"one\" } geometry Sphere { radius 2 } }\n"
      "InlineLoadControl { url \"x.wrl\" }\n"
      "DEF B Box3D { size 1 2 3 }\nTransform { children USE B }\n"
      "Sphere { alphaChannel \"AUTO\" autoCenter 1 2 3 radius 5 }\n");
  ASSERT_EQ(world.roots.size(), 3u);  // the Shape, the Transform, the Sphere
  EXPECT_EQ(world.roots[0]->field("geometry")->nodes[0]->field("radius")->numbers,
            std::vector<double>{2});
  EXPECT_EQ(world.roots[2]->field("radius")->numbers, std::vector<double>{5});
  EXPECT_EQ(world.warnings,
            (std::vector<std::string>{
                "world.wrl:3:3: unknown field 'shadows' of Shape",
                "world.wrl:3:16: unknown field 'blendMode' of Shape",
                "world.wrl:3:26: unknown node type 'BlendMode'",  // its value, skipped
                "world.wrl:4:1: unknown node type 'InlineLoadControl'",
                "world.wrl:5:7: unknown node type 'Box3D'",
                "world.wrl:7:10: unknown field 'alphaChannel' of Sphere",
                "world.wrl:7:30: unknown field 'autoCenter' of Sphere",
            }));
}

TEST(VrmlParser, AScriptMayUseTheNodeItIsDefinedAs) {
  const vrml::ParsedWorld world =
      parse_world("DEF S Script { field SFNode self USE S directOutput TRUE }\nGroup {}\n");
  EXPECT_EQ(world.ignored, (std::map<std::string, int>{{"Script", 1}}));
  EXPECT_TRUE(
      world_fails_at("DEF T Transform { children USE T }", 2, 32, "node 'T' is not DEFined"));
}

TEST(VrmlParser, NonVisualNodesAndRoutesAreCounted) {
  const vrml::ParsedWorld world = parse_world(
      "DEF Clock TimeSensor { cycleInterval 4 loop TRUE }\n"
      "DEF Mover PositionInterpolator { key [0 1] keyValue [0 0 0, 1 1 1] }\n"
      "DEF S Script { field SFNode target USE Clock eventIn SFFloat set_fraction\n"
      "               url \"javascript: function set_fraction(f) {}\" }\n"
      "DEF T Transform { children Text { string \"hi\" } }\n"
      "ROUTE Clock.fraction_changed TO Mover.set_fraction\n"
      "ROUTE Mover.value_changed TO T.set_translation\n");
  ASSERT_EQ(world.roots.size(), 1u);
  EXPECT_EQ(world.ignored,
            (std::map<std::string, int>{
                {"PositionInterpolator", 1}, {"ROUTE", 2}, {"Script", 1}, {"TimeSensor", 1}}));
  EXPECT_EQ(world.unsupported, (std::map<std::string, int>{{"Text", 1}}));
}

TEST(VrmlParser, ErrorsNameFileLineAndColumn) {
  EXPECT_TRUE(world_fails_at("Sphere { radius 1 colour 2 }", 2, 19,
                             "unknown field 'colour' of Sphere", strict_budget()));
  EXPECT_TRUE(
      world_fails_at("Frobnicator {}", 2, 1, "unknown node type 'Frobnicator'", strict_budget()));
  EXPECT_TRUE(world_fails_at("Sphere { radius big }", 2, 17,
                             "expected a number for radius of Sphere, found 'big'"));
  EXPECT_TRUE(world_fails_at("Transform { translation 1 2 }", 2, 29,
                             "expected a number for translation of Transform, found '}'"));
  EXPECT_TRUE(world_fails_at("Group {\n  children [ Shape {}", 3, 22,
                             "unexpected end of file: expected a node"));
  EXPECT_TRUE(world_fails_at("Fog { fogType \"LINEAR }", 2, 15, "unterminated string"));
  EXPECT_TRUE(world_fails_at("Switch { whichChoice 1.5 }", 2, 22,
                             "expected a 32-bit integer for whichChoice of Switch, found '1.5'"));
  EXPECT_TRUE(world_fails_at("PROTO P [ field SFFloat r 1 ] { Sphere { radius IS q } }", 2, 52,
                             "'q' is not a field of PROTO 'P'"));
  EXPECT_TRUE(world_fails_at("PROTO P [ field SFFloat r 1 ] { Box { size IS r } }", 2, 39,
                             "'size' of Box has another type than the PROTO field it IS"));
  EXPECT_TRUE(world_fails_at("PROTO P [ field SFFloat r 1 ] { Sphere {} }\nP { s 2 }", 3, 5,
                             "unknown field 's' of PROTO 'P'", strict_budget()));
}

std::string gzip(const std::string& text) {
  z_stream stream{};
  EXPECT_EQ(deflateInit2(&stream, 9, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&stream, text.size()) + 32, '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  stream.avail_in = static_cast<uInt>(text.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&stream, Z_FINISH), Z_STREAM_END);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  return out;
}

TEST(VrmlParser, GzipStreamsAreInflated) {
  const std::string text = std::string(kVrmlHeader) + "Shape { geometry Sphere {} }\n";
  const std::string packed = gzip(text);
  ASSERT_EQ(static_cast<unsigned char>(packed[0]), 0x1f);
  LoadMeter meter{LoadBudget{}};
  EXPECT_EQ(vrml::vrml_text(packed, "w.wrl.gz", meter), text);
  EXPECT_EQ(meter.total(LoadLimit::BytesRead), text.size());  // inflated bytes are counted
  MemorySource source;
  source.add("w.wrl.gz", packed);
  EXPECT_EQ(load_vrml(source, "w.wrl.gz").objects.size(), 1u);
  LoadBudget small;
  small.max_bytes_read = 10;
  LoadMeter small_meter(small);
  EXPECT_THROW(vrml::vrml_text(packed, "w.wrl.gz", small_meter),
               LoadBudgetExceeded);  // inflates too far
  EXPECT_THROW(vrml::vrml_text(packed.substr(0, packed.size() / 2), "w.wrl.gz", meter),
               SceneError);  // truncated
}

}  // namespace
}  // namespace tessera::test

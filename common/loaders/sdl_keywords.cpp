// The SDL keywords of `002_…` §3.2-3.3 and what each does to the scene: one handler per
// keyword and one table (at the end) that maps every keyword to its handler.
#include <array>
#include <climits>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/loaders/lexical.h"
#include "common/loaders/polyhedra.h"
#include "common/loaders/sdl_parser.h"
#include "common/loaders/sdl_square.h"
#include "common/loaders/teapot.h"

namespace tessera::sdl {
namespace {

// ---------------------------------------------------------------------------------------------
// Transformations (§3.2.3): each post-multiplies the CT, so the last one written applies first.

void identity_affine(FileParser& p) { p.ct() = Affine::identity(); }

// <angle> <ux> <uy> <uz>, shared by rotate and mbRotate: an error at <ux> when the axis is
// zero, with `axis_hint` after the message.
struct AxisRotation {
  double degrees;
  Vec3 axis;
  Affine rotation;
};

AxisRotation read_rotation(FileParser& p, const char* axis_hint) {
  const double degrees = p.number("<angle>");
  const Number ux = p.read_number("<ux>");
  const Vec3 axis{ux.value, p.number("<uy>"), p.number("<uz>")};
  const std::optional<Affine> rotation = Affine::rotation(degrees, axis);
  if (!rotation)
    p.fail(ux.token, "'" + std::string(p.keyword_name()) + "' needs a non-zero axis" + axis_hint);
  return {degrees, axis, *rotation};
}

void rotate(FileParser& p) { p.ct() = p.ct() * read_rotation(p, " <ux> <uy> <uz>").rotation; }

void translate(FileParser& p) {
  p.ct() = p.ct() * Affine::translation(p.vec3("<dx>", "<dy>", "<dz>"));
}

void scale(FileParser& p) { p.ct() = p.ct() * Affine::scaling(p.vec3("<sx>", "<sy>", "<sz>")); }

void transform(FileParser& p) {
  // The three triples are the columns of the linear part: the images of the x, y and z axes.
  const Vec3 cx = p.vec3("<x1>", "<y1>", "<z1>");
  const Vec3 cy = p.vec3("<x2>", "<y2>", "<z2>");
  const Vec3 cz = p.vec3("<x3>", "<y3>", "<z3>");
  p.ct() = p.ct() * Affine::from_columns(cx, cy, cz);
}

void push(FileParser& p) { p.push_ct(); }
void pop(FileParser& p) { p.pop_ct(); }

// ---------------------------------------------------------------------------------------------
// Motion blur (§3.2.6): the next shape's motion over one frame. Each keyword sets its part
// (a second mbRotate replaces the first); the next shape takes the motion if mbEnable was
// given, and every shape clears it.

void mb_clear(FileParser& p) { p.motion() = {}; }

void mb_rotate(FileParser& p) {
  const AxisRotation r = read_rotation(p, "");
  p.motion().motion.angle_degrees = r.degrees;
  p.motion().motion.axis = r.axis;
}

void mb_translate(FileParser& p) { p.motion().motion.translation = p.vec3("<dx>", "<dy>", "<dz>"); }

void mb_scale(FileParser& p) {
  const double sx = p.number("<sx>", Range::Positive);
  const double sy = p.number("<sy>", Range::Positive);
  const double sz = p.number("<sz>", Range::Positive);
  p.motion().motion.scale = {sx, sy, sz};
}

void mb_enable(FileParser& p) { p.motion().enabled = true; }

// ---------------------------------------------------------------------------------------------
// Shapes (§3.3)

void sphere(FileParser& p) { p.add_object(Sphere{}); }
void cube(FileParser& p) { p.add_object(Cube{}); }

// Hill's SDL writes the tapered cylinders without the manual's <distort-texture> flag (the
// caps' texture mapping), which is then false.
bool distort_texture(FileParser& p) { return p.number_follows() && p.flag("<distort-texture>"); }

void cone(FileParser& p) { p.add_object(TaperedCylinder{0, distort_texture(p)}); }

void cylinder(FileParser& p) { p.add_object(TaperedCylinder{1, distort_texture(p)}); }

void tapered_cylinder(FileParser& p) {
  const double top_radius = p.number("<small-radius>", Range::NonNegative);
  p.add_object(TaperedCylinder{top_radius, distort_texture(p)});
}

// Hill's `torus` has no parameters: his generic torus has tube radius 0.2 and torus radius 1
// (the glutSolidTorus(0.2, 1.0, ...) his Torus class draws).
constexpr Torus kHillTorus{0.2, 1};

void torus(FileParser& p) {
  if (!p.number_follows()) {
    p.add_object(kHillTorus);
    return;
  }
  const double tube_radius = p.number("<tube-radius>", Range::Positive);
  const double torus_radius = p.number("<torus-radius>", Range::Positive);
  p.add_object(Torus{tube_radius, torus_radius});
}

// Hill's generic square: [-1, 1]² in the plane z = 0, facing +z.
void square(FileParser& p) { p.add_object(MeshShape{p.built_in_mesh(hill_square_mesh), false}); }

// Algebraic surfaces (§3.3.6): the box extent's width, height and depth.
template <AlgebraicKind kind>
void algebraic_surface(FileParser& p) {
  const double width = p.number("<box-extent-width>", Range::Positive);
  const double height = p.number("<box-extent-height>", Range::Positive);
  const double depth = p.number("<box-extent-depth>", Range::Positive);
  p.add_object(AlgebraicSurface{kind, {width, height, depth}});
}

void mesh(FileParser& p) {
  const Token name = p.word("a file name for <filename> of 'mesh'");
  // Hill's `mesh <filename>` shades with the normals the file gives (or, for 3DM, that its
  // faces give), as his Mesh class draws them.
  const bool interpolate = !p.number_follows() || p.flag("<interpolate-normals>");
  p.add_object(MeshShape{p.mesh(name), interpolate});
}

// Polyhedra (§3.3.1): flat-shaded meshes of convex polygons.
template <Polyhedron kind>
void polyhedron(FileParser& p) {
  p.add_object(MeshShape{p.built_in_mesh([] { return polyhedron_mesh(kind); }), false});
}

// The Utah teapot (§3.3.3): a mesh shipped with the program, Phong-shaded.
void teapot(FileParser& p) { p.add_object(MeshShape{p.built_in_mesh(teapot_mesh), true}); }

// ---------------------------------------------------------------------------------------------
// Material properties (§3.2.5): they set the current material of every following shape.

void default_materials(FileParser& p) { p.material() = Material{}; }

void surface_roughness(FileParser& p) {
  p.material().surface_roughness = p.number("<value>", Range::NonNegative);
}
void emissive(FileParser& p) { p.material().emissive = p.color("<red>", "<green>", "<blue>"); }
void ambient(FileParser& p) { p.material().ambient = p.color("<red>", "<green>", "<blue>"); }
void diffuse(FileParser& p) { p.material().diffuse = p.color("<red>", "<green>", "<blue>"); }
void specular(FileParser& p) { p.material().specular = p.color("<red>", "<green>", "<blue>"); }
void specular_exponent(FileParser& p) {
  p.material().specular_exponent = p.number("<value>", Range::NonNegative);
}
void light_back_faces(FileParser& p) { p.material().light_back_faces = p.flag("<value>"); }
void reflectivity(FileParser& p) {
  p.material().reflectivity = p.number("<value>", Range::UnitInterval);
}
void gloss_strength(FileParser& p) {
  p.material().gloss_strength = p.number("<value>", Range::NonNegative);
}
void transparency(FileParser& p) {
  p.material().transparency = p.number("<value>", Range::UnitInterval);
}
void translucency_strength(FileParser& p) {
  p.material().translucency_strength = p.number("<value>", Range::NonNegative);
}
void priority(FileParser& p) { p.material().priority = p.integer("<value>", 1, INT_MAX); }
void speed_of_light(FileParser& p) {
  p.material().speed_of_light = p.number("<value>", Range::Positive);
}
void retain_ambient_color(FileParser& p) { p.material().retain_ambient_color = p.flag("<value>"); }
void retain_diffuse_color(FileParser& p) { p.material().retain_diffuse_color = p.flag("<value>"); }
void retain_specular_reflection(FileParser& p) {
  p.material().retain_specular_reflection = p.flag("<value>");
}
void disable_refraction(FileParser& p) { p.material().disable_refraction = p.flag("<value>"); }

// ---------------------------------------------------------------------------------------------
// Textures (§3.2.8)

struct TextureParam {
  const char* name;
  int choices = 0;  // > 0: an integer in [0, choices); 0: any number
};

// The parameters of solid texture types 0-9, as the manual lists them.
const std::array<std::vector<TextureParam>, 10>& solid_texture_params() {
  static const std::array<std::vector<TextureParam>, 10> params{{
      {},                                             // 0: none
      {{"<scale-x>"}, {"<scale-y>"}, {"<scale-z>"}},  // 1: checkerboard
      {{"<scale-x>"}, {"<scale-y>"}, {"<scale-z>"}},  // 2: stacked colour bars
      {{"<scale-x>"}, {"<scale-y>"}, {"<scale-z>"}},  // 3: RGB cubes
      {{"<coordinate>", 3}, {"<scale>"}},             // 4: contours of one coordinate
      {{"<coordinates>", 3}, {"<distance-measure>", 4}, {"<scale-1>"}, {"<scale-2>"}},  // 5
      {{"<distance-measure>", 2}, {"<scale-x>"}, {"<scale-y>"}, {"<scale-z>"}},         // 6
      {{"<ring-thickness>"},
       {"<wobble-strength>"},
       {"<wobbles>"},
       {"<twist-strength>"},
       {"<red-1>"},
       {"<green-1>"},
       {"<blue-1>"},
       {"<red-2>"},
       {"<green-2>"},
       {"<blue-2>"},
       {"<smooth>"}},  // 7: wood grain
      {{"<coordinate>", 3},
       {"<turbulence>"},
       {"<red-weight>"},
       {"<green-weight>"},
       {"<blue-weight>"}},  // 8: marble
      {{"<threshold>"}},    // 9: cow spots
  }};
  return params;
}

// The parameters of procedural (flat) texture types 0-2.
const std::array<std::vector<TextureParam>, 3>& procedural_texture_params() {
  static const std::array<std::vector<TextureParam>, 3> params{{
      {},                              // 0: none
      {{"<tiles-s>"}, {"<tiles-t>"}},  // 1: checkerboard
      {{"<inside-red>"},
       {"<inside-green>"},
       {"<inside-blue>"},
       {"<outside-red>"},
       {"<outside-green>"},
       {"<outside-blue>"}},  // 2: radial colours
  }};
  return params;
}

std::vector<double> texture_params(FileParser& p, const std::vector<TextureParam>& specs) {
  std::vector<double> values;
  for (const TextureParam& spec : specs) {
    values.push_back(spec.choices > 0 ? p.integer(spec.name, 0, spec.choices - 1)
                                      : p.number(spec.name));
  }
  return values;
}

void solid_texture(FileParser& p) {
  const int type = p.integer("<type>", 0, 9);
  SolidTexture texture;
  texture.type = type;
  texture.params = texture_params(p, solid_texture_params()[static_cast<std::size_t>(type)]);
  p.material().solid_texture = std::move(texture);
}

// An object has an image or a procedural texture, not both: each replaces the other. The
// offsets of flatTextureOffset are kept.
void image_texture(FileParser& p) {
  const Token name = p.word("a file name for <filename> of 'imageTexture'");
  const std::string path = p.resolve(name);
  const bool decal = !p.flag("<method>");
  const double tile_s = p.number("<tile-s>", Range::Positive);
  const double tile_t = p.number("<tile-t>", Range::Positive);
  p.image(path, name);  // read now, so that the file travels in the scene's bundle
  FlatTexture& texture = p.material().flat_texture;
  texture.kind = FlatTexture::Kind::Image;
  texture.image_file = path;
  texture.procedural_type = 0;
  texture.params.clear();
  texture.decal = decal;
  texture.tile_s = tile_s;
  texture.tile_t = tile_t;
}

void procedural_texture(FileParser& p) {
  const int type = p.integer("<type>", 0, 2);
  const bool decal = !p.flag("<method>");
  std::vector<double> params =
      texture_params(p, procedural_texture_params()[static_cast<std::size_t>(type)]);
  FlatTexture& texture = p.material().flat_texture;
  texture.kind = type == 0 ? FlatTexture::Kind::None : FlatTexture::Kind::Procedural;
  texture.image_file.clear();
  texture.procedural_type = type;
  texture.params = std::move(params);
  texture.decal = decal;
  texture.tile_s = 1;
  texture.tile_t = 1;
}

void flat_texture_offset(FileParser& p) {
  const double s = p.number("<s-offset>", Range::UnitInterval);
  const double t = p.number("<t-offset>", Range::UnitInterval);
  p.material().flat_texture.offset_s = s;
  p.material().flat_texture.offset_t = t;
}

// Keywords of Hill's SDL that this renderer has no counterpart for (his textures, his
// Cook-Torrance share): read and checked as his Scene::getObject reads them, then ignored with a
// warning, so that his scenes render (untextured).
void hill_ignored(FileParser& p, const char* reason) {
  p.warn("Hill's '" + std::string(p.keyword_name()) + "' is ignored: " + reason);
}

constexpr const char* kOwnTextures = "Tessera has its own textures (solidTexture, imageTexture)";

void hill_texture(FileParser& p) {
  p.number("<type>");
  hill_ignored(p, kOwnTextures);
}

void hill_parameters(FileParser& p) {
  const int count = p.integer("<count>", 0, 10);  // his Material holds ten
  for (int i = 0; i < count; ++i) p.number("<parameter>");
  hill_ignored(p, kOwnTextures);
}

void hill_make_pixmap(FileParser& p) {
  p.integer("<index>", 0, 7);  // his Scene holds eight pixmaps
  p.word("a file name for <filename> of 'makePixmap'");
  hill_ignored(p, kOwnTextures);
}

void hill_specular_fraction(FileParser& p) {
  p.number("<value>", Range::UnitInterval);
  hill_ignored(p, "Tessera shades with Phong's model, not Cook-Torrance's");
}

// ---------------------------------------------------------------------------------------------
// Lights (§3.2.2), in world coordinates: the CT does not apply to them.

void light(FileParser& p) {
  Light l;
  l.position = p.vec3("<px>", "<py>", "<pz>");
  l.color = p.color("<red>", "<green>", "<blue>");
  p.add_light(l);
}

void spotlight(FileParser& p) {
  Light l;
  l.position = p.vec3("<px>", "<py>", "<pz>");
  l.color = p.color("<red>", "<green>", "<blue>");
  const Number dx = p.read_number("<dx>");
  const double dy = p.number("<dy>");
  const double dz = p.number("<dz>");
  const Vec3 direction = unit_or_zero({dx.value, dy, dz});
  if (direction == Vec3{})
    p.fail(dx.token, "'spotlight' needs a non-zero direction <dx> <dy> <dz>");
  l.is_spot = true;
  l.spot.direction = direction;
  l.spot.cutoff_degrees = p.number("<cut-off angle>", Range::Cutoff);
  l.spot.exponent = p.number("<exponent>", Range::NonNegative);
  p.add_light(l);
}

// ---------------------------------------------------------------------------------------------
// Global scene attributes (§3.2.7). Only the top-level file sets them: each handler reads its
// parameters, then applies them if accept_global() agrees.

void eye_point(FileParser& p) {
  const Vec3 eye = p.vec3("<x>", "<y>", "<z>");
  if (!p.accept_global()) return;
  p.scene().camera.eye = eye;
  p.note_camera_position();
}

void view_point(FileParser& p) {
  const Vec3 look_at = p.vec3("<x>", "<y>", "<z>");
  if (!p.accept_global()) return;
  p.scene().camera.look_at = look_at;
  p.note_camera_position();
}

void view_angle(FileParser& p) {
  const double angle = p.number("<value>", Range::OpenAngle);
  if (p.accept_global()) p.scene().camera.view_angle = angle;
}

void up_direction(FileParser& p) {
  const Vec3 up = p.vec3("<dx>", "<dy>", "<dz>");
  if (!p.accept_global()) return;
  p.scene().camera.up = up;
  p.note_up_direction();
}

void background(FileParser& p) {
  const Rgb c = p.color("<red>", "<green>", "<blue>");
  if (p.accept_global()) p.scene().globals.background = c;
}

void global_ambient(FileParser& p) {
  const Rgb c = p.color("<red>", "<green>", "<blue>");
  if (p.accept_global()) p.scene().globals.global_ambient = c;
}

void light_attenuation(FileParser& p) {
  LightAttenuation a;
  a.constant = p.number("<constant-factor>", Range::NonNegative);
  a.linear = p.number("<linear-factor>", Range::NonNegative);
  a.quadratic = p.number("<quadratic-factor>", Range::NonNegative);
  if (a.constant == 0 && a.linear == 0 && a.quadratic == 0) {
    p.fail(p.keyword(), "'lightAttenuation' needs at least one non-zero factor");
  }
  if (p.accept_global()) p.scene().globals.light_attenuation = a;
}

void atmospheric_attenuation(FileParser& p) {
  AtmosphericAttenuation a;
  const Number front = p.read_number("<front-plane>");
  a.front_distance = front.value;
  a.front_scale = p.number("<front-scale>", Range::UnitInterval);
  const Number back = p.read_number("<back-plane>");
  a.back_distance = back.value;
  a.back_scale = p.number("<back-scale>", Range::UnitInterval);
  a.color = p.color("<red>", "<green>", "<blue>");
  if (a.back_distance == a.front_distance) {
    p.fail(back.token, "'atmosphericAttenuation' needs <back-plane> different from <front-plane>");
  }
  if (p.accept_global()) p.scene().globals.atmospheric_attenuation = a;
}

void fog(FileParser& p) {
  Fog f;
  f.start = p.number("<fog-start>");
  const Number end = p.read_number("<fog-end>");
  f.end = end.value;
  f.color = p.color("<red>", "<green>", "<blue>");
  if (f.end == f.start) p.fail(end.token, "'fog' needs <fog-end> different from <fog-start>");
  if (p.accept_global()) p.scene().globals.fog = f;
}

void shadow_feeler_epsilon(FileParser& p) {
  const double v = p.number("<value>", Range::NonNegative);
  if (p.accept_global()) p.scene().globals.shadow_feeler_epsilon = v;
}
void reflectivity_epsilon(FileParser& p) {
  const double v = p.number("<value>", Range::NonNegative);
  if (p.accept_global()) p.scene().globals.reflectivity_epsilon = v;
}
void transparency_epsilon(FileParser& p) {
  const double v = p.number("<value>", Range::NonNegative);
  if (p.accept_global()) p.scene().globals.transparency_epsilon = v;
}
void mesh_epsilon(FileParser& p) {
  const double v = p.number("<value>", Range::NonNegative);
  if (p.accept_global()) p.scene().globals.mesh_epsilon = v;
}
void adapted_shadow_computation(FileParser& p) {
  const bool v = p.flag("<value>");
  if (p.accept_global()) p.scene().globals.adapted_shadow_computation = v;
}
void min_reflectivity(FileParser& p) {
  const double v = p.number("<value>", Range::UnitInterval);
  if (p.accept_global()) p.scene().globals.min_reflectivity = v;
}
void min_transparency(FileParser& p) {
  const double v = p.number("<value>", Range::UnitInterval);
  if (p.accept_global()) p.scene().globals.min_transparency = v;
}
void max_recursion_depth(FileParser& p) {
  const int v = p.integer("<value>", 0, INT_MAX);
  if (p.accept_global()) p.scene().globals.max_recursion_depth = v;
}
void show_extents(FileParser& p) {
  const bool v = p.flag("<value>");
  if (p.accept_global()) p.scene().globals.show_extents = v;
}
void motion_blur(FileParser& p) {
  const double frame_length = p.number("<frame-length>", Range::NonNegative);
  const int samples = p.integer("<#time-samples>", 1, kMaxTimeSamples);
  if (!p.accept_global()) return;
  p.scene().globals.motion_blur_frame_length = frame_length;
  p.scene().globals.motion_blur_time_samples = samples;
}

// ---------------------------------------------------------------------------------------------
// Macros (§3.2.9) and includes (§3.2.10)

void def(FileParser& p) { p.define(); }
void use(FileParser& p) { p.use(); }
void include(FileParser& p) { p.include(p.word("a file name after 'include'")); }

// ---------------------------------------------------------------------------------------------
// Boolean objects (§3.2.4): each takes the next two objects as its children.

template <CsgOperation operation>
void boolean_object(FileParser& p) {
  p.begin_csg(operation);
}

// ---------------------------------------------------------------------------------------------
// The table: every keyword and its handler.

constexpr Keyword kKeywords[] = {
    // Transformations
    {"identityAffine", identity_affine},
    {"rotate", rotate},
    {"translate", translate},
    {"scale", scale},
    {"transform", transform},
    {"push", push},
    {"pop", pop},
    // Boolean objects
    {"union", boolean_object<CsgOperation::Union>},
    {"intersection", boolean_object<CsgOperation::Intersection>},
    {"difference", boolean_object<CsgOperation::Difference>},
    // Shapes
    {"sphere", sphere},
    {"cube", cube},
    {"square", square},
    {"cone", cone},
    {"cylinder", cylinder},
    {"taperedCylinder", tapered_cylinder},
    {"mesh", mesh},
    {"teapot", teapot},
    {"torus", torus},
    {"buckyball", polyhedron<Polyhedron::Buckyball>},
    {"diamond", polyhedron<Polyhedron::Diamond>},
    {"dodecahedron", polyhedron<Polyhedron::Dodecahedron>},
    {"icosahedron", polyhedron<Polyhedron::Icosahedron>},
    {"octahedron", polyhedron<Polyhedron::Octahedron>},
    {"pyramid", polyhedron<Polyhedron::Pyramid>},
    {"tetrahedron", polyhedron<Polyhedron::Tetrahedron>},
    {"oneSheetHyperboloid", algebraic_surface<AlgebraicKind::OneSheetHyperboloid>},
    {"twoSheetHyperboloid", algebraic_surface<AlgebraicKind::TwoSheetHyperboloid>},
    {"ellipticCylinder", algebraic_surface<AlgebraicKind::EllipticCylinder>},
    {"ellipticCone", algebraic_surface<AlgebraicKind::EllipticCone>},
    {"ellipticParaboloid", algebraic_surface<AlgebraicKind::EllipticParaboloid>},
    {"hyperbolicParaboloid", algebraic_surface<AlgebraicKind::HyperbolicParaboloid>},
    {"pinchedSurfaceWithHoles", algebraic_surface<AlgebraicKind::PinchedSurfaceWithHoles>},
    {"pinchedSurfaceWithLobe", algebraic_surface<AlgebraicKind::PinchedSurfaceWithLobe>},
    {"fourLobes", algebraic_surface<AlgebraicKind::FourLobes>},
    {"steinersRomanSurface", algebraic_surface<AlgebraicKind::SteinersRomanSurface>},
    {"toothCube", algebraic_surface<AlgebraicKind::ToothCube>},
    // Material properties
    {"defaultMaterials", default_materials},
    {"surfaceRoughness", surface_roughness},
    {"emissive", emissive},
    {"ambient", ambient},
    {"diffuse", diffuse},
    {"specular", specular},
    {"specularExponent", specular_exponent},
    {"lightBackFaces", light_back_faces},
    {"reflectivity", reflectivity},
    {"glossStrength", gloss_strength},
    {"transparency", transparency},
    {"translucencyStrength", translucency_strength},
    {"priority", priority},
    {"speedOfLight", speed_of_light},
    {"retainAmbientColor", retain_ambient_color},
    {"retainDiffuseColor", retain_diffuse_color},
    {"retainSpecularReflection", retain_specular_reflection},
    {"disableRefraction", disable_refraction},
    // Textures
    {"solidTexture", solid_texture},
    {"imageTexture", image_texture},
    {"proceduralTexture", procedural_texture},
    {"flatTextureOffset", flat_texture_offset},
    // Hill's texture keywords, read and ignored
    {"texture", hill_texture},
    {"parameters", hill_parameters},
    {"makePixmap", hill_make_pixmap},
    {"specularFraction", hill_specular_fraction},
    // Lights
    {"light", light},
    {"spotlight", spotlight},
    // Motion blur
    {"mbClear", mb_clear},
    {"mbRotate", mb_rotate},
    {"mbTranslate", mb_translate},
    {"mbScale", mb_scale},
    {"mbEnable", mb_enable},
    // Global scene attributes
    {"eyePoint", eye_point},
    {"viewPoint", view_point},
    {"viewAngle", view_angle},
    {"upDirection", up_direction},
    {"background", background},
    {"globalAmbient", global_ambient},
    {"lightAttenuation", light_attenuation},
    {"atmosphericAttenuation", atmospheric_attenuation},
    {"fog", fog},
    {"shadowFeelerEpsilon", shadow_feeler_epsilon},
    {"reflectivityEpsilon", reflectivity_epsilon},
    {"transparencyEpsilon", transparency_epsilon},
    {"meshEpsilon", mesh_epsilon},
    {"adaptedShadowComputation", adapted_shadow_computation},
    {"minReflectivity", min_reflectivity},
    {"minTransparency", min_transparency},
    {"maxRecursionDepth", max_recursion_depth},
    {"showExtents", show_extents},
    {"motionBlur", motion_blur},
    // Macros and includes
    {"def", def},
    {"use", use},
    {"include", include},
};

constexpr bool names_fit(std::size_t limit) {
  for (const Keyword& keyword : kKeywords) {
    if (keyword.name.size() > limit) return false;
  }
  return true;
}
static_assert(names_fit(32), "find_keyword lower-cases names into a 32-character buffer");

}  // namespace

const Keyword* find_keyword(std::string_view name) {
  // Lower-case names of the table, and the table entries by them.
  static const std::vector<std::string> lower_names = [] {
    std::vector<std::string> names;
    for (const Keyword& keyword : kKeywords) names.push_back(to_lower(keyword.name));
    return names;
  }();
  static const std::unordered_map<std::string_view, const Keyword*> by_name = [] {
    std::unordered_map<std::string_view, const Keyword*> map;
    for (std::size_t i = 0; i < lower_names.size(); ++i) map.emplace(lower_names[i], &kKeywords[i]);
    return map;
  }();
  // Lower-case into a small buffer: no keyword is longer, so a longer word is no keyword.
  std::array<char, 32> buffer;
  if (name.size() > buffer.size()) return nullptr;
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char c = name[i];
    buffer[i] = c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
  }
  const auto found = by_name.find(std::string_view(buffer.data(), name.size()));
  return found == by_name.end() ? nullptr : found->second;
}

}  // namespace tessera::sdl

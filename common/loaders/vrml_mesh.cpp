#include "common/loaders/vrml_mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/loaders/vrml_fields.h"
#include "common/math/portable_math.h"

namespace tessera::vrml {
namespace {

// Polygons with more corners than this are fanned when the file says they are convex: ear
// clipping is quadratic in the corners.
constexpr std::size_t kMaxClippedCorners = 256;

std::vector<Vec3> vectors(const std::vector<double>& numbers) {
  std::vector<Vec3> out(numbers.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = {numbers[3 * i], numbers[3 * i + 1], numbers[3 * i + 2]};
  return out;
}

// Newell's normal: twice the polygon's vector area, robust for non-planar polygons.
Vec3 newell_normal(const std::vector<Vec3>& polygon) {
  Vec3 n;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % polygon.size()];
    n += Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  return n;
}

struct Point2 {
  double u = 0, v = 0;
};

double cross2(const Point2& a, const Point2& b, const Point2& c) {
  return (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u);
}

// A polygon: its corners' position indices and each corner's normal index, colour and
// texture coordinate (each list empty when the mesh has none).
struct Polygon {
  std::vector<std::uint32_t> positions;
  std::vector<std::uint32_t> normals;
  std::vector<Rgb> colours;
  std::vector<TexCoord> tex_coords;
};

[[noreturn]] void index_out_of_range(const FieldValue& field, const char* name, double index,
                                     std::size_t count, const char* what) {
  throw SceneError(field.where, std::string(name) + " " +
                                    std::to_string(static_cast<long long>(index)) +
                                    " is out of range: the " + what + " has " +
                                    std::to_string(count) + " entries");
}

// Where a corner finds its entry in a list of normals, colours or texture coordinates
// (§6.23): through the list's own index field (normalIndex, ...) when it is not empty, laid
// out like coordIndex per vertex or one entry per face; otherwise by the corner's coordinate
// index per vertex, or the face's number per face.
class AttributeIndex {
 public:
  AttributeIndex(const Node& face_set, const char* index_field, const FieldValue& coord_index,
                 bool per_vertex, std::size_t count, const char* list)
      : index_(face_set.field(index_field)),
        coord_index_(coord_index),
        name_(index_field),
        list_(list),
        per_vertex_(per_vertex),
        count_(count) {}

  // The entry of the corner at `slot` of coordIndex, which names `vertex`, on face `face`.
  std::uint32_t at(std::size_t slot, std::size_t face, std::uint32_t vertex) const {
    const std::size_t key = per_vertex_ ? slot : face;
    double index = per_vertex_ ? vertex : static_cast<double>(face);
    if (index_ && key < index_->numbers.size()) index = index_->numbers[key];
    if (index < 0 || index >= static_cast<double>(count_))
      index_out_of_range(index_ ? *index_ : coord_index_, name_, index, count_, list_);
    return static_cast<std::uint32_t>(index);
  }

 private:
  const FieldValue* index_;
  const FieldValue& coord_index_;
  const char* name_;
  const char* list_;
  bool per_vertex_;
  std::size_t count_;
};

std::vector<TexCoord> tex_coords(const std::vector<double>& numbers) {
  std::vector<TexCoord> out(numbers.size() / 2);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {numbers[2 * i], numbers[2 * i + 1]};
  return out;
}

// §6.23's default texture mapping: s from 0 to 1 along the bounding box's longest side, t
// from 0 along the second longest, at the same scale (ties go to x, then y, then z).
std::vector<TexCoord> default_tex_coords(const std::vector<Vec3>& positions) {
  if (positions.empty()) return {};
  Vec3 lo = positions.front(), hi = lo;
  for (const Vec3& p : positions) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  const Vec3 size = hi - lo;
  std::array<int, 3> axes{0, 1, 2};
  std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return size[a] > size[b]; });
  const int s = axes[0], t = axes[1];
  const double scale = size[s] > 0 ? 1 / size[s] : 0;
  std::vector<TexCoord> out;
  out.reserve(positions.size());
  for (const Vec3& p : positions) out.push_back({(p[s] - lo[s]) * scale, (p[t] - lo[t]) * scale});
  return out;
}

// A TextureCoordinate node holding `points` (s t pairs).
NodePtr tex_coord_node(const Node& from, std::vector<double> points) {
  auto out = std::make_shared<Node>();
  out->type = "TextureCoordinate";
  out->where = from.where;
  out->fields["point"] = {FieldType::MFVec2f, std::move(points), {}, {}, from.where};
  return out;
}

// A face set node with the given points and polygons and the fields `from` shares with face
// sets (an ElevationGrid's normals, colours and texture coordinates are indexed like the
// face set's vertices and faces).
std::shared_ptr<Node> face_set(const Node& from, std::vector<double> points,
                               std::vector<double> indices) {
  auto coord = std::make_shared<Node>();
  coord->type = "Coordinate";
  coord->where = from.where;
  coord->fields["point"] = {FieldType::MFVec3f, std::move(points), {}, {}, from.where};
  auto out = std::make_shared<Node>();
  out->type = "IndexedFaceSet";
  out->where = from.where;
  out->fields["coord"] = {FieldType::SFNode, {}, {}, {coord}, from.where};
  out->fields["coordIndex"] = {FieldType::MFInt32, std::move(indices), {}, {}, from.where};
  for (const char* flag : {"ccw", "solid", "creaseAngle", "normal", "normalPerVertex", "color",
                           "colorPerVertex", "texCoord"})
    if (const FieldValue* v = from.field(flag)) out->fields[flag] = *v;
  return out;
}

// The fractions of a polyline's length at each of its points, from 0 to 1 (all 0 when it has
// no length).
template <typename Distance>
std::vector<double> length_fractions(std::size_t count, Distance&& distance) {
  std::vector<double> out(count, 0);
  for (std::size_t i = 1; i < count; ++i) out[i] = out[i - 1] + distance(i - 1, i);
  const double total = count > 0 ? out.back() : 0;
  for (double& f : out) f = total > 0 ? f / total : 0;
  return out;
}

// An Extrusion's default texture coordinates (§6.18.1): for the n x m points of the sides, s
// along the cross-section and t along the spine by length, then for the caps, the
// cross-section's points with its larger side (x or z) scaled to [0, 1].
std::vector<double> extrusion_tex_coords(const std::vector<std::array<double, 2>>& section,
                                         const std::vector<Vec3>& spine) {
  const std::vector<double> s = length_fractions(section.size(), [&](std::size_t a, std::size_t b) {
    return std::hypot(section[b][0] - section[a][0], section[b][1] - section[a][1]);
  });
  const std::vector<double> t = length_fractions(
      spine.size(), [&](std::size_t a, std::size_t b) { return length(spine[b] - spine[a]); });
  std::vector<double> out;
  for (const double ti : t)
    for (const double sk : s) out.insert(out.end(), {sk, ti});
  std::array<double, 2> lo = section.front(), hi = lo;
  for (const auto& p : section)
    for (int a = 0; a < 2; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  const double side = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  const double scale = side > 0 ? 1 / side : 0;
  for (const auto& [x, z] : section)
    out.insert(out.end(), {(x - lo[0]) * scale, (z - lo[1]) * scale});
  return out;
}

// The Extrusion's texCoordIndex: its sides' corners (before `side_indices`) index the side
// coordinates like coordIndex; a cap's corner k takes the caps' coordinate n m + k.
std::vector<double> extrusion_tex_indices(std::vector<double> indices, std::size_t side_indices,
                                          std::size_t n, std::size_t m) {
  for (std::size_t q = side_indices; q < indices.size(); ++q)
    if (indices[q] >= 0)
      indices[q] = static_cast<double>(n * m) + std::fmod(indices[q], static_cast<double>(m));
  return indices;
}

void add_quad(std::vector<double>& indices, std::size_t a, std::size_t b, std::size_t c,
              std::size_t d) {
  for (const std::size_t i : {a, b, c, d}) indices.push_back(static_cast<double>(i));
  indices.push_back(-1);
}

}  // namespace

NodePtr elevation_grid_face_set(const Node& grid) {
  const auto nx = static_cast<std::size_t>(std::max(sf_float(grid, "xDimension", 0), 0.0));
  const auto nz = static_cast<std::size_t>(std::max(sf_float(grid, "zDimension", 0), 0.0));
  const std::vector<double>& height = mf_numbers(grid, "height");
  if (height.size() < nx * nz)
    throw SceneError(grid.where, "ElevationGrid: height has " + std::to_string(height.size()) +
                                     " values for " + std::to_string(nx) + " x " +
                                     std::to_string(nz) + " points");
  const double dx = sf_float(grid, "xSpacing", 1), dz = sf_float(grid, "zSpacing", 1);
  std::vector<double> points, indices;
  for (std::size_t j = 0; j < nz; ++j)
    for (std::size_t i = 0; i < nx; ++i)
      points.insert(points.end(),
                    {static_cast<double>(i) * dx, height[i + j * nx], static_cast<double>(j) * dz});
  // Quads wound so that ccw TRUE faces +y.
  for (std::size_t j = 0; j + 1 < nz; ++j)
    for (std::size_t i = 0; i + 1 < nx; ++i)
      add_quad(indices, i + j * nx, i + (j + 1) * nx, i + 1 + (j + 1) * nx, i + 1 + j * nx);
  std::shared_ptr<Node> out = face_set(grid, std::move(points), std::move(indices));
  if (!sf_node(grid, "texCoord") && nx >= 2 && nz >= 2) {
    // The default texture coordinates: (0, 0) at the first point, (1, 1) at the last, s along
    // +x and t along +z.
    std::vector<double> st;
    for (std::size_t j = 0; j < nz; ++j)
      for (std::size_t i = 0; i < nx; ++i)
        st.insert(st.end(), {static_cast<double>(i) / static_cast<double>(nx - 1),
                             static_cast<double>(j) / static_cast<double>(nz - 1)});
    out->fields["texCoord"] = {
        FieldType::SFNode, {}, {}, {tex_coord_node(grid, std::move(st))}, grid.where};
  }
  return out;
}

NodePtr extrusion_face_set(const Node& extrusion) {
  const auto pairs = [](const std::vector<double>& v) {
    std::vector<std::array<double, 2>> out(v.size() / 2);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = {v[2 * i], v[2 * i + 1]};
    return out;
  };
  const FieldValue* cross_field = extrusion.field("crossSection");
  const FieldValue* spine_field = extrusion.field("spine");
  const auto section = pairs(cross_field ? cross_field->numbers
                                         : std::vector<double>{1, 1, 1, -1, -1, -1, -1, 1, 1, 1});
  const std::vector<Vec3> spine =
      vectors(spine_field ? spine_field->numbers : std::vector<double>{0, 0, 0, 0, 1, 0});
  const auto scale = pairs(mf_numbers(extrusion, "scale"));
  const std::vector<double>& orientation = mf_numbers(extrusion, "orientation");
  const std::size_t n = spine.size(), m = section.size();
  std::vector<double> points, indices;
  if (n < 2 || m < 2) return face_set(extrusion, {}, {});

  // The spine-aligned cross-section plane at each spine point (§6.18.2): Y along the spine,
  // Z across the bend. An open spine's end points take their neighbours' Z; where the spine
  // runs straight, a point takes the Z of the nearest point before it that has one (at the
  // start, after it); a spine straight throughout takes the rotation of +y to Y.
  const bool closed = spine.front() == spine.back();
  std::vector<Vec3> ys(n), zs(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 prev = i > 0 ? spine[i - 1] : (closed ? spine[n - 2] : spine[0]);
    const Vec3 next = i + 1 < n ? spine[i + 1] : (closed ? spine[1] : spine[n - 1]);
    ys[i] = unit_or_zero(next - prev);
    zs[i] = unit_or_zero(cross(next - spine[i], prev - spine[i]));
  }
  if (!closed && n > 2) {
    zs[0] = zs[1];
    zs[n - 1] = zs[n - 2];
  }
  const auto bent = std::find_if(zs.begin(), zs.end(), [](const Vec3& z) { return z != Vec3{}; });
  Vec3 last_z = bent == zs.end() ? Vec3{0, 0, 1} : *bent;
  for (std::size_t i = 0; i < n; ++i) {
    Vec3& z = zs[i];
    if (bent == zs.end()) {
      if (const auto r = Affine::rotation(
              tessera::acos(std::clamp(ys[i].y, -1.0, 1.0)) * 180 / std::numbers::pi,
              cross({0, 1, 0}, ys[i])))
        z = r->apply_vector({0, 0, 1});
      else
        z = last_z;
    } else if (z == Vec3{}) {
      z = last_z;
    } else if (dot(z, last_z) < 0) {
      z = -z;  // keep the plane from flipping at an inflection
    }
    last_z = z;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& y = ys[i];
    const Vec3& z = zs[i];
    const Vec3 x = cross(y, z);
    const Affine plane = Affine::from_columns(x, y == Vec3{} ? Vec3{0, 1, 0} : y, z);
    Affine turn = Affine::identity();
    const std::size_t o = orientation.size() >= 4 * n ? 4 * i : 0;
    if (orientation.size() >= o + 4)
      turn = Affine::rotation(orientation[o + 3] * 180 / std::numbers::pi,
                              {orientation[o], orientation[o + 1], orientation[o + 2]})
                 .value_or(Affine::identity());
    const std::array<double, 2> s =
        scale.empty() ? std::array<double, 2>{1, 1} : scale[scale.size() >= n ? i : 0];
    for (const auto& [cx, cz] : section) {
      const Vec3 p = spine[i] + plane.apply_vector(turn.apply_vector({s[0] * cx, 0, s[1] * cz}));
      points.insert(points.end(), {p.x, p.y, p.z});
    }
  }
  for (std::size_t i = 0; i + 1 < n; ++i)
    for (std::size_t k = 0; k + 1 < m; ++k)
      add_quad(indices, i * m + k, i * m + k + 1, (i + 1) * m + k + 1, (i + 1) * m + k);
  const std::size_t side_indices = indices.size();
  // Caps: the cross-section without its closing point; the begin cap faces back.
  const std::size_t corners = section.front() == section.back() ? m - 1 : m;
  if (corners >= 3 && sf_bool(extrusion, "beginCap", true)) {
    for (std::size_t k = corners; k-- > 0;) indices.push_back(static_cast<double>(k));
    indices.push_back(-1);
  }
  if (corners >= 3 && sf_bool(extrusion, "endCap", true)) {
    for (std::size_t k = 0; k < corners; ++k)
      indices.push_back(static_cast<double>((n - 1) * m + k));
    indices.push_back(-1);
  }
  std::vector<double> tex_indices = extrusion_tex_indices(indices, side_indices, n, m);
  std::shared_ptr<Node> out = face_set(extrusion, std::move(points), std::move(indices));
  out->fields["texCoord"] = {FieldType::SFNode,
                             {},
                             {},
                             {tex_coord_node(extrusion, extrusion_tex_coords(section, spine))},
                             extrusion.where};
  out->fields["texCoordIndex"] = {
      FieldType::MFInt32, std::move(tex_indices), {}, {}, extrusion.where};
  return out;
}

std::uint64_t generated_triangles(const Node& node) {
  // In doubles, which cannot overflow here, then capped.
  double rows = 0, columns = 0, caps = 0;
  if (node.type == "ElevationGrid") {
    rows = sf_float(node, "xDimension", 0) - 1;
    columns = sf_float(node, "zDimension", 0) - 1;
  } else if (node.type == "Extrusion") {
    const FieldValue* spine = node.field("spine");
    const FieldValue* section = node.field("crossSection");
    rows = (spine ? static_cast<double>(spine->numbers.size() / 3) : 2) - 1;
    columns = (section ? static_cast<double>(section->numbers.size() / 2) : 5) - 1;
    caps = 2 * (columns + 1);
  }
  const double triangles = 2 * std::max(rows, 0.0) * std::max(columns, 0.0) + caps;
  return triangles >= 1e18 ? std::uint64_t{1'000'000'000'000'000'000}
                           : static_cast<std::uint64_t>(triangles);
}

std::vector<std::array<std::uint32_t, 3>> triangulate_polygon(const std::vector<Vec3>& polygon) {
  std::vector<std::array<std::uint32_t, 3>> out;
  if (polygon.size() < 3) return out;
  const Vec3 normal = newell_normal(polygon);
  const int axis = max_axis(abs(normal));
  const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
  const double sign = normal[axis] < 0 ? -1 : 1;  // so that the polygon turns positively
  std::vector<Point2> p(polygon.size());
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = {polygon[i][ua], polygon[i][va]};

  std::vector<std::uint32_t> left(polygon.size());
  for (std::uint32_t i = 0; i < left.size(); ++i) left[i] = i;
  const auto fan = [&] {
    for (std::size_t i = 1; i + 1 < left.size(); ++i)
      out.push_back({left[0], left[i], left[i + 1]});
  };
  if (polygon.size() > kMaxClippedCorners) {
    fan();
    return out;
  }
  while (left.size() > 3) {
    const std::size_t m = left.size();
    bool clipped = false;
    for (std::size_t i = 0; i < m && !clipped; ++i) {
      const std::uint32_t a = left[(i + m - 1) % m], b = left[i], c = left[(i + 1) % m];
      if (sign * cross2(p[a], p[b], p[c]) <= 0) continue;  // reflex or flat corner
      bool empty = true;
      for (const std::uint32_t k : left) {
        if (k == a || k == b || k == c) continue;
        if (sign * cross2(p[a], p[b], p[k]) >= 0 && sign * cross2(p[b], p[c], p[k]) >= 0 &&
            sign * cross2(p[c], p[a], p[k]) >= 0) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      out.push_back({a, b, c});
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped) break;
  }
  fan();
  return out;
}

FaceSetMesh face_set_mesh(const Node& face_set, CornerAttributes wanted) {
  FaceSetMesh out;
  Mesh& mesh = out.mesh;
  mesh.source = face_set.where.to_string();
  const Node* coord = sf_node(face_set, "coord");
  const FieldValue* coord_index = face_set.field("coordIndex");
  if (!coord || !coord_index) return out;
  mesh.positions = vectors(mf_numbers(*coord, "point"));

  const Node* normal_node = sf_node(face_set, "normal");
  if (normal_node) mesh.normals = vectors(mf_numbers(*normal_node, "vector"));
  const AttributeIndex normal_at(face_set, "normalIndex", *coord_index,
                                 sf_bool(face_set, "normalPerVertex", true), mesh.normals.size(),
                                 "Normal");

  const Node* colour_node = wanted.colours ? sf_node(face_set, "color") : nullptr;
  std::vector<Rgb> colours;
  if (colour_node) {
    const std::vector<Vec3> c = vectors(mf_numbers(*colour_node, "color"));
    for (const Vec3& v : c) colours.push_back({v.x, v.y, v.z});
  }
  const AttributeIndex colour_at(face_set, "colorIndex", *coord_index,
                                 sf_bool(face_set, "colorPerVertex", true), colours.size(),
                                 "Color");

  // Given texture coordinates are indexed per vertex; the default ones belong to the vertices.
  const Node* tex_coord_node = wanted.tex_coords ? sf_node(face_set, "texCoord") : nullptr;
  const std::vector<TexCoord> given_tex_coords =
      tex_coord_node ? tex_coords(mf_numbers(*tex_coord_node, "point")) : std::vector<TexCoord>{};
  const std::vector<TexCoord> vertex_tex_coords = wanted.tex_coords && !tex_coord_node
                                                      ? default_tex_coords(mesh.positions)
                                                      : std::vector<TexCoord>{};
  const AttributeIndex tex_coord_at(face_set, "texCoordIndex", *coord_index, true,
                                    given_tex_coords.size(), "TextureCoordinate");

  // Split coordIndex at -1 into polygons.
  std::vector<Polygon> polygons;
  Polygon current;
  std::size_t face = 0;  // faces counted as the file writes them, for per-face normals
  const std::vector<double>& indices = coord_index->numbers;
  for (std::size_t slot = 0; slot <= indices.size(); ++slot) {
    if (slot == indices.size() || indices[slot] == -1) {
      if (current.positions.size() >= 3) polygons.push_back(current);
      if (!current.positions.empty()) ++face;
      current = {};
      continue;
    }
    const double index = indices[slot];
    if (index < 0 || index >= static_cast<double>(mesh.positions.size()))
      index_out_of_range(*coord_index, "coordIndex", index, mesh.positions.size(), "Coordinate");
    const auto vertex = static_cast<std::uint32_t>(index);
    current.positions.push_back(vertex);
    if (normal_node) current.normals.push_back(normal_at.at(slot, face, vertex));
    if (colour_node) current.colours.push_back(colours[colour_at.at(slot, face, vertex)]);
    if (tex_coord_node)
      current.tex_coords.push_back(given_tex_coords[tex_coord_at.at(slot, face, vertex)]);
    if (!vertex_tex_coords.empty()) current.tex_coords.push_back(vertex_tex_coords[vertex]);
  }
  if (!sf_bool(face_set, "ccw", true)) {
    for (Polygon& polygon : polygons) {
      std::reverse(polygon.positions.begin(), polygon.positions.end());
      std::reverse(polygon.normals.begin(), polygon.normals.end());
      std::reverse(polygon.colours.begin(), polygon.colours.end());
      std::reverse(polygon.tex_coords.begin(), polygon.tex_coords.end());
    }
  }

  // Generated normals: a corner averages the normals of the faces around its vertex that lie
  // within the crease angle of its own face (area-weighted); at creaseAngle 0, flat faces.
  const double crease = sf_float(face_set, "creaseAngle", 0);
  if (!normal_node && crease > 0) {
    std::vector<Vec3> face_normals;
    std::vector<std::vector<std::uint32_t>> faces_at(mesh.positions.size());
    for (std::uint32_t f = 0; f < polygons.size(); ++f) {
      std::vector<Vec3> corners;
      for (const std::uint32_t v : polygons[f].positions) corners.push_back(mesh.positions[v]);
      face_normals.push_back(newell_normal(corners));
      for (const std::uint32_t v : polygons[f].positions) faces_at[v].push_back(f);
    }
    const double cos_crease = tessera::cos(std::min(crease, std::numbers::pi));
    for (std::uint32_t f = 0; f < polygons.size(); ++f) {
      const Vec3 own = unit_or_zero(face_normals[f]);
      for (const std::uint32_t v : polygons[f].positions) {
        Vec3 sum;
        for (const std::uint32_t g : faces_at[v])
          if (dot(own, unit_or_zero(face_normals[g])) >= cos_crease) sum += face_normals[g];
        polygons[f].normals.push_back(static_cast<std::uint32_t>(mesh.normals.size()));
        mesh.normals.push_back(normalize_or(sum, own));
      }
    }
  }
  out.smooth = !mesh.normals.empty();

  for (const Polygon& polygon : polygons) {
    std::vector<Vec3> corners;
    for (const std::uint32_t v : polygon.positions) corners.push_back(mesh.positions[v]);
    for (const auto& [a, b, c] : triangulate_polygon(corners)) {
      MeshTriangle triangle;
      triangle.v = {polygon.positions[a], polygon.positions[b], polygon.positions[c]};
      if (out.smooth) triangle.n = {polygon.normals[a], polygon.normals[b], polygon.normals[c]};
      mesh.triangles.push_back(triangle);
      if (colour_node)
        mesh.corner_colours.insert(mesh.corner_colours.end(),
                                   {polygon.colours[a], polygon.colours[b], polygon.colours[c]});
      if (wanted.tex_coords)
        mesh.corner_tex_coords.insert(
            mesh.corner_tex_coords.end(),
            {polygon.tex_coords[a], polygon.tex_coords[b], polygon.tex_coords[c]});
    }
  }
  return out;
}

}  // namespace tessera::vrml

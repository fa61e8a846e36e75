#include "common/loaders/vrml_mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/loaders/vrml_fields.h"

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

// A polygon: its corners' position indices and the normal index of each corner (or none).
struct Polygon {
  std::vector<std::uint32_t> positions;
  std::vector<std::uint32_t> normals;
};

[[noreturn]] void index_out_of_range(const FieldValue& field, const char* name, double index,
                                     std::size_t count, const char* what) {
  throw SceneError(field.where, std::string(name) + " " +
                                    std::to_string(static_cast<long long>(index)) +
                                    " is out of range: the " + what + " has " +
                                    std::to_string(count) + " entries");
}

// A face set node with the given points and polygons and `from`'s shared flags.
NodePtr face_set(const Node& from, std::vector<double> points, std::vector<double> indices) {
  auto coord = std::make_shared<Node>();
  coord->type = "Coordinate";
  coord->where = from.where;
  coord->fields["point"] = {FieldType::MFVec3f, std::move(points), {}, {}, from.where};
  auto out = std::make_shared<Node>();
  out->type = "IndexedFaceSet";
  out->where = from.where;
  out->fields["coord"] = {FieldType::SFNode, {}, {}, {coord}, from.where};
  out->fields["coordIndex"] = {FieldType::MFInt32, std::move(indices), {}, {}, from.where};
  for (const char* flag : {"ccw", "solid", "creaseAngle"})
    if (const FieldValue* v = from.field(flag)) out->fields[flag] = *v;
  return out;
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
  return face_set(grid, std::move(points), std::move(indices));
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
  // Z across the bend; where the spine is straight, the rotation taking +y to Y.
  const bool closed = spine.front() == spine.back();
  Vec3 last_z{0, 0, 1};
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 prev = i > 0 ? spine[i - 1] : (closed ? spine[n - 2] : spine[0]);
    const Vec3 next = i + 1 < n ? spine[i + 1] : (closed ? spine[1] : spine[n - 1]);
    const Vec3 y = unit_or_zero(next - prev);
    Vec3 z = unit_or_zero(cross(next - spine[i], prev - spine[i]));
    if (z == Vec3{}) {
      z = last_z;
      if (const auto r = Affine::rotation(
              std::acos(std::clamp(y.y, -1.0, 1.0)) * 180 / std::numbers::pi, cross({0, 1, 0}, y)))
        z = r->apply_vector({0, 0, 1});
    } else if (i > 0 && dot(z, last_z) < 0) {
      z = -z;  // keep the plane from flipping at an inflection
    }
    last_z = z;
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
  return face_set(extrusion, std::move(points), std::move(indices));
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

FaceSetMesh face_set_mesh(const Node& face_set) {
  FaceSetMesh out;
  Mesh& mesh = out.mesh;
  mesh.source = face_set.where.to_string();
  const Node* coord = sf_node(face_set, "coord");
  const FieldValue* coord_index = face_set.field("coordIndex");
  if (!coord || !coord_index) return out;
  mesh.positions = vectors(mf_numbers(*coord, "point"));

  const Node* normal_node = sf_node(face_set, "normal");
  const bool per_vertex = sf_bool(face_set, "normalPerVertex", true);
  const FieldValue* normal_index = face_set.field("normalIndex");
  if (normal_node) mesh.normals = vectors(mf_numbers(*normal_node, "vector"));
  const auto normal_at = [&](std::size_t slot, double fallback) -> std::uint32_t {
    double index = fallback;
    if (normal_index && slot < normal_index->numbers.size()) index = normal_index->numbers[slot];
    if (index < 0 || index >= static_cast<double>(mesh.normals.size()))
      index_out_of_range(normal_index ? *normal_index : *coord_index, "normalIndex", index,
                         mesh.normals.size(), "Normal");
    return static_cast<std::uint32_t>(index);
  };

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
    current.positions.push_back(static_cast<std::uint32_t>(index));
    if (normal_node) {
      current.normals.push_back(per_vertex ? normal_at(slot, index)
                                           : normal_at(face, static_cast<double>(face)));
    }
  }
  if (!sf_bool(face_set, "ccw", true)) {
    for (Polygon& polygon : polygons) {
      std::reverse(polygon.positions.begin(), polygon.positions.end());
      std::reverse(polygon.normals.begin(), polygon.normals.end());
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
    const double cos_crease = std::cos(std::min(crease, std::numbers::pi));
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
    }
  }
  return out;
}

}  // namespace tessera::vrml

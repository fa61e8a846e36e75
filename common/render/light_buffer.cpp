#include "common/render/light_buffer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

namespace tessera {

namespace {

constexpr int kN = LightBuffer::kCells;
constexpr double kHalf = kN / 2.0;
// The largest tangent of a direction a face may be asked about, widened by a cell.
constexpr double kWidened = 1 + 2.0 / kN;

// Bounds are shrunk by this share of themselves, and by this share of the coordinates' magnitude,
// before they are stored: far more than the rounding of the bounds, of the feeler's origin and of
// its squared distance (a few units in the last place each).
constexpr double kRelativeMargin = 1e-9;

// The least u^2 over cell i widened by a cell on each side: the least squared tangent of any
// direction whose rounding could have put it in cell i.
std::array<double, kN> least_squared_tangents() {
  std::array<double, kN> out{};
  for (int i = 0; i < kN; ++i) {
    const double lo = -1 + (i - 1) / kHalf, hi = -1 + (i + 2) / kHalf;
    const double least = lo <= 0 && hi >= 0 ? 0 : std::min(std::fabs(lo), std::fabs(hi));
    out[i] = least * least;
  }
  return out;
}

// The cells [first, last] a coordinate range [lo, hi] reaches, widened by `widen` cells each
// side (a cell, for boxes: so that a feeler whose direction rounding moved into a neighbouring
// cell, or onto the next face, still finds the object); false when it reaches none.
bool cell_range(double lo, double hi, int& first, int& last, int widen = 1) {
  // Clamped before the conversion: a box near the light's plane projects to huge tangents.
  const double a = std::clamp((lo + 1) * kHalf, -4.0, kN + 4.0);
  const double b = std::clamp((hi + 1) * kHalf, -4.0, kN + 4.0);
  first = std::max(static_cast<int>(std::floor(a)) - widen, 0);
  last = std::min(static_cast<int>(std::floor(b)) + widen, kN - 1);
  return first <= last;
}

bool finite(const Bounds3& b) {
  return std::isfinite(b.lo.x) && std::isfinite(b.lo.y) && std::isfinite(b.lo.z) &&
         std::isfinite(b.hi.x) && std::isfinite(b.hi.y) && std::isfinite(b.hi.z);
}

// The cells of one face that a box (relative to the light) may lie in: [i0, i1] x [j0, j1], none
// when i0 > i1. `projected` when its projection is bounded (the box lies beyond the face's plane,
// at least major_lo along its axis); otherwise every cell of the face.
struct FaceCells {
  int i0 = 0, i1 = -1, j0 = 0, j1 = -1;
  bool projected = false;
  double major_lo = 0;
};

FaceCells face_cells(const Vec3& lo, const Vec3& hi, bool bounded, int face, double margin) {
  const int k = face / 2, ka = (k + 1) % 3, kb = (k + 2) % 3;
  // The face's axis points away from the light: along +k, or -k for odd faces.
  // A point in the face's pyramid is at least as far along the axis as across it (up to
  // the widening by a cell, and rounding): the part of the box nearer along the axis than
  // it is across lies in other faces' pyramids.
  const double across = std::max({lo[ka], -hi[ka], lo[kb], -hi[kb], 0.0}) / kWidened;
  const double major_lo = std::max(face % 2 ? -hi[k] : lo[k], across);
  const double major_hi = face % 2 ? -lo[k] : hi[k];
  FaceCells out;
  if (!(major_hi >= major_lo - margin) && bounded) return out;  // wholly in other faces
  if (!(major_lo > margin) || !bounded) {
    // The box reaches the light's side of the face's plane: its projection is unbounded.
    out.i0 = out.j0 = 0;
    out.i1 = out.j1 = kN - 1;
    return out;
  }
  const double u_lo = std::min(lo[ka] / major_lo, lo[ka] / major_hi);
  const double u_hi = std::max(hi[ka] / major_lo, hi[ka] / major_hi);
  const double v_lo = std::min(lo[kb] / major_lo, lo[kb] / major_hi);
  const double v_hi = std::max(hi[kb] / major_lo, hi[kb] / major_hi);
  if (!cell_range(u_lo, u_hi, out.i0, out.i1) || !cell_range(v_lo, v_hi, out.j0, out.j1))
    return FaceCells{};
  out.projected = true;
  out.major_lo = major_lo;
  return out;
}

// The squared distance from the light to a box relative to it (0 when the box is unbounded).
double squared_gap(const Vec3& lo, const Vec3& hi, bool bounded) {
  double out = 0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({lo[k], -hi[k], 0.0});
    out += gap * gap;
  }
  return bounded ? out : 0;
}

// The cells of one face that an object reaches, a bit a cell: those of its whole box's
// rectangle that one of its pieces' rectangles reaches, each piece marking its rectangle a row at
// a time, so that a cell is visited once however many pieces reach it. With them, bounds on the
// distance of the pieces that mark a cell, the least over them: a point in a cell lies in one of
// those pieces, so no nearer than the least of their bounds there.
class CoveredCells {
 public:
  // Marks the cells of `whole` (the whole box's on `face`) that some piece reaches, or all of
  // them when there are no pieces; false when none is marked.
  bool cover(const FaceCells& whole, std::span<const Bounds3> pieces, const Vec3& light, int face,
             double margin) {
    for (int i = whole.i0; i <= whole.i1; ++i) rows_[i] = {};
    least_gap_ = 0;
    least_major_ = 0;
    if (pieces.empty()) return mark(whole, whole);
    least_gap_ = kInfinity;
    least_major_ = kInfinity;
    bool any = false;
    for (const Bounds3& piece : pieces) {
      if (piece.empty()) continue;
      const Vec3 lo = piece.lo - light, hi = piece.hi - light;
      const bool bounded = finite(piece);
      const FaceCells cells = face_cells(lo, hi, bounded, face, margin);
      if (!mark(whole, cells)) continue;
      any = true;
      least_gap_ = std::min(least_gap_, squared_gap(lo, hi, bounded));
      least_major_ = std::min(least_major_, cells.projected ? cells.major_lo : 0.0);
    }
    return any;
  }

  // Word w (columns 64 w to 64 w + 63) of row i.
  std::uint64_t row(int i, int w) const { return rows_[i][w]; }
  // The least over the marking pieces of their squared distance from the light, and of how far
  // along the face's axis they lie (0 for a piece across the face's plane); 0 without pieces.
  double least_gap() const { return least_gap_; }
  double least_major() const { return least_major_; }

 private:
  static_assert(kN == 128, "a row is two words");
  using Row = std::array<std::uint64_t, 2>;

  // Marks the cells of `cells` within `whole`; whether there are any.
  bool mark(const FaceCells& whole, const FaceCells& cells) {
    const int i0 = std::max(cells.i0, whole.i0), i1 = std::min(cells.i1, whole.i1);
    const int j0 = std::max(cells.j0, whole.j0), j1 = std::min(cells.j1, whole.j1);
    if (i0 > i1 || j0 > j1) return false;
    Row span{};
    for (int w = 0; w < 2; ++w) {
      const int a = std::max(j0 - 64 * w, 0), b = std::min(j1 - 64 * w, 63);
      if (a > b) continue;
      const std::uint64_t through_b = ~std::uint64_t{0} >> (63 - b);
      span[w] = through_b & (~std::uint64_t{0} << a);
    }
    for (int i = i0; i <= i1; ++i) rows_[i][0] |= span[0], rows_[i][1] |= span[1];
    return true;
  }

  std::array<Row, kN> rows_{};
  double least_gap_ = 0, least_major_ = 0;
};

}  // namespace

LightBuffer::LightBuffer(const Vec3& light, std::span<const Bounds3> bounds,
                         std::span<const std::uint32_t> ids, std::span<const InscribedBall> balls,
                         Pieces pieces)
    : light_(light), cells_(6 * kN * kN) {
  static const std::array<double, kN> tangents = least_squared_tangents();
  const double light_size = max_component(abs(light));
  if (std::any_of(ids.begin(), ids.end(), [](std::uint32_t id) { return id > kMaxId; })) {
    cells_.clear();
    return;
  }
  std::size_t entries = 0;
  CoveredCells reached;
  for (std::size_t o = 0; o < bounds.size(); ++o) {
    const Bounds3& box = bounds[o];
    if (box.empty()) continue;
    // The box relative to the light, and the distance from the light to it.
    const Vec3 lo = box.lo - light, hi = box.hi - light;
    const bool bounded = finite(box);
    const double euclid = squared_gap(lo, hi, bounded);
    const double margin =
        kRelativeMargin *
        (light_size +
         (bounded ? std::max(max_component(abs(box.lo)), max_component(abs(box.hi))) : 0));
    const std::span<const Bounds3> own_pieces =
        pieces.first.empty()
            ? std::span<const Bounds3>{}
            : pieces.boxes.subspan(pieces.first[o], pieces.first[o + 1] - pieces.first[o]);
    for (int face = 0; face < 6; ++face) {
      const FaceCells cells = face_cells(lo, hi, bounded, face, margin);
      if (cells.i0 > cells.i1) continue;
      // Why a cell left unmarked holds no feeler that the object blocks: such a feeler meets
      // the object at a point x that its own test can hit, which lies in the whole box and in
      // some piece (Pieces' contract). The feeler's cell is the one of the direction x - light
      // up to rounding; the rectangles below, the box's and the piece's alike, are those of
      // face_cells, the projection widened by a cell, which holds the cell of every feeler
      // through a point of its box. So the cell lies in both rectangles: it is marked.
      if (!reached.cover(cells, own_pieces, light, face, margin)) continue;
      // A point of the box in cell (i, j) is at least major_lo along the axis and its tangents
      // are at least those of the widened cell: its distance is no less. So is it from the
      // piece it lies in, which marked the cell: x is no nearer than the greater of the two
      // bounds, the box's and the least over the pieces marking this face.
      const double gap = std::max(euclid, reached.least_gap());
      const double major = std::max(cells.projected ? cells.major_lo : 0.0, reached.least_major());
      const std::size_t base = static_cast<std::size_t>(face) * kN * kN;
      for (int i = cells.i0; i <= cells.i1; ++i)
        for (int w = 0; w < 2; ++w)
          for (std::uint64_t row = reached.row(i, w); row; row &= row - 1) {
            const int j = 64 * w + std::countr_zero(row);
            const double reach_squared =
                std::max(gap, major * major * (1 + tangents[i] + tangents[j]));
            // Stored shrunk by the margins.
            const double shrunk = std::sqrt(reach_squared) * (1 - kRelativeMargin) - margin;
            insert(base + static_cast<std::size_t>(i) * kN + j, shrunk > 0 ? shrunk * shrunk : 0,
                   ids[o]);
            ++entries;
          }
      if (entries > kMaxEntries) {
        cells_.clear();
        return;
      }
    }
  }
  if (balls.empty()) return;
  // The least distance (squared) beyond which some ball blocks the cell's feelers, then stored.
  std::vector<float> blocked(cells_.size(), kNoReach);
  std::vector<std::uint32_t> covered;  // the cells with a finite `blocked`
  for (const InscribedBall& ball : balls) insert_ball(ball, blocked, covered);
  for (const std::uint32_t cell : covered) {
    Cell& c = cells_[cell];
    if (blocked[cell] <= c.reach[2]) {
      c.reach[2] = -blocked[cell];
    } else {
      // A third candidate is nearer: its bound moves to the third place, negated, and the
      // second holds the ball's, negated too; the second candidate is then tested from the
      // first's bound on (where its own bound lay before).
      c.reach[1] = -blocked[cell];
      c.reach[2] = -c.reach[2];
    }
  }
}

void LightBuffer::insert(std::size_t cell, double reach_squared_double, std::uint32_t id) {
  float reach =
      static_cast<float>(std::min(reach_squared_double, double{std::numeric_limits<float>::max()}));
  if (reach > reach_squared_double) reach = std::nextafter(reach, 0.0f);
  Cell& c = cells_[cell];
  if (!(reach < c.reach[2])) return;
  if (!(reach < c.reach[1])) {
    c.reach[2] = reach;
  } else if (!(reach < c.reach[0])) {
    c.reach[2] = c.reach[1];
    c.reach[1] = reach;
    c.ids[1] = static_cast<std::uint16_t>(id);
  } else {
    c.reach[2] = c.reach[1];
    c.reach[1] = c.reach[0];
    c.ids[1] = c.ids[0];
    c.reach[0] = reach;
    c.ids[0] = static_cast<std::uint16_t>(id);
  }
}

void LightBuffer::insert_ball(const InscribedBall& ball, std::vector<float>& blocked_beyond,
                              std::vector<std::uint32_t>& covered) {
  const Vec3 v = ball.centre - light_;
  const double distance2 = dot(v, v), b = ball.radius;
  // Not from inside the ball or its rim; nor so near the light, against the coordinates' size,
  // that the rounding of a feeler's direction (origin - light) could reach the cells' margin.
  if (!(distance2 > b * b * (1 + 1e-6) && distance2 > 1e-12 * dot(light_, light_))) return;
  // Beyond the ball: |o - light| > |v| + b, squared, rounded up.
  const double beyond = std::sqrt(distance2) * (1 + 1e-9) + b;
  const double beyond2 = beyond * beyond * (1 + 1e-9);
  float blocked = static_cast<float>(std::min(beyond2, double{std::numeric_limits<float>::max()}));
  if (blocked < beyond2) blocked = std::nextafter(blocked, kNoReach);
  if (!(blocked < std::numeric_limits<float>::max())) return;
  // A direction passes within b of the centre when its angle to v is at most asin(b / |v|).
  // The cone taken is narrower by twice the widening of a cell's corners, a millionth of a
  // cell (at most 1e-6 / kHalf in tangent, so in angle): a feeler's cell index, from tangents
  // exact to a few units in the last place, is then right for every direction of the cell.
  const double angle = std::asin(b / std::sqrt(distance2)) * (1 - 1e-9) - 2e-6 / kHalf;
  if (!(angle > 0)) return;
  const double cosine = std::cos(angle);
  // (d . v)^2 >= |d|^2 |v|^2 cos^2, with d . v > 0.
  const double least_cosine2 = distance2 * cosine * cosine * (1 + 1e-9);
  bool used = false;
  std::vector<char> corners;
  for (int face = 0; face < 6; ++face) {
    const int k = face / 2, ka = (k + 1) % 3, kb = (k + 2) % 3;
    const double sign = face % 2 ? -1 : 1;
    // The cells that the ball's box projects to, when the ball lies wholly before the face's
    // plane: the cone of directions through a ball across the plane is left to the boxes.
    const double major_lo = sign * v[k] - b, major_hi = sign * v[k] + b;
    if (!(major_lo > 0)) continue;
    const double u_lo = std::min((v[ka] - b) / major_lo, (v[ka] - b) / major_hi);
    const double u_hi = std::max((v[ka] + b) / major_lo, (v[ka] + b) / major_hi);
    const double w_lo = std::min((v[kb] - b) / major_lo, (v[kb] - b) / major_hi);
    const double w_hi = std::max((v[kb] + b) / major_lo, (v[kb] + b) / major_hi);
    // (Only the cells that the cone meets can lie in it: no widening.)
    int i0, i1, j0, j1;
    if (!cell_range(u_lo, u_hi, i0, i1, 0) || !cell_range(w_lo, w_hi, j0, j1, 0)) continue;
    // Which corners of the cells lie in the cone, once each: the cone meets the face's plane in
    // a convex set, so a cell lies in it when its four corners do.
    const int rows = i1 - i0 + 2, columns = j1 - j0 + 2;
    corners.assign(static_cast<std::size_t>(rows) * columns, 0);
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < columns; ++j) {
        Vec3 d;
        d[k] = sign;
        d[ka] = -1 + (i0 + i) / kHalf;
        d[kb] = -1 + (j0 + j) / kHalf;
        const double along = dot(d, v);
        corners[static_cast<std::size_t>(i) * columns + j] =
            along > 0 && along * along >= dot(d, d) * least_cosine2;
      }
    const std::size_t base = static_cast<std::size_t>(face) * kN * kN;
    for (int i = 0; i + 1 < rows; ++i)
      for (int j = 0; j + 1 < columns; ++j) {
        const char* corner = &corners[static_cast<std::size_t>(i) * columns + j];
        if (!(corner[0] && corner[1] && corner[columns] && corner[columns + 1])) continue;
        const std::size_t cell = base + static_cast<std::size_t>(i0 + i) * kN + j0 + j;
        if (!(blocked_beyond[cell] < kNoReach)) covered.push_back(static_cast<std::uint32_t>(cell));
        blocked_beyond[cell] = std::min(blocked_beyond[cell], blocked);
        used = true;
      }
  }
  if (used) longest_blocked_ = std::min(longest_blocked_, ball.longest * ball.longest * (1 - 1e-9));
}

}  // namespace tessera

// A light buffer (Haines & Greenberg, 1986), made exact: for a point light or spotlight, a cube
// of directions around the light whose cells hold lower bounds on how far from the light the
// objects' world bounds lie in that direction. A hard shadow feeler runs from its origin
// straight to the light, so every point of it lies in one direction from the light, at most
// |origin - light| away: only objects whose bound in that cell is nearer can block it. Where
// those are at most two, the tracer tests them alone instead of walking the scene BVH (and not
// even the feeler's own object when it provably cannot block); otherwise the feeler walks as
// before. The far side: a cell whose every direction passes through a ball inside an opaque
// solid (inscribed_balls.h) settles as blocked every feeler from beyond the ball. Shadows, hence
// images, stay bit for bit those of the walk; only the counts of BVH nodes and shape tests fall.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "common/math/ray.h"
#include "common/math/vec3.h"
#include "common/render/inscribed_balls.h"

namespace tessera {

class LightBuffer {
 public:
  // Cells along each side of a cube face (6 * kCells^2 cells a light, 1.5 MB). Finer cells
  // let more feelers skip the walk; docs/PERFORMANCE.md has 32, 64 and 96 measured against it.
  static constexpr int kCells = 128;
  // Past this many cell entries (objects times the cells they are entered in, never more than
  // their bounds cover: pieces only leave cells out), or with an id past kMaxId, a light gets no
  // buffer: its build would cost more than its feelers save.
  static constexpr std::size_t kMaxEntries = std::size_t{1} << 22;
  static constexpr std::uint32_t kMaxId = 0xFFFF;  // a cell is 16 bytes

  // The objects that may block a feeler from some origin to the light: at most two, or
  // `walk` when there may be more (or the buffer cannot tell); or `blocked`, when an opaque
  // solid certainly blocks it (then `walk` is false and there are no candidates).
  struct Candidates {
    bool walk = true;
    bool blocked = false;
    int count = 0;
    std::uint32_t ids[2] = {};
    // dot(origin - light, origin - light), set unless `walk` or `blocked`.
    double squared = 0;
  };

  // Tighter shapes of some objects (a torus's sectors, prepared_scene.h): object o's pieces are
  // boxes[first[o]] to boxes[first[o + 1]] (exclusive); `first` holds one offset more than there
  // are objects, or none when no object has pieces. An object with pieces is entered only in
  // the cells that one of them reaches within its bounds' cells, once, bounded there by its
  // bounds and its pieces: their union must hold every point that the object's own tests can
  // hit.
  struct Pieces {
    std::span<const Bounds3> boxes;
    std::span<const std::uint32_t> first;
  };

  // The buffer of the light at `light` over objects with world bounds `bounds`, identified by
  // `ids` (the same length), balls inside opaque solids `balls` (inscribed_balls.h, for this
  // light) and the objects' `pieces`. Empty (every feeler walks) past kMaxEntries or kMaxId.
  LightBuffer(const Vec3& light, std::span<const Bounds3> bounds,
              std::span<const std::uint32_t> ids, std::span<const InscribedBall> balls = {},
              Pieces pieces = {});

  // Which objects' bounds may meet the segment from `origin` to the light, the light excluded:
  // nearest first.
  Candidates candidates(const Vec3& origin) const;

  bool empty() const { return cells_.empty(); }

 private:
  // The three least lower bounds (squared, shrunk by a margin, rounded down to floats) over
  // the objects whose bounds reach the cell or one of its neighbours, and the ids of the two
  // nearest. A negative third bound says that a ball blocks every feeler of the cell longer
  // than some d (rounded up): the third is -d^2 when d^2 is no more than the third bound it
  // replaces (feelers shorter than d have at most two candidates, as before); otherwise the
  // third holds minus that bound and the second -d^2: feelers between them walk, those shorter
  // test both candidates from the first bound on.
  struct alignas(16) Cell {
    float reach[3] = {kNoReach, kNoReach, kNoReach};
    std::uint16_t ids[2] = {};
  };
  static constexpr float kNoReach = std::numeric_limits<float>::infinity();
  static constexpr double kHalfCells = kCells / 2.0;
  void insert(std::size_t cell, double reach_squared, std::uint32_t id);
  // Lowers `blocked_beyond` (by cell) to the distance, squared and rounded up, beyond which
  // the ball blocks the feelers of each cell it covers; adds the cells it lowers from infinity
  // to `covered`.
  void insert_ball(const InscribedBall& ball, std::vector<float>& blocked_beyond,
                   std::vector<std::uint32_t>& covered);

  Vec3 light_;
  std::vector<Cell> cells_;  // face * kCells^2 + row * kCells + column
  // Feelers this long or longer (squared) are never settled as blocked: the balls' proofs
  // assume less (InscribedBall::longest).
  double longest_blocked_ = kInfinity;
};

// Here and forced inline: point_shadow looks up every hard shadow feeler, and the call (its
// result packed into registers and spilled again) cost the renders 0.5 % of their instructions.
[[gnu::always_inline]] inline LightBuffer::Candidates LightBuffer::candidates(
    const Vec3& origin) const {
  Candidates out;
  if (cells_.empty()) return out;
  const Vec3 v = origin - light_;
  const double squared = dot(v, v);
  if (!(squared > 0 && squared < kInfinity)) return out;  // NaN too
  // The face of the largest coordinate (ties to the first) and the tangents across it, as
  // cells. A cell here may differ from the build's by rounding: each object covers one more.
  const double ax = std::fabs(v.x), ay = std::fabs(v.y), az = std::fabs(v.z);
  double major, a, b;
  int face;
  if (ax >= ay && ax >= az) {
    major = v.x, a = v.y, b = v.z, face = 0;
  } else if (ay >= az) {
    major = v.y, a = v.z, b = v.x, face = 2;
  } else {
    major = v.z, a = v.x, b = v.y, face = 4;
  }
  if (major < 0) ++face;
  const double scale = kHalfCells / std::fabs(major);
  // In [0, kCells] (a tangent is at most 1), truncated towards zero.
  const int i = std::min(static_cast<int>(a * scale + kHalfCells), kCells - 1);
  const int j = std::min(static_cast<int>(b * scale + kHalfCells), kCells - 1);
  const Cell& c = cells_[(static_cast<std::size_t>(face) * kCells + i) * kCells + j];
  const float third = c.reach[2];
  if (!(squared < std::fabs(third))) {
    const float second = c.reach[1];
    if (third < 0 && !(squared < -second) && squared < longest_blocked_) {
      out.walk = false;
      out.blocked = true;
    }
    return out;
  }
  out.walk = false;
  out.squared = squared;
  out.count = squared < c.reach[0] ? 0 : squared < c.reach[1] ? 1 : 2;
  out.ids[0] = c.ids[0];
  out.ids[1] = c.ids[1];
  return out;
}

}  // namespace tessera

// The prepared, traceable scene (docs/ARCHITECTURE.md, "Two scene forms"): built once per render
// (or per job on a worker) from a parsed Scene: instances with inverse transforms, mesh and scene
// BVHs, the camera frame, the decoded texture images, and the effect set that decides which work
// the tracer does at all.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/accel/bvh.h"
#include "common/accel/mesh_accel.h"
#include "common/geometry/instance.h"
#include "common/image/image.h"
#include "common/render/effects.h"
#include "common/render/light_buffer.h"
#include "common/scene/scene.h"
#include "common/texture/surface_texture.h"

namespace tessera {

// A still torus enters the light buffers as this many sector boxes, so that a cell lists it only
// when some sector's box, not merely the whole torus's, reaches the cell's directions.
inline constexpr int kTorusLightBufferSectors = 64;

// Appends the pieces by which the light buffers enter the instance (LightBuffer::Pieces): world
// boxes whose union holds every point its own tests can hit. A still torus's sectors; none for
// any other object, which enters as its world bounds.
void light_buffer_pieces(const Instance& instance, std::vector<Bounds3>& out);

// The pinhole camera of §4.1: a vertical field of view `view_angle` through the image centre.
struct CameraFrame {
  Vec3 eye;
  Vec3 forward, right, up;  // orthonormal; right x up = -forward
  double tan_half_height = 0;
  // VRML: the view angle spans the smaller side of the image, so a portrait image widens
  // the vertical angle (Camera::view_angle_on_smaller_side).
  bool angle_on_smaller_side = false;
  // The primary ray through image position (px, py) in pixels, (0, 0) the top-left corner of
  // the image and (width, height) the bottom-right one.
  // One ray; ImageRays spares a render the size's factors at every sample.
  Ray ray_through(double px, double py, int width, int height) const;
};

// The primary rays of an image of one size, with what depends on the size alone (the aspect
// ratio, the angle widened for a portrait image) worked out once instead of for every sample:
// each ray is CameraFrame::ray_through's, bit for bit.
class ImageRays {
 public:
  ImageRays(const CameraFrame& frame, int width, int height);
  Ray through(double px, double py) const;
  // The parts of through(px, py): its origin, the same for every ray, and its unit direction.
  const Vec3& eye() const { return frame_.eye; }
  Vec3 direction_through(double px, double py) const;
  // direction_through(px[k], py[k]) into out[k] for the four k, bit for bit: with SSE2 two
  // at a time, the same IEEE operations lane by lane in the same order (nothing is fused), in
  // straight-line code, for a quarter of the scalar instructions.
  void directions_through(const double (&px)[4], const double (&py)[4], Vec3 (&out)[4]) const;

 private:
  // A value in both lanes of an SSE2 register: directions_through loads it as one, without the
  // shuffle of a broadcast at every call.
  struct alignas(16) Twice {
    double lane[2] = {};
  };

  CameraFrame frame_;
  double width_, height_;
  double aspect_;    // width / height
  double tan_half_;  // of the vertical angle
  // directions_through's operands: the ones above and the frame's axes, coordinate by coordinate.
  Twice width2_, height2_, aspect2_, tan_half2_;
  Twice forward2_[3], right2_[3], up2_[3];
};

// Where a ray leaving an instance's surface outward cannot meet that instance again, the
// surface there being that of its convex hull (Tracer::leaves_own_hull): decided once for each
// instance, not again for every shadow feeler.
struct OwnHull {
  enum class Kind : std::uint8_t {
    None,            // nowhere known
    Convex,          // anywhere: a closed convex solid under an affine map (sphere, cube, closed
                     // tapered cylinder)
    TorusOuterHalf,  // where rho^2 = x^2 + y^2 (object space) exceeds torus_radius_squared
  };
  Kind kind = Kind::None;
  double torus_radius_squared = 0;  // R^2, for TorusOuterHalf
};

class PreparedScene {
 public:
  // Throws SceneError for what cannot be traced (degenerate camera, an image texture that
  // cannot be decoded). `scene` must outlive
  // the prepared scene (meshes are referenced, not copied).
  // `build_threads` build the meshes' BVHs (the same trees for any count).
  PreparedScene(const Scene& scene, BvhMode mode, int build_threads = 1);
  PreparedScene(Scene&& temporary, BvhMode mode) = delete;  // it would dangle
  PreparedScene(const PreparedScene&) = delete;
  PreparedScene& operator=(const PreparedScene&) = delete;

  // The scene as traced: the given one, plus its extents' bars under showExtents.
  const Scene& scene() const { return *scene_; }
  const CameraFrame& camera() const { return camera_; }
  const EffectSet& effects() const { return effects_; }
  const std::vector<Instance>& instances() const { return instances_; }
  const Bvh& bvh() const { return bvh_; }
  // Whether any shape has a texture or corner colours; only then may texture() be called.
  bool textured() const { return !textures_.empty(); }
  const ObjectTexture& texture(std::uint32_t index) const { return textures_[index]; }
  // For a transparent object, the other transparent objects whose world bounds meet its own:
  // those whose boundaries may coincide with it (empty unless the scene refracts).
  const std::vector<std::uint32_t>& transparent_neighbours(std::uint32_t instance) const {
    return transparent_neighbours_[instance];
  }
  // The light buffer of Scene::lights[light] for hard shadow feelers, or null: directional
  // lights, lights that cast no shadows, renders without a BVH and scenes too large for one
  // (LightBuffer::kMaxEntries) have none.
  const LightBuffer* light_buffer(std::size_t light) const {
    return light_buffers_[light] && !light_buffers_[light]->empty() ? &*light_buffers_[light]
                                                                    : nullptr;
  }
  const OwnHull& own_hull(std::uint32_t instance) const { return own_hulls_[instance]; }
  // What the scene asks for that this renderer does not simulate, or that changes nothing
  // here, one line each.
  const std::vector<std::string>& unsupported() const { return unsupported_; }

 private:
  const Scene* scene_;                   // the given scene, or with_extents_
  std::unique_ptr<Scene> with_extents_;  // showExtents: the scene plus its extents' bars
  CameraFrame camera_;
  EffectSet effects_;
  std::vector<std::unique_ptr<MeshAccel>> meshes_;
  std::vector<Instance> instances_;
  std::vector<Image> images_;            // Scene::images decoded, in the same order
  std::vector<ObjectTexture> textures_;  // per instance; empty when no shape has a texture
  Bvh bvh_;
  std::vector<std::vector<std::uint32_t>> transparent_neighbours_;
  std::vector<std::optional<LightBuffer>> light_buffers_;  // per Scene::lights
  std::vector<OwnHull> own_hulls_;                         // per instance
  std::vector<std::string> unsupported_;
};

}  // namespace tessera

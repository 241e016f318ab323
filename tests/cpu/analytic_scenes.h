// Analytic test scenes and a tiny ray caster that turns them into the depth buffers (and normals)
// a rasteriser would produce for a sao::Camera: for each texel centre of the input image
// (viewport + guard band) the view ray is intersected with the geometry in double, the hit's
// camera-space z is projected to window depth with the camera's own projection matrix, and the
// result is quantised with encodeDepth. Shared by the CPU, OpenGL and Vulkan backend tests.
//
// Camera space: right-handed, the camera at the origin looking down -z, +y up. Lengths in view
// units (metres with metersToViewUnits = 1).
#pragma once
#include <string>
#include <vector>

#include "sao/camera.h"
#include "sao/image.h"

namespace sao::test {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

// Keeps the points p with dot(p - point, normal) <= 0.
struct HalfSpace {
  Vec3 point, normal;
};

// An infinite plane (optionally cut by half-spaces). `normal` need not be unit length.
struct Plane {
  Vec3 point, normal;
  std::vector<HalfSpace> keep;
};

struct Sphere {
  Vec3 centre;
  double radius = 1;
};

// Axis-aligned box.
struct Box {
  Vec3 lo, hi;
};

// An open tube around a vertical (y) axis through (x, z), for y in [yMin, yMax]; no caps.
struct Rod {
  double x = 0, z = 0, radius = 0.01;
  double yMin = -1e9, yMax = 1e9;
};

struct Hit {
  double t = 0;  // ray parameter (origin + t * dir)
  Vec3 point;    // camera space
  Vec3 normal;   // unit, outward (planes: as given, made unit)
};

struct Scene {
  std::string name;
  std::vector<Plane> planes;
  std::vector<Sphere> spheres;
  std::vector<Box> boxes;
  std::vector<Rod> rods;

  // Every surface crossing with t > 0 (solids: entry and exit), nearest first.
  std::vector<Hit> trace(Vec3 origin, Vec3 dir) const;
};

// ---- Scenes

Scene skyScene();                         // nothing: every texel is the clear value
Scene planeScene(double distance);        // a plane z = -distance facing the camera
// A symmetric 90-degree concave crease: z = -distance + |x|, two half-planes meeting along the
// vertical line x = 0 (the screen centre for a centred projection), the camera looking into the
// corner. Normals (1, 0, 1)/sqrt2 (x < 0) and (-1, 0, 1)/sqrt2 (x > 0).
Scene creaseScene(double distance);
// A floor y = -1, a sphere of radius 0.5 resting on it at z = -3, and a wall z = -8.
Scene sphereOnPlaneScene();
// A floor y = -1 and six steps (0.2 m high, 0.3 m deep, 3 m wide) rising away from z = -2, with
// a wall behind them.
Scene stairsScene();
// Five thin vertical rods (radius 0.02) at z = -3, 0.5 m apart, in front of a wall z = -4.
Scene rodsScene();

// ---- Camera helpers

// The depth input's extent: viewport + 2 * guard band.
Extent inputExtent(const Camera& camera);

// The view ray through the centre of input texel (x, y) (guard band included; row 0 at NDC y = -1,
// or +1 with camera.flipY). Perspective rays start at the eye, orthographic ones on the near plane.
void viewRay(const Camera& camera, std::uint32_t x, std::uint32_t y, Vec3& origin, Vec3& dir);

// The stored window depth of camera-space z (< 0) under the camera's projection and conventions,
// in double, unclamped.
double windowDepth(const Camera& camera, double z);

// The clear value: 1 for standard depth, 0 for reversed-Z.
double clearDepth(const Camera& camera);

// ---- Rendering (layer 0: nearest surface, layer 1: the next one, as a deep G-buffer's second
// layer). Surfaces nearer than the near plane or beyond a finite far plane are clipped away, as a
// rasteriser would; texels without a surface get the clear value (LinearZ: +0.0).

// Depth as the GPU would store it. LinearZ stores camera-space z as R32F.
DepthImage renderDepth(const Scene& scene, const Camera& camera, DepthFormat format, int layer = 0);
// The analytic camera-space z per texel (0 where there is no surface), row 0 first.
std::vector<double> renderZ(const Scene& scene, const Camera& camera, int layer = 0);
// Camera-space unit normals of layer 0, oriented toward the viewer, 4 channels (w = 0);
// (0, 0, 0, 0) where there is no surface.
FloatImage renderNormals(const Scene& scene, const Camera& camera);

}  // namespace sao::test

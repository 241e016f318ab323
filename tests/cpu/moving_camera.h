// A camera that moves through an analytic scene (analytic_scenes.h), for the temporal tests: the
// scenes are written in the frame of a camera at the origin, which serves as the world frame; a
// camera whose eye sits at `eye` (same orientation) sees the scene translated by -eye, and its
// Camera::view is that translation.
#pragma once
#include "analytic_scenes.h"
#include "sao/camera.h"

namespace sao::test {

inline Scene translated(Scene s, Vec3 by) {
  auto move = [&](Vec3& p) { p = {p.x + by.x, p.y + by.y, p.z + by.z}; };
  for (Plane& p : s.planes) {
    move(p.point);
    for (HalfSpace& h : p.keep) move(h.point);
  }
  for (Sphere& sp : s.spheres) move(sp.centre);
  for (Box& b : s.boxes) {
    move(b.lo);
    move(b.hi);
  }
  for (Rod& r : s.rods) {
    r.x += by.x;
    r.z += by.z;
    r.yMin += by.y;
    r.yMax += by.y;
  }
  return s;
}

// `base` with its eye at `eye` in the world frame: view = translation by -eye.
inline Camera movedCamera(Camera base, Vec3 eye) {
  base.view = std::array<double, 16>{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -eye.x, -eye.y, -eye.z, 1};
  return base;
}

// What that camera sees of `world`.
inline Scene seenFrom(const Scene& world, Vec3 eye) { return translated(world, {-eye.x, -eye.y, -eye.z}); }

}  // namespace sao::test

// Triangle meshes in world space (the scene's units, metres for the built-in scenes; y up) and the
// primitives the built-in scenes use.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace sao::scenes {

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;  // three per triangle, counter-clockwise seen from outside

  std::size_t triangleCount() const { return indices.size() / 3; }
  void append(const Mesh& other, const glm::dmat4& transform = glm::dmat4(1.0));
};

// Builders. Every closed solid is watertight and faces outwards.
class MeshBuilder {
 public:
  // A quad p0 p1 p2 p3 (counter-clockwise seen from the side its normal points to).
  MeshBuilder& quad(glm::dvec3 p0, glm::dvec3 p1, glm::dvec3 p2, glm::dvec3 p3);
  // An axis-aligned box from min to max corner.
  MeshBuilder& box(glm::dvec3 min, glm::dvec3 max);
  // A box of the given half extents, rotated about y by yawRadians, centred at `centre`.
  MeshBuilder& orientedBox(glm::dvec3 centre, glm::dvec3 halfExtents, double yawRadians);
  // A vertical cylinder standing on `base`, capped at both ends.
  MeshBuilder& cylinder(glm::dvec3 base, double radius, double height, int segments);
  MeshBuilder& sphere(glm::dvec3 centre, double radius, int rings, int segments);
  // A semicircular arch in the xy plane (spanning x from centre.x - r to centre.x + r, springing
  // at centre.y), of wall thickness `thickness` along z and ring depth `ringDepth`.
  MeshBuilder& arch(glm::dvec3 centre, double innerRadius, double ringDepth, double thickness, int segments);
  // A spur gear in the xz plane, lying on `base` (y up), `teeth` teeth.
  MeshBuilder& gear(glm::dvec3 base, double rootRadius, double tipRadius, double thickness, int teeth);
  // A flight of `steps` steps rising along +z from `origin` (front-left-bottom corner).
  MeshBuilder& stairs(glm::dvec3 origin, double width, double stepDepth, double stepHeight, int steps);
  // A thin blade: a triangle of base width w at `base`, tip at base + height*up, leaning by lean.
  MeshBuilder& blade(glm::dvec3 base, double width, double height, glm::dvec3 lean, double yawRadians);

  Mesh build() { return std::move(mesh_); }
  const Mesh& mesh() const { return mesh_; }

 private:
  std::uint32_t vertex(glm::dvec3 p);
  void tri(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  Mesh mesh_;
};

}  // namespace sao::scenes

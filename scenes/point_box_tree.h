#pragma once
// A tree of axis-aligned boxes over a set of points, answering "does any
// point lie more than `depth` below this plane?" without visiting most of
// them: a box whose lowest corner is above the threshold holds no such
// point, and one whose highest corner is below it holds only such points.
// Receiver inference asks this once per planar mesh of a scene; scanning
// every vertex each time made a 200,000-node glTF take minutes.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace sb {

class PointBoxTree {
 public:
  explicit PointBoxTree(std::vector<glm::vec3> points);

  // Whether some point p has dot(n, p) + d < -depth.
  bool any_below(const glm::dvec3& n, double d, double depth) const;

  size_t size() const { return points_.size(); }

 private:
  struct Node {
    glm::dvec3 lo{0.0}, hi{0.0};
    uint32_t begin = 0, end = 0;  // its points, points_[begin, end)
    uint32_t left = 0;            // children left and left + 1; 0 for a leaf
  };
  void build(uint32_t index, uint32_t begin, uint32_t end, int depth);

  std::vector<glm::vec3> points_;
  std::vector<Node> nodes_;
};

}  // namespace sb

// A beam's tapered pieces as staircases of uniform prisms (staircase.hpp).
#include "staircase.hpp"

#include <fmt/format.h>

namespace modalbench::dtfm::detail {

Scene staircase(const Scene& scene, int steps) {
  Scene out = scene;
  out.segments.clear();
  for (const Segment& p : scene.segments) {
    if (!p.tapered()) {
      out.segments.push_back(p);
      continue;
    }
    const double l = p.length();
    for (int i = 0; i < steps; ++i) {
      const double from = p.x_from + l * i / steps, to = i + 1 == steps ? p.x_to : p.x_from + l * (i + 1) / steps;
      Segment step = p.uniform_at(0.5 * (from + to));
      step.x_from = from;
      step.x_to = to;
      out.segments.push_back(step);
    }
  }
  // The scene's section is the first piece's (its extent stays the largest of the tapered ones).
  if (!out.segments.empty()) {
    out.cross_section = out.segments.front().section;
    out.material = out.segments.front().material;
  }
  return out;
}

int staircase_steps(const Discretization& mesh) {
  if (mesh.counts.size() != 1)
    throw InputError("", "--mesh",
                     fmt::format("a tapered beam's dtfm mesh is N, the uniform steps per tapered piece (each one "
                                 "prism: its section is not cut; got '{}')",
                                 mesh.spec()));
  const int n = mesh.counts[0];
  if (n < kMinSteps || n > kMaxSteps)
    throw InputError("", "--mesh",
                     fmt::format("the steps per tapered piece must lie in [{}, {}] (got {})", kMinSteps, kMaxSteps, n));
  return n;
}

Discretization staircase_mesh(int steps) { return Discretization{{steps}}; }

}  // namespace modalbench::dtfm::detail

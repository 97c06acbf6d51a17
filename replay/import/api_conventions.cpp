#include "import/api_conventions.h"

namespace aor {

double windowRow(const ApiConventions& c, const RawViewport& v, double ndcY) {
  const double y = c.clipOriginUpperLeft ? -ndcY : ndcY;
  return double(v.y) + (y + 1.0) * 0.5 * double(v.height);
}

double windowDepth(const ApiConventions& c, double ndcZ) { return c.clipZMinusOneToOne ? (ndcZ + 1.0) * 0.5 : ndcZ; }

glm::mat4 projectionToZeroToOne(const ApiConventions& c, const glm::mat4& projection) {
  if (!c.clipZMinusOneToOne) return projection;
  glm::mat4 p = projection;
  for (int column = 0; column < 4; ++column) p[column][2] = (projection[column][2] + projection[column][3]) * 0.5f;
  return p;
}

}  // namespace aor

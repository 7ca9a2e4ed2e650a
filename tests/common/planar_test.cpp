#include "tightfit/common/planar.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace tightfit {
namespace planar_test {

TEST(Planar, PolygonSignedAreaIsPositiveCounterClockwise) {
  const std::vector<Vec2> square = {Vec2(0, 0), Vec2(2, 0), Vec2(2, 1), Vec2(0, 1)};
  EXPECT_DOUBLE_EQ(signed_area(square), 2.0);
  const std::vector<Vec2> reversed(square.rbegin(), square.rend());
  EXPECT_DOUBLE_EQ(signed_area(reversed), -2.0);
  // A non-convex L of area 3: the shoelace sum equals the fan of triangle areas.
  const std::vector<Vec2> l = {Vec2(0, 0), Vec2(2, 0), Vec2(2, 1),
                               Vec2(1, 1), Vec2(1, 2), Vec2(0, 2)};
  EXPECT_DOUBLE_EQ(polygon_signed_area(l.size(), [&l](std::size_t i) { return l[i]; }), 3.0);
  double fan = 0.0;
  for (std::size_t i = 1; i + 1 < l.size(); ++i) fan += signed_area(l[0], l[i], l[i + 1]);
  EXPECT_NEAR(fan, 3.0, 1e-15);
  EXPECT_DOUBLE_EQ(signed_area(std::vector<Vec2>{}), 0.0);
}

}  // namespace planar_test
}  // namespace tightfit

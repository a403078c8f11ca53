// The VPL clamps' length (trimmed_diagonal): the triangles' bounds' diagonal with their
// outlying 10^-4 of area left out at each end of each axis.
#include "scene/extent.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace tessera {
namespace {

// Appends the two triangles of the axis-aligned square at height y over [x0, x0+s]×[0, s].
void add_square(std::vector<float>& xyz, float x0, float y, float s) {
    const float t[18] = {x0, y, 0, x0 + s, y, 0, x0 + s, y, s, x0, y, 0, x0 + s, y, s, x0, y, s};
    xyz.insert(xyz.end(), t, t + 18);
}

SceneBounds bounds_of(const std::vector<float>& xyz) {
    SceneBounds b;
    for (size_t i = 0; i + 2 < xyz.size(); i += 3) b.grow({xyz[i], xyz[i + 1], xyz[i + 2]});
    return b;
}

// Two unit squares a unit apart in y: the diagonal of [0,1]×[0,1]×[0,1], √3. A square of
// 1e-6 the area 1,000 units away is left out (it holds less than 10^-4 of the area); one
// of half the area is not.
TEST(TrimmedDiagonal, LeavesOutSpecksButNotSurfaces) {
    std::vector<float> xyz;
    add_square(xyz, 0, 0, 1);
    add_square(xyz, 0, 1, 1);
    EXPECT_FLOAT_EQ(trimmed_diagonal(xyz.data(), xyz.size() / 9, bounds_of(xyz)), std::sqrt(3.0f));
    std::vector<float> speck = xyz;
    add_square(speck, 1000, 0, 1e-3f);
    EXPECT_FLOAT_EQ(trimmed_diagonal(speck.data(), speck.size() / 9, bounds_of(speck)), std::sqrt(3.0f));
    std::vector<float> wall = xyz;
    add_square(wall, 1000, 0, std::sqrt(0.5f));
    EXPECT_GT(trimmed_diagonal(wall.data(), wall.size() / 9, bounds_of(wall)), 999.0f);
}

// Without area the whole bounds' diagonal (three collinear points: 5); without triangles 0.
TEST(TrimmedDiagonal, WithoutAreaTheBoundsDiagonal) {
    const std::vector<float> line = {0, 0, 0, 3, 4, 0, 1.5f, 2, 0};
    EXPECT_FLOAT_EQ(trimmed_diagonal(line.data(), 1, bounds_of(line)), 5.0f);
    EXPECT_EQ(trimmed_diagonal(nullptr, 0, SceneBounds{}), 0.0f);
}

}  // namespace
}  // namespace tessera

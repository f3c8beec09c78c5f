// The D3D11 triangle-domain pattern's float reference (model/d3d11_pattern.hpp): the properties
// every implementation has (tests/support/d3d11_pattern_checks.hpp), its factor processing's
// 16.16 rounding, and the names of the partitionings and windings.
#include <array>

#include <gtest/gtest.h>

#include "model/d3d11_pattern.hpp"
#include "tests/support/d3d11_pattern_checks.hpp"

namespace tessim {
namespace {

using d3d11_checks::D3D11PatternProperties;

INSTANTIATE_TEST_SUITE_P(FloatReference, D3D11PatternProperties,
                         ::testing::Values(d3d11_checks::D3D11Implementation{"float_reference", d3d11_tri_pattern}),
                         d3d11_checks::implementation_name);

// Factors reach the 16.16 grid rounded to nearest, ties to even (2.2f is 0x23333).
TEST(D3D11Factors, SixteenSixteenRoundsToNearestEven) {
  auto fixed = [](float f) { return d3d11_tri_factors({f, 3, 3}, 3, Partitioning::fractional_odd).outer_fixed[0]; };
  EXPECT_EQ(fixed(2.2f), 0x23333);
  EXPECT_EQ(fixed(2.5f), 0x28000);
  EXPECT_EQ(fixed(3.0f + 1.0f / 131072.0f), 0x30000);  // half a step: ties to the even 0
  EXPECT_EQ(fixed(3.0f + 3.0f / 131072.0f), 0x30002);  // one and a half: to the even 2
  EXPECT_EQ(fixed(3.0f + 5.0f / 131072.0f), 0x30002);  // two and a half: to the even 2
  EXPECT_EQ(fixed(3.0f + 7.0f / 131072.0f), 0x30004);
}

TEST(D3D11Names, RoundTrip) {
  for (Partitioning part : {Partitioning::integer, Partitioning::pow2, Partitioning::fractional_odd,
                            Partitioning::fractional_even})
    EXPECT_EQ(parse_partitioning(partitioning_name(part)), part);
  EXPECT_FALSE(parse_partitioning("fractional").has_value());
  EXPECT_EQ(parse_winding("cw"), Winding::cw);
  EXPECT_FALSE(parse_winding("CW").has_value());
}

}  // namespace
}  // namespace tessim

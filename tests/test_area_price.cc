// area_price (Solver/AreaPrice.hh): how the skinned and frames modules price a collapse by its area.
#include <OpenMeshSkinned/Solver/AreaPrice.hh>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

using OpenMeshSkinned::area_price;

TEST(AreaPrice, PerAreaBelowTheFloorAndOverAPowerAbove) {
  EXPECT_EQ(area_price(8.0, 16.0, 0.0, 4.0), 8.0);  // exponent 0: the energy, whatever the floor
  EXPECT_EQ(area_price(8.0, 16.0, 1.0, 4.0), 0.5);  // 1: a mean squared distance
  EXPECT_DOUBLE_EQ(area_price(8.0, 16.0, 0.5, 4.0), 8.0 / 4.0);
  EXPECT_DOUBLE_EQ(area_price(8.0, 1.0, 0.5, 4.0), 8.0 / 1.0 * 2.0);  // per area, times floor^(1/2)
  EXPECT_DOUBLE_EQ(area_price(8.0, 4.0, 0.5, 4.0), 8.0 / 2.0);        // the two meet at the floor
  EXPECT_DOUBLE_EQ(area_price(8.0, 1.0, 0.5, 0.0), 8.0);              // no floor: over the root all the way
}

TEST(AreaPrice, ACollapseStandingForNoAreaIsFree) {
  EXPECT_EQ(area_price(8.0, 0.0, 0.5, 4.0), 0.0);
  EXPECT_EQ(area_price(8.0, 0.0, 1.0, 0.0), 0.0);
  EXPECT_EQ(area_price(8.0, 0.0, 0.0, 0.0), 8.0);  // the energy needs no area
}

TEST(AreaPrice, BadSettingsAreRefusedNamingTheModule) {
  for (double bad : {-0.01, 1.01, std::nan("")})
    EXPECT_THROW(OpenMeshSkinned::check_area_exponent("M", bad), std::invalid_argument);
  for (double bad : {-1.0, HUGE_VAL, std::nan("")})
    EXPECT_THROW(OpenMeshSkinned::check_area_floor("M", bad), std::invalid_argument);
  EXPECT_NO_THROW(OpenMeshSkinned::check_area_exponent("M", 0.0));
  EXPECT_NO_THROW(OpenMeshSkinned::check_area_floor("M", 0.0));
  try {
    OpenMeshSkinned::check_area_exponent("ModFrameQuadricT", 2.0);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("ModFrameQuadricT: the area exponent must be in [0, 1]", 0), 0u) << e.what();
  }
}

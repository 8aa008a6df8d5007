#include <gtest/gtest.h>
#include "remesh/remesh.h"
#include "test_support.h"
namespace eqmesh {
TEST(Remesh, Sphere) {
  RemeshReport r;
  auto m = Remesh(testing::MakeIcosphere(3), RemeshOptions{3, 12, false, nullptr}, &r);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
}
}

#include <doctest/doctest.h>

#include "image/metrics.h"

using namespace pt;

TEST_CASE("rmse and relmse") {
    Image a(2, 1), b(2, 1);
    b.set(0, 0, Color(1, 1, 1));
    b.set(1, 0, Color(0, 0, 0));
    a.set(0, 0, Color(1.5, 1.5, 1.5));  // error 0.5 where the reference is 1
    a.set(1, 0, Color(0.1, 0.1, 0.1));  // error 0.1 where the reference is 0
    CHECK(rmse(a, b) == doctest::Approx(std::sqrt((0.25 + 0.01) / 2)));
    CHECK(relmse(a, b) == doctest::Approx((0.25 / 1.01 + 0.01 / 0.01) / 2));
    CHECK(rmse(b, b) == 0);
    CHECK(relmse(b, b) == 0);
    CHECK_THROWS(rmse(a, Image(1, 1)));
}

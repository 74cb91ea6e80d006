// The doctest check of a chi-square result, shared by the statistical tests:
// the message is logged on failure, and printed always when the environment
// variable PT_CHI2_VERBOSE is set (to see the p-values of a passing run).
#pragma once

#include <doctest/doctest.h>

#include <cstdlib>

#include "statistical/chi2.h"

namespace pt::stats {

inline void check_passes(const Chi2Result& r) {
    INFO(r.message);
    if (std::getenv("PT_CHI2_VERBOSE")) MESSAGE(r.message);
    CHECK(r.passed);
}

}  // namespace pt::stats

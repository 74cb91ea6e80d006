// The false-failure test of the grader for parts 4 to 9: the reference,
// graded as if it were a student's, earns full marks on every one of 20
// seeds (parts 1 to 3 and the correct alternatives: test_full_marks.cpp).
#include <doctest/doctest.h>

#include "full_marks.h"

using namespace pt;
using namespace pt::testing;

TEST_CASE("the reference graded as the student earns full marks on 20 of 20 seeds, parts 4 to 9") {
    for (int part : {4, 5, 6, 7, 8, 9}) {
        SUBCASE(("part " + std::to_string(part)).c_str()) {
            full_marks_on_20_seeds(part, reference_stages());
        }
    }
}

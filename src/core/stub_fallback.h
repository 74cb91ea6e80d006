// Handout stubs with a slow but correct fallback (DESIGN.md "The stages and
// the switch"): until the student writes construct_bvh, bvh_intersect or
// bvh_has_intersection, Part 2 builds one leaf of everything and scans every
// primitive, so `part2` still renders the right image, only slowly.
//
// Such a stub calls stub_fallback() before it falls back. Normally that
// prints "Part N: FUNCTION is not implemented yet; using FALLBACK" once per
// function and returns. While a StubFallbacksAreNotImplemented object
// lives (the grader holds one around every task), it throws
// NotImplemented instead, so a fallback is graded "not implemented" and is
// never given the points of the correct code it stands in for.
#pragma once

namespace pt {

/// See the file comment. `task` is the task number within the part ("3"),
/// `function` the stub's name, `fallback` what it does instead ("a linear scan").
void stub_fallback(int part, const char* task, const char* function, const char* fallback);

/// While one of these lives, stub_fallback() throws NotImplemented (for
/// every thread). Nests; not copyable.
class StubFallbacksAreNotImplemented {
  public:
    StubFallbacksAreNotImplemented();
    ~StubFallbacksAreNotImplemented();
    StubFallbacksAreNotImplemented(const StubFallbacksAreNotImplemented&) = delete;
    StubFallbacksAreNotImplemented& operator=(const StubFallbacksAreNotImplemented&) = delete;
};

}  // namespace pt

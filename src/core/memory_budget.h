// How much geometry this machine can hold, so that a huge mesh or a typo
// in a generated one ("segments": 5000000) stops at once with a message that
// says the limit, instead of swapping, being killed, or failing after
// minutes (issue 22).
//
// The budget is three quarters of the memory this process may use: the
// physical memory, lowered by a cgroup limit (a container) or by
// RLIMIT_AS / RLIMIT_DATA (ulimit -v / -d). Not "available" memory: it
// changes from second to second, and a limit should not.
//
// Cost per triangle, measured with /usr/bin/time's maximum RSS while loading
// and building the BVH (pathtracer -r 8 8): a 2M-triangle torus knot 147
// bytes, a 1M-triangle OBJ grid with 0.5M vertices 212 bytes (tinyobjloader's
// copy included). The estimate below, 256 per triangle and 64 per vertex, is
// above both.
#pragma once

#include <cstdint>
#include <string>

namespace pt {

constexpr uint64_t kBytesPerTriangle = 256;
constexpr uint64_t kBytesPerVertex = 64;

/// The memory this process may use, in bytes (see the file comment).
uint64_t usable_memory_bytes();

/// The most triangles (with half as many vertices, as in a typical mesh)
/// that fit the budget.
uint64_t max_triangles();

/// Throws InputError "WHERE: T triangles and V vertices need about X GB,
/// more than this machine can hold: at most M triangles (...)" when the
/// scene's geometry would not fit. Counts are totals for the whole scene.
void check_geometry_budget(uint64_t triangles, uint64_t vertices, const std::string& where);

}  // namespace pt

#include "core/memory_budget.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "core/error.h"

namespace pt {
namespace {

/// A cgroup's memory limit (v2 memory.max, else v1), or "no limit".
uint64_t cgroup_limit() {
    for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        std::ifstream in(path);
        unsigned long long limit = 0;
        if (in >> limit && limit > 0) return limit;  // "max" (no limit) fails to parse
    }
    return UINT64_MAX;
}

uint64_t rlimit_bytes(int resource) {
    struct rlimit r;
    if (getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return UINT64_MAX;
    return uint64_t(r.rlim_cur);
}

std::string gigabytes(double bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
    return text;
}

std::string with_commas(uint64_t n) {
    std::string digits = std::to_string(n), out;
    for (size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

uint64_t budget_bytes() { return usable_memory_bytes() / 4 * 3; }

}  // namespace

uint64_t usable_memory_bytes() {
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    uint64_t physical = pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : (uint64_t(1) << 32);
    return std::min({physical, cgroup_limit(), rlimit_bytes(RLIMIT_AS), rlimit_bytes(RLIMIT_DATA)});
}

uint64_t max_triangles() { return budget_bytes() / (kBytesPerTriangle + kBytesPerVertex / 2); }

void check_geometry_budget(uint64_t triangles, uint64_t vertices, const std::string& where) {
    // Saturating: a count near 2^64 must not wrap into a small product.
    const uint64_t cap = UINT64_MAX / 2 / kBytesPerTriangle;
    double needed = double(std::min(triangles, cap)) * kBytesPerTriangle + double(std::min(vertices, cap)) * kBytesPerVertex;
    if (needed <= double(budget_bytes())) return;
    throw InputError(where + ": " + with_commas(triangles) + " triangles and " + with_commas(vertices) +
                     " vertices need about " + gigabytes(needed) + ", more than this machine can hold: at most " +
                     with_commas(max_triangles()) + " triangles (3/4 of its " + gigabytes(double(usable_memory_bytes())) +
                     " of memory, at about " + std::to_string(kBytesPerTriangle) + " bytes per triangle)");
}

}  // namespace pt

// A first, streaming pass over an OBJ file, before tinyobjloader reads it.
//
// tinyobjloader is lenient where this project must not be: it reads a
// coordinate it cannot parse ("nan", "1.2.3") as 0, wraps a face index past
// 2^31 (atoi) into another vertex, and keeps a line of any length in
// memory. The scan reads the file a line at a time (at most kMaxObjLine
// bytes each, so a 2 GB file is never held whole) and rejects, naming the
// line:
//   - a number on a v, vn or vt line that is not finite,
//   - a face index that is not a whole number, is 0, or lies outside
//     [-2^31 + 1, 2^31 - 1] (issue 22: 4294967299 used to become vertex 3),
//   - a line longer than kMaxObjLine.
// It counts vertices and triangles so that the caller can check the memory
// budget (core/memory_budget.h) before anything is loaded.
#pragma once

#include <cstdint>
#include <string>

namespace pt {

constexpr size_t kMaxObjLine = 1 << 20;  // 1 MiB: a face of ~100,000 corners

struct ObjCounts {
    uint64_t vertices = 0;   ///< v lines
    uint64_t triangles = 0;  ///< after triangulation: n - 2 per face of n corners
};

/// Scans `path` (a readable regular file); throws InputError "WHERE: line N: ...".
ObjCounts scan_obj(const std::string& path, const std::string& where);

}  // namespace pt

// Manifests: one per part, assignments/partN/grading.json, written and
// edited by the instructor. A manifest lists the part's tasks: id, name,
// points, the check that grades it, its type, and the check's parameters
// (thresholds, scenes, sample counts). Example (Part 1):
//
//   {
//     "part": 1,
//     "title": "Ray generation and scene intersection",
//     "tasks": [
//       {"id": "part1.1", "name": "Camera rays", "check": "generate_ray",
//        "type": "function", "points": 25, "params": {"rel_tol": 1e-6}}
//     ]
//   }
//
// Unknown keys, unknown checks, a type that does not match the check, and
// parameters the check does not accept are errors (InputError, exit 2):
// a typo in a manifest must never grade silently with a default.
#pragma once

#include <string>
#include <vector>

#include "grade/task.h"

namespace pt {

/// The course parts a manifest may belong to: 1 to 9 (Part 7, BDPT, and
/// any part without a grading.json are simply skipped by read_manifests).
constexpr int kFirstPart = 1;
constexpr int kLastPart = 9;

struct PartManifest {
    int part = 0;
    std::string title;
    std::string path;  ///< the grading.json it was read from
    std::vector<TaskSpec> tasks;
};

/// Reads and validates one manifest; `expected_part` (kFirstPart to
/// kLastPart, or 0 for any) must match its "part".
PartManifest read_manifest(const std::string& path, int expected_part = 0);

/// The manifests of parts kFirstPart to kLastPart found under `assignments_dir`
/// (partN/grading.json). A part without a manifest is skipped, with a note
/// appended to `notes`.
std::vector<PartManifest> read_manifests(const std::string& assignments_dir,
                                         std::vector<std::string>* notes);

}  // namespace pt

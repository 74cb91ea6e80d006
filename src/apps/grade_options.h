// The flags of `grade` (grade_main.cpp parses them; grade_class.cpp grades
// a whole class with them).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace pt {

struct GradeOptions {
    std::string out_dir = "grade_report";
    bool out_given = false;
    std::string manifests_dir = PT_DEFAULT_ASSIGNMENTS_DIR;
    std::string assets_dir = PT_DEFAULT_ASSETS_DIR;
    std::string cache_dir = PT_DEFAULT_GRADE_CACHE_DIR;
    uint64_t seed = 1;
    int threads = int(std::max(1u, std::thread::hardware_concurrency()));
    bool threads_given = false;
    std::vector<int> parts;          ///< empty = all parts with a manifest
    std::vector<std::string> tasks;  ///< empty = all tasks
    double timeout = 600;            ///< seconds per task in its runner; 0 = no limit
    double budget = 0;               ///< seconds for the whole submission; 0 = no limit
    bool sandbox = true;             ///< bubblewrap around the runners
    bool quiet = false, help = false, list_checks = false;

    // One submission graded by `grade --class` (not for hand use).
    std::string runners_dir;          ///< where grade_runner_KEY are; "" = next to grade
    std::string student_dir;          ///< the submission, for the report; "" = the build's
    std::vector<int> not_submitted;   ///< parts whose tasks are "not submitted"

    // A class: grade --class DIR --out DIR [-j N] [--shard K/N]; grade --merge DIR... --out DIR.
    std::string class_dir;
    int jobs = 1;
    int shard = 1, shards = 1;
    double build_timeout = 600;       ///< seconds per configure and per build of a submission
    std::string build_dir;            ///< the workers' build folders; "" = OUT/.build
    std::vector<std::string> merge_dirs;
};

int run_class(const GradeOptions& o);
int run_merge(const GradeOptions& o);

}  // namespace pt

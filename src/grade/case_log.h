// CaseLog: the bookkeeping of a function check. Each input case is
// recorded under a category ("random", "edges", "parallel", ...) as agreed,
// allowed (a disagreement inside the documented edge band, where one ulp
// flips the verdict) or a mismatch with a description of the input and of
// what differed. finish() turns the log into the task's verdict: pass when
// the mismatches outside the band are at most `max_mismatches`.
#pragma once

#include <string>
#include <vector>

#include "core/vec3.h"
#include "grade/task.h"

namespace pt {

class CaseLog {
  public:
    /// Starts (or returns to) a category; later records count under it.
    void category(const std::string& name);
    void agreed() { ++current().cases; }
    void allowed() {
        ++current().cases;
        ++current().allowed;
    }
    void mismatch(const std::string& description);

    int cases() const;
    int mismatches() const;
    int allowed_count() const;

    /// Fills a TaskResult: metric "mismatches", comparison "<=", the first
    /// mismatches and per-category counts in details. `against` names what
    /// the answers were compared with, for the message ("agrees with the
    /// reference on ...", "... disagree with brute force").
    TaskResult finish(const TaskSpec& spec, int max_mismatches,
                      const std::string& against = "the reference") const;

  private:
    struct Category {
        std::string name;
        int cases = 0, mismatches = 0, allowed = 0;
        std::vector<std::string> examples;  ///< the first few mismatches
    };
    Category& current();
    std::vector<Category> categories_;
    size_t current_ = 0;
};

/// "(1.25, -3, 0.5)" with up to 9 significant digits.
std::string format_vec(const Vec3& v);
/// "1.25" with up to 9 significant digits.
std::string format_num(double v);

}  // namespace pt

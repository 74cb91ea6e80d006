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
    ///
    /// Points by case family: when the task's params have "families", a
    /// list of {"name", "points", "categories": [category names]} that
    /// covers every category once and whose points add up to the task's,
    /// each family passes on its own (at most max_mismatches outside the
    /// edge band), the task passes when all do, and a failing task earns
    /// the points of the families that pass (TaskResult::family_points),
    /// its message naming each lost family and its first mismatch.
    /// InputError for a family list that does not fit the categories.
    TaskResult finish(const TaskSpec& spec, int max_mismatches,
                      const std::string& against = "the reference") const;

  private:
    struct Family {
        std::string name;
        double points = 0;
        std::vector<size_t> categories;  ///< indices into categories_
    };
    /// The manifest's "families" checked against the logged categories.
    std::vector<Family> families(const TaskSpec& spec) const;
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

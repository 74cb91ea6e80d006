#include "grade/case_log.h"

#include <cstdio>

namespace pt {

namespace {
constexpr size_t kExamplesPerCategory = 3;
}

void CaseLog::category(const std::string& name) {
    for (size_t i = 0; i < categories_.size(); ++i) {
        if (categories_[i].name == name) {
            current_ = i;
            return;
        }
    }
    Category c;
    c.name = name;
    categories_.push_back(c);
    current_ = categories_.size() - 1;
}

CaseLog::Category& CaseLog::current() {
    if (categories_.empty()) category("cases");
    return categories_[current_];
}

void CaseLog::mismatch(const std::string& description) {
    Category& c = current();
    ++c.cases;
    ++c.mismatches;
    if (c.examples.size() < kExamplesPerCategory) c.examples.push_back(description);
}

int CaseLog::cases() const {
    int n = 0;
    for (const Category& c : categories_)
        n += c.cases;
    return n;
}

int CaseLog::mismatches() const {
    int n = 0;
    for (const Category& c : categories_)
        n += c.mismatches;
    return n;
}

int CaseLog::allowed_count() const {
    int n = 0;
    for (const Category& c : categories_)
        n += c.allowed;
    return n;
}

TaskResult CaseLog::finish(const TaskSpec& spec, int max_mismatches,
                           const std::string& against) const {
    TaskResult r;
    r.metric = "mismatches";
    r.value = mismatches();
    r.comparison = "<=";
    r.threshold = max_mismatches;
    r.status = mismatches() <= max_mismatches ? TaskStatus::pass : TaskStatus::fail;
    if (r.status == TaskStatus::pass) {
        int agreed = cases() - mismatches() - allowed_count();
        r.message = "agrees with " + against + " on " + std::to_string(agreed) + " of " +
                    std::to_string(cases()) + " cases";
        if (allowed_count() > 0)
            r.message += "; the other " + std::to_string(allowed_count()) +
                         " lie in the edge band, where a one-ulp difference may flip the answer";
    } else {
        std::string first;
        for (const Category& c : categories_) {
            if (!c.examples.empty()) {
                first = c.name + ": " + c.examples.front();
                break;
            }
        }
        r.message = std::to_string(mismatches()) + " of " + std::to_string(cases()) +
                    " cases disagree with " + against + "; first: " + first;
    }
    for (const Category& c : categories_) {
        char line[256];
        std::snprintf(line, sizeof line, "%s: %d cases, %d mismatches, %d allowed in the edge band",
                      c.name.c_str(), c.cases, c.mismatches, c.allowed);
        r.details.push_back(line);
        for (const std::string& e : c.examples)
            r.details.push_back("  " + c.name + ": " + e);
    }
    (void)spec;
    return r;
}

std::string format_num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

std::string format_vec(const Vec3& v) {
    return "(" + format_num(v.x) + ", " + format_num(v.y) + ", " + format_num(v.z) + ")";
}

}  // namespace pt

#include "grade/case_log.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"

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

std::vector<CaseLog::Family> CaseLog::families(const TaskSpec& spec) const {
    std::vector<Family> out;
    auto it = spec.params.find("families");
    if (it == spec.params.end()) return out;
    const std::string where = spec.manifest + ": task " + spec.id + ": params.families";
    if (!it->is_array() || it->empty()) throw InputError(where + ": expected a non-empty list");
    std::vector<int> owner(categories_.size(), -1);
    double total = 0;
    for (const auto& f : *it) {
        if (!f.is_object() || !f.contains("name") || !f["name"].is_string() ||
            !f.contains("points") || !f["points"].is_number() || !f.contains("categories") ||
            !f["categories"].is_array() || f.size() != 3)
            throw InputError(where + ": each family is {\"name\", \"points\", \"categories\"}, not " +
                             f.dump());
        Family family{f["name"].get<std::string>(), f["points"].get<double>(), {}};
        for (const auto& c : f["categories"]) {
            size_t i = 0;
            while (i < categories_.size() && !(c.is_string() && c == categories_[i].name))
                ++i;
            if (i == categories_.size())
                throw InputError(where + ": family \"" + family.name + "\": no case category " +
                                 c.dump());
            if (owner[i] >= 0)
                throw InputError(where + ": category \"" + categories_[i].name +
                                 "\" is in two families");
            owner[i] = int(out.size());
            family.categories.push_back(i);
        }
        total += family.points;
        out.push_back(family);
    }
    for (size_t i = 0; i < categories_.size(); ++i)
        if (owner[i] < 0)
            throw InputError(where + ": category \"" + categories_[i].name + "\" is in no family");
    if (std::fabs(total - spec.points) > 1e-9)
        throw InputError(where + ": the families' points add up to " + format_num(total) +
                         ", not the task's " + format_num(spec.points));
    return out;
}

TaskResult CaseLog::finish(const TaskSpec& spec, int max_mismatches,
                           const std::string& against) const {
    const std::vector<Family> split = families(spec);
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
    if (!split.empty() && r.status == TaskStatus::fail) {
        // Each family passes or fails on its own; say which lost its share and why.
        std::string lost;
        for (const Family& f : split) {
            int bad = 0, cases = 0;
            std::string first;
            for (size_t i : f.categories) {
                const Category& c = categories_[i];
                bad += c.mismatches;
                cases += c.cases;
                if (first.empty() && !c.examples.empty()) first = c.name + ": " + c.examples.front();
            }
            if (bad <= max_mismatches) {
                r.family_points += f.points;
                continue;
            }
            lost += std::string(lost.empty() ? "" : "; ") + "family \"" + f.name + "\" loses its " +
                    format_num(f.points) + " points (" + std::to_string(bad) + " of " +
                    std::to_string(cases) + " cases disagree with " + against + "; first: " +
                    first + ")";
        }
        r.message = format_num(r.family_points) + " of " + format_num(spec.points) +
                    " points: " + lost;
    }
    for (const Family& f : split) {
        std::string names;
        for (size_t i : f.categories)
            names += (names.empty() ? "" : ", ") + categories_[i].name;
        r.details.push_back("family \"" + f.name + "\" (" + format_num(f.points) +
                            " points): " + names);
    }
    for (const Category& c : categories_) {
        char line[256];
        std::snprintf(line, sizeof line, "%s: %d cases, %d mismatches, %d allowed in the edge band",
                      c.name.c_str(), c.cases, c.mismatches, c.allowed);
        r.details.push_back(line);
        for (const std::string& e : c.examples)
            r.details.push_back("  " + c.name + ": " + e);
    }
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

// The exclusions of scripts/coverage.sh (docs/grading.md, "Coverage"): each
// manifest's "coverage_exclusions" entry names a function, a line of the
// handout-steps solution (tests/grading/solution/) by its text, and a
// reason. The coverage run itself takes minutes (a build folder of its own),
// so it is a script; this cheap test keeps its exclusions honest: an entry
// whose line is no longer in the solution would silently exclude nothing.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "grading_helpers.h"

using namespace pt::testing;

namespace {

std::string trimmed(const std::string& s) {
    size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
    return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

/// Every line of the solution's files of `part`, stripped.
std::set<std::string> solution_lines(int part) {
    std::set<std::string> lines;
    const std::filesystem::path dir =
        source_dir() + "/tests/grading/solution/part" + std::to_string(part);
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        std::ifstream in(e.path());
        for (std::string line; std::getline(in, line);)
            lines.insert(trimmed(line));
    }
    return lines;
}

}  // namespace

TEST_CASE("every coverage exclusion names a line of the handout-steps solution and says why") {
    int exclusions = 0;
    for (int part : graded_parts()) {
        std::ifstream in(source_dir() + "/assignments/part" + std::to_string(part) + "/grading.json");
        const nlohmann::json manifest = nlohmann::json::parse(in);
        if (!manifest.contains("coverage_exclusions")) continue;
        const std::set<std::string> lines = solution_lines(part);
        for (const nlohmann::json& ex : manifest["coverage_exclusions"]) {
            INFO("part " << part << ": " << ex.dump());
            REQUIRE(ex.is_object());
            CHECK(ex.size() == 3);
            CHECK_FALSE(ex.value("function", std::string()).empty());
            CHECK(ex.value("reason", std::string()).size() >= 20);  // a reason, not a word
            CHECK(lines.count(ex.value("line", std::string())) == 1);
            ++exclusions;
        }
    }
    CHECK(exclusions == 14);  // docs/grading.md lists them; a new one is a decision
}

// The include rule of the source tree (README "Design notes"): every
// #include "floor/..." points to the same floor or one below,
//     apps, grade  ->  render  ->  stages  ->  scene  ->  image  ->  core
// and a student's files (assignments/) see only stages and below. A stage
// added on top of the renderer's own files would close a loop again; this
// test names the first file that does.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "test_util.h"

namespace fs = std::filesystem;

namespace {

const std::map<std::string, int> kFloor = {{"core", 0},   {"image", 1},  {"scene", 2},
                                           {"stages", 3}, {"render", 4}, {"apps", 5},
                                           {"grade", 5}};

/// Every violation of the rule in the C++ files under `dir`, whose own
/// floor is `own` (or the folder's name under src/ when `own` < 0).
std::vector<std::string> violations(const fs::path& dir, int own) {
    std::vector<std::string> found;
    std::regex include("#include \"([a-z_]+)/");
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        std::string ext = entry.path().extension().string();
        if (ext != ".h" && ext != ".cpp") continue;
        int floor = own;
        if (floor < 0) {
            std::string top = fs::relative(entry.path(), dir).begin()->string();
            auto it = kFloor.find(top);
            if (it == kFloor.end()) continue;
            floor = it->second;
        }
        std::ifstream in(entry.path());
        std::string line;
        while (std::getline(in, line)) {
            std::smatch m;
            if (!std::regex_search(line, m, include)) continue;
            auto it = kFloor.find(m[1].str());
            if (it != kFloor.end() && it->second > floor)
                found.push_back(entry.path().string() + " includes " + m[1].str() + "/");
        }
    }
    return found;
}

}  // namespace

TEST_CASE("includes point down the floors: apps, render, stages, scene, image, core") {
    std::vector<std::string> bad = violations(pt::test::source_path("src"), -1);
    for (const std::string& b : bad)
        MESSAGE(b);
    CHECK(bad.empty());
}

TEST_CASE("student files include only the stages floor and below") {
    std::vector<std::string> bad = violations(pt::test::source_path("assignments"), kFloor.at("stages"));
    for (const std::string& b : bad)
        MESSAGE(b);
    CHECK(bad.empty());
}

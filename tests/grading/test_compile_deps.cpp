// The two guards that keep the project's .cpp files out of a submission's
// compile (docs/grading.md "How a submission is built"): the headers-only
// view of src/ that bubblewrap binds in its place, and the check of the
// compiler's dependency lists where bubblewrap does not run.
#include <doctest/doctest.h>

#include <filesystem>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "grade/compile_deps.h"
#include "grade/header_view.h"

namespace fs = std::filesystem;
using namespace pt;

namespace {
const std::string kRoot = std::string(PT_TEST_OUTPUT_DIR) + "/compile_deps";
}

TEST_CASE("the headers-only view holds every header of src/ and nothing else") {
    const std::string view = kRoot + "/view";
    fs::remove_all(kRoot);
    fs::create_directories(view + "/stale");
    std::ofstream(view + "/stale/old.cpp") << "left from before\n";
    const size_t copied = make_header_view(std::string(PT_SOURCE_DIR) + "/src", view);
    size_t headers = 0, others = 0;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(std::string(PT_SOURCE_DIR) + "/src"))
        if (e.is_regular_file()) (is_header(e.path()) ? headers : others)++;
    CHECK(copied == headers);
    CHECK(others > 100);  // the reference .cpp files the view leaves out
    size_t in_view = 0;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(view))
        if (e.is_regular_file()) {
            ++in_view;
            CHECK_MESSAGE(is_header(e.path()), e.path());
        }
    CHECK(in_view == headers);  // the stale file is gone too
    CHECK(fs::exists(view + "/stages/bvh.h"));
    CHECK_FALSE(fs::exists(view + "/stages/camera.cpp"));
    CHECK(fs::last_write_time(view + "/stages/bvh.h") ==
          fs::last_write_time(std::string(PT_SOURCE_DIR) + "/src/stages/bvh.h"));
}

TEST_CASE("dependency lists: GCC's make format and ninja -t deps") {
    const CompileDeps d = parse_make_deps(
        "CMakeFiles/ptstudent.dir/a.cpp.o: /sub/my\\ dir/part1/a.cpp \\\n"
        " /usr/include/stdc-predef.h ../src/stages/camera.cpp \\\n  /p/x$$y.h\n");
    CHECK(d.source == "/sub/my dir/part1/a.cpp");
    REQUIRE(d.files.size() == 4);
    CHECK(d.files[2] == "../src/stages/camera.cpp");
    CHECK(d.files[3] == "/p/x$y.h");

    const std::vector<CompileDeps> n = parse_ninja_deps(
        "CMakeFiles/o.dir/a.cpp.o: #deps 2, deps mtime 1 (VALID)\n    /s/a.cpp\n    /s/b.h\n\n"
        "CMakeFiles/o.dir/c.cpp.o: #deps 1, deps mtime 1 (VALID)\n    /s/c.cpp\n");
    REQUIRE(n.size() == 2);
    CHECK(n[0].source == "/s/a.cpp");
    CHECK(n[0].files.size() == 2);
    CHECK(n[1].files == std::vector<std::string>{"/s/c.cpp"});
}

TEST_CASE("a source of src/ read by a compile is found, through a link or a relative path") {
    const std::string src = std::string(PT_SOURCE_DIR) + "/src";
    fs::create_directories(kRoot + "/sub");
    fs::remove(kRoot + "/sub/ref.h");
    fs::create_symlink(src + "/stages/camera.cpp", kRoot + "/sub/ref.h");
    const std::string build = kRoot + "/build";
    fs::create_directories(build);
    const std::string rel = fs::relative(src, build).string();
    CHECK(project_source_read({"/usr/include/stdc-predef.h", src + "/stages/camera.h"}, src, build) == "");
    CHECK(project_source_read({rel + "/stages/camera.cpp"}, src, build) ==
          fs::canonical(src + "/stages/camera.cpp").string());
    CHECK(project_source_read({kRoot + "/sub/ref.h"}, src, build) ==
          fs::canonical(src + "/stages/camera.cpp").string());
}

TEST_CASE("under Ninja the lists come from ninja -t deps (the .d files are gone)") {
    // What class_build.cpp runs for a Ninja build folder: `cmake --build
    // DIR -- -t deps`. A toy project whose source includes a .cpp of a
    // stand-in src/ folder through the include path.
    if (std::system("command -v ninja > /dev/null 2>&1") != 0) {
        MESSAGE("ninja is not installed: skipped");
        return;
    }
    const std::string dir = kRoot + "/ninja";
    fs::remove_all(dir);
    fs::create_directories(dir + "/src/stages");
    fs::create_directories(dir + "/sub");
    std::ofstream(dir + "/src/stages/ref.cpp") << "inline int reference_answer() { return 42; }\n";
    std::ofstream(dir + "/src/stages/api.h") << "#pragma once\n";
    std::ofstream(dir + "/sub/a.cpp") << "#include \"stages/api.h\"\n#include \"stages/ref.cpp\"\n"
                                         "int f() { return reference_answer(); }\n";
    std::ofstream(dir + "/CMakeLists.txt")
        << "cmake_minimum_required(VERSION 3.20)\nproject(toy CXX)\n"
           "add_library(student OBJECT sub/a.cpp)\ntarget_include_directories(student PRIVATE src)\n";
    const std::string b = dir + "/build";
    REQUIRE(std::system(("cmake -G Ninja -S " + dir + " -B " + b + " > " + dir + "/log.txt 2>&1").c_str()) == 0);
    REQUIRE(std::system(("cmake --build " + b + " >> " + dir + "/log.txt 2>&1").c_str()) == 0);
    bool any_d = false;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(b))
        any_d = any_d || e.path().extension() == ".d";
    CHECK_FALSE(any_d);  // why the Makefile way would find nothing
    REQUIRE(std::system(("cmake --build " + b + " -- -t deps > " + dir + "/deps.txt 2>&1").c_str()) == 0);
    std::ifstream in(dir + "/deps.txt");
    std::stringstream text;
    text << in.rdbuf();
    const std::vector<CompileDeps> deps = parse_ninja_deps(text.str());
    REQUIRE(deps.size() == 1);
    CHECK(fs::weakly_canonical(fs::path(b) / deps[0].source) == fs::weakly_canonical(dir + "/sub/a.cpp"));
    CHECK(project_source_read(deps[0].files, dir + "/src", b) ==
          fs::canonical(dir + "/src/stages/ref.cpp").string());
}

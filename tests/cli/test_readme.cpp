// The README and the handouts say what the program prints; these tests run
// their commands (with small images where the fact does not depend on the
// size) and fail when a printed fact drifts from the text (issue 22: "36
// triangles" where the loader printed 32, a transcript that no longer
// matched). The README's images are checked by scripts/readme_images.sh,
// which re-renders them at full size (minutes, so not in ctest).
#include <doctest/doctest.h>

#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "test_util.h"

using namespace pt::test;

namespace {

std::string readme() { return read_file(source_path("README.md")); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

/// A scratch folder where "assets/..." and "build/bin/..." resolve as they
/// do in a checkout, so that commands run exactly as the README spells them
/// and print the same paths, without writing into the source tree.
std::string checkout_like(const std::string& name) {
    std::string dir = scratch_dir(name);
    REQUIRE(run("ln -s '" + source_path("assets") + "' '" + dir + "/assets' && mkdir -p '" + dir + "/build' && ln -s '" +
                    std::string(PT_BIN_DIR) + "' '" + dir + "/build/bin'",
                dir)
                .exit_code == 0);
    return dir;
}

/// Stdout and stderr of a shell command in `dir`, merged in the order a
/// terminal shows them (line-buffered, as on a terminal).
std::string terminal_output(const std::string& command, const std::string& dir) {
    return run("cd '" + dir + "' && " + command + " 2>&1", dir).out;
}

/// Timings and rates vary from run to run: every decimal number becomes #.
std::string without_decimals(const std::string& line) {
    return std::regex_replace(line, std::regex("[0-9]+\\.[0-9]+"), "#");
}

/// The code block of `text` that contains `marker`.
std::string block_with(const std::string& text, const std::string& marker) {
    size_t at = text.find(marker);
    REQUIRE(at != std::string::npos);
    size_t start = text.rfind("```", at), end = text.find("```", at);
    REQUIRE(start != std::string::npos);
    REQUIRE(end != std::string::npos);
    return text.substr(text.find('\n', start) + 1, end - text.find('\n', start) - 1);
}

/// The rows of the Markdown table that follows `marker`, split into cells.
std::vector<std::vector<std::string>> table_after(const std::string& text, const std::string& marker) {
    size_t at = text.find(marker);
    REQUIRE(at != std::string::npos);
    std::vector<std::vector<std::string>> rows;
    bool in_table = false;
    for (const std::string& line : split_lines(text.substr(at))) {
        if (line.rfind("|", 0) != 0) {
            if (in_table) break;
            continue;
        }
        in_table = true;
        if (line.find("---") != std::string::npos) continue;
        std::vector<std::string> cells;
        std::istringstream in(line.substr(1));
        for (std::string cell; std::getline(in, cell, '|');) {
            cell.erase(0, cell.find_first_not_of(' '));
            cell.erase(cell.find_last_not_of(' ') + 1);
            cells.push_back(cell);
        }
        rows.push_back(cells);
    }
    return rows;
}

/// The value of a "program: key: value" line in the output.
std::string printed(const std::string& output, const std::string& key) {
    for (const std::string& line : split_lines(output)) {
        size_t at = line.find(": " + key + ": ");
        if (at != std::string::npos) return line.substr(at + key.size() + 4);
    }
    return "";
}

}  // namespace

TEST_CASE("the README's part1 transcript is what part1 prints") {
    std::string dir = checkout_like("readme_part1");
    // Each "$ command" of the block, run in turn in one shell (so that
    // "echo $?" sees the command before it); "..." in the README skips lines.
    std::string block = block_with(readme(), "$ build/bin/part1 -r 320 240 -f mine.png");
    std::vector<std::string> expected, script;
    for (const std::string& line : split_lines(block)) {
        if (line.rfind("$ ", 0) == 0) {
            script.push_back(line.substr(2) + (line.find("echo") == std::string::npos ? " 2>&1" : ""));
            continue;
        }
        expected.push_back(line);
    }
    std::string shell;
    for (const std::string& s : script) shell += (s.rfind("echo", 0) == 0 ? "" : "stdbuf -oL -eL ") + s + "\n";
    write_file(dir + "/transcript.sh", shell);
    std::vector<std::string> actual = split_lines(terminal_output("sh transcript.sh", dir));
    size_t a = 0;
    for (size_t e = 0; e < expected.size(); ++e) {
        CAPTURE(expected[e]);
        if (expected[e] == "...") {  // skip to the next expected line
            REQUIRE(e + 1 < expected.size());
            while (a < actual.size() && without_decimals(actual[a]) != without_decimals(expected[e + 1])) ++a;
            continue;
        }
        REQUIRE(a < actual.size());
        CHECK(without_decimals(actual[a]) == without_decimals(expected[e]));
        ++a;
    }
}

TEST_CASE("the README's effects table is what the renderer prints at -m 5") {
    std::string dir = checkout_like("readme_effects");
    auto rows = table_after(readme(), "| scene | effects | integrator | skipped |");
    REQUIRE(rows.size() >= 5);
    for (size_t r = 1; r < rows.size(); ++r) {
        REQUIRE(rows[r].size() == 4);
        const std::string names = rows[r][0];
        const std::regex quoted("`([a-z_]+)`");
        for (std::sregex_iterator it(names.begin(), names.end(), quoted), end; it != end; ++it) {
            std::string scene = (*it)[1];
            CAPTURE(scene);
            std::string out = terminal_output(
                "build/bin/pathtracer -q -t 2 -r 4 4 -m 5 -f out.png assets/scenes/" + scene + ".json", dir);
            CHECK(printed(out, "effects") == rows[r][1]);
            CHECK(printed(out, "integrator").rfind(rows[r][2] + " (", 0) == 0);
            // The table leaves out the reasons in parentheses.
            CHECK(std::regex_replace(printed(out, "skipped"), std::regex(" \\([^)]*\\)"), "") == rows[r][3]);
        }
    }
    // "At the default -m 1, cbox gets the direct integrator and whitted the Whitted integrator."
    REQUIRE(contains(readme(), "At the default `-m 1`, `cbox` gets the direct integrator and `whitted` the\nWhitted integrator."));
    CHECK(printed(terminal_output("build/bin/pathtracer -q -r 4 4 -f o.png assets/scenes/cbox.json", dir), "integrator")
              .rfind("direct (", 0) == 0);
    CHECK(printed(terminal_output("build/bin/pathtracer -q -r 4 4 -f o.png assets/scenes/whitted.json", dir),
                  "integrator")
              .rfind("whitted (", 0) == 0);
}

TEST_CASE("the README's BVH table: triangles, nodes and depth of the asset scenes as bench bvh builds them") {
    std::string dir = checkout_like("readme_bvh");
    auto rows = table_after(readme(), "| scene | triangles | build ms | nodes | depth |");
    std::string out = terminal_output(
        "build/bin/bench bvh assets/scenes/cbox.json assets/scenes/cbox_knot.json --no-linear --no-kernels -r 16 12 -t 1",
        dir);
    auto measured = table_after(out, "| scene ");
    int checked = 0;
    for (const auto& row : rows) {
        for (const auto& m : measured) {
            if (m.size() < 7 || row.size() < 5 || m[0] != row[0] || m[0] == "scene") continue;
            CAPTURE(row[0]);
            CHECK(m[2] == row[1]);  // triangles
            CHECK(m[5] == row[3]);  // nodes
            CHECK(m[6] == row[4]);  // depth
            ++checked;
        }
    }
    CHECK(checked == 2);
}

TEST_CASE("triangle counts the handouts and docs state are what the loader prints") {
    std::string dir = checkout_like("readme_counts");
    struct Fact {
        std::string document, claim, scene, printed;
    };
    const Fact facts[] = {
        {"assignments/part2/README.md", "Cornell box\n(32 triangles)", "assets/scenes/cbox.json", "32 triangles"},
        {"assignments/part2/README.md", "generated torus knot of 5,800 triangles", "assets/scenes/knot.json",
         "5800 triangles"},
        {"docs/scenes.md", "a generated 5,800-triangle torus knot", "assets/scenes/knot.json", "5800 triangles"},
        {"README.md", "a generated 10,000-triangle torus knot", "assets/scenes/cbox_knot.json", "10012 triangles"},
    };
    for (const Fact& f : facts) {
        CAPTURE(f.claim);
        CHECK(contains(read_file(source_path(f.document)), f.claim));
        CHECK(contains(terminal_output("build/bin/pathtracer -q -r 4 4 -f o.png " + f.scene, dir), f.printed));
    }
    // The ray_cost row says how many rays its command traces.
    CHECK(contains(readme(), "the same 300,000 shadow rays"));
    CHECK(contains(readme(), "`build/tests/ray_cost SCENE --rays 300000 --accel bvh`"));
    std::string tools = std::string(PT_BIN_DIR) + "/../tests/";
    CHECK(contains(terminal_output("'" + tools + "ray_cost' assets/scenes/cbox.json --rays 3000 --accel bvh", dir),
                   "3000 shadow rays"));
}

TEST_CASE("every scene the README and docs/scenes.md name exists, and docs/scenes.md names every asset scene") {
    namespace fs = std::filesystem;
    std::string docs = read_file(source_path("docs/scenes.md")), text = readme() + docs;
    std::regex scene_path("assets/(scenes|meshes|env)/[A-Za-z0-9_]+\\.(json|obj|mtl|hdr)");
    for (std::sregex_iterator it(text.begin(), text.end(), scene_path), end; it != end; ++it) {
        CAPTURE(it->str());
        CHECK(file_exists(source_path(it->str())));
    }
    for (const auto& entry : fs::directory_iterator(source_path("assets/scenes"))) {
        std::string name = entry.path().filename().string();
        if (name.rfind("grading_", 0) == 0) continue;  // listed as assets/scenes/grading_*.json
        INFO("add a row for assets/scenes/" << name << " to docs/scenes.md (\"The scenes and meshes that ship\")");
        CHECK(contains(docs, "`assets/scenes/" + name + "`"));
    }
    // No document a clone has points at ../shared (the clone does not have it),
    // except the optional real meshes of bench bvh --shared.
    for (const char* document : {"README.md", "assignments/part1/README.md", "assignments/part2/README.md",
                                 "assignments/part3/README.md", "assignments/part4/README.md",
                                 "assignments/part5/README.md", "docs/scenes.md"}) {
        CAPTURE(document);
        for (const std::string& line : split_lines(read_file(source_path(document))))
            if (contains(line, "../shared")) CHECK(contains(line, "--shared"));
    }
}

// The last unsafe inputs of issue 22, from the command line: each is one
// line naming the file and what was wrong, exit code 2, and neither a hang
// nor memory that grows without bound.
#include <doctest/doctest.h>

#include <sys/stat.h>

#include <algorithm>
#include <string>

#include "test_util.h"

using namespace pt::test;

namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

size_t lines(const std::string& s) {
    size_t n = size_t(std::count(s.begin(), s.end(), '\n'));
    return (!s.empty() && s.back() != '\n') ? n + 1 : n;
}

/// pathtracer on `scene` in `dir`, under a 60-second timeout (a hang fails
/// the test with exit code 124 instead of stalling the suite), after `prefix`
/// (e.g. a ulimit).
CommandResult render(const std::string& dir, const std::string& scene, const std::string& prefix = "") {
    return run("cd '" + dir + "' && " + prefix + "timeout 60 '" + bin_path("pathtracer") + "' -q -t 2 -r 8 8 -f x.png " +
                   scene,
               dir);
}

const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

void expect_error(const CommandResult& r, const std::string& message) {
    CHECK(r.exit_code == 2);
    CHECK(contains(r.err, "pathtracer: error: " + message));
    CHECK(lines(r.err) == 1);
}

}  // namespace

TEST_CASE("an MTL path must be a regular file: /dev/zero and a fifo are refused at once") {
    std::string dir = scratch_dir("unsafe_mtl_path");
    write_file(dir + "/zero.obj", "mtllib ../../../../../../../../../../dev/zero\n" + std::string(kTriangle) + "f 1 2 3\n");
    expect_error(render(dir, "zero.obj"),
                 "zero.obj: mtllib: cannot read ../../../../../../../../../../dev/zero: not a regular file");
    REQUIRE(mkfifo((dir + "/fifo.mtl").c_str(), 0644) == 0);
    write_file(dir + "/fifo.obj", "mtllib fifo.mtl\n" + std::string(kTriangle) + "f 1 2 3\n");
    expect_error(render(dir, "fifo.obj"), "fifo.obj: mtllib: cannot read fifo.mtl: not a regular file");
    write_file(dir + "/absent.obj", "mtllib absent.mtl\n" + std::string(kTriangle) + "f 1 2 3\n");
    expect_error(render(dir, "absent.obj"), "absent.obj: material library 'absent.mtl' not found (absent.mtl)");
}

TEST_CASE("face indices that overflow an int are errors, not other vertices") {
    std::string dir = scratch_dir("unsafe_obj_index");
    struct Case {
        std::string face, message;
    };
    const Case cases[] = {
        {"f 1 2 4294967299", "line 4: face corner '4294967299': vertex index 4294967299 is out of range (OBJ "
                             "indices here are at most 2147483647)"},
        {"f 1 2 2147483648", "line 4: face corner '2147483648': vertex index 2147483648 is out of range"},
        {"f 1 2 -2147483648", "line 4: face corner '-2147483648': vertex index -2147483648 is out of range"},
        {"f 1 2 3/1/99999999999999999999", "line 4: face corner '3/1/99999999999999999999': normal index "
                                           "99999999999999999999 is out of range"},
        {"f 1 2 0", "line 4: face corner '0': vertex index 0 (OBJ indices start at 1, or count back from -1)"},
        {"f 1 2 3x", "line 4: face corner '3x': '3x' is not a vertex index"},
        {"f 1 2 2147483647", "face in '' uses vertex 2147483647 but the file has 3"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.face);
        write_file(dir + "/m.obj", std::string(kTriangle) + c.face + "\n");
        expect_error(render(dir, "m.obj"), "m.obj: " + c.message);
    }
}

TEST_CASE("scene and mesh files are size-checked before they are read") {
    std::string dir = scratch_dir("unsafe_sizes");
    // Sparse 2 GB files: they take no disk space, and would take 4 GB of
    // memory if read whole (ulimit -v: more than 1 GB would fail the test).
    REQUIRE(run("truncate -s 2G '" + dir + "/big.json' '" + dir + "/big.obj'", dir).exit_code == 0);
    expect_error(render(dir, "big.json", "ulimit -v 1000000 && "),
                 "scene: big.json is 2147483648 bytes; a scene file (meshes go in OBJ files) is at most 67108864 bytes");
    expect_error(render(dir, "big.obj", "ulimit -v 1000000 && "),
                 "big.obj: line 1 is longer than 1048576 bytes (not an OBJ file?)");
    // A PFM header that promises 65536 x 65536 pixels (48 GB) in a 20-byte file.
    write_file(dir + "/huge.pfm", "PF\n65536 65536\n-1.0\n");
    expect_error(render(dir, "-e huge.pfm " + source_path("assets/scenes/cbox.json"), "ulimit -v 1000000 && "),
                 "huge.pfm: PFM pixel data is truncated");
}

TEST_CASE("the triangle limit comes from the machine's memory, and the message says it") {
    std::string dir = scratch_dir("unsafe_triangle_cap");
    // ulimit -v 500000 (KiB): 0.512 GB usable, 3/4 of it for geometry at
    // 256 + 64/2 bytes per triangle: at most 1,333,333 triangles.
    const std::string limit = "ulimit -v 500000 && ";
    write_file(dir + "/knot.json", R"({"camera": {"position": [0, 0, 6], "look_at": [0, 0, 0]},
        "materials": {"m": {"type": "diffuse"}},
        "objects": [{"type": "torus_knot", "segments": 100000, "sides": 20, "material": "m"}]})");
    expect_error(render(dir, "knot.json", limit),
                 "knot.json: objects[0] (2 * segments * sides): 4,000,000 triangles and 2,000,000 vertices need about "
                 "1.2 GB, more than this machine can hold: at most 1,333,333 triangles (3/4 of its 0.5 GB of memory, "
                 "at about 256 bytes per triangle)");
    // An OBJ is counted before tinyobjloader reads it: 1.6 million faces.
    std::string faces;
    for (int i = 0; i < 100000; ++i) faces += "f 1 2 3\n";
    std::string obj = kTriangle;
    for (int i = 0; i < 16; ++i) obj += faces;
    write_file(dir + "/many.obj", obj);
    expect_error(render(dir, "many.obj", limit),
                 "many.obj: 1,600,000 triangles and 3 vertices need about 0.4 GB, more than this machine can hold: at "
                 "most 1,333,333 triangles");
}

TEST_CASE("a negative Ni and a duplicate JSON key are errors") {
    std::string dir = scratch_dir("unsafe_ni_duplicates");
    write_file(dir + "/glass.obj", "mtllib glass.mtl\n" + std::string(kTriangle) + "usemtl g\nf 1 2 3\n");
    write_file(dir + "/glass.mtl", "newmtl g\nillum 7\nNi -1.5\n");
    expect_error(render(dir, "glass.obj"),
                 "glass.obj: glass.mtl: line 3: Ni (index of refraction of 'g') must be a finite number >= 0, got '-1.5'");
    write_file(dir + "/glass.mtl", "newmtl g\nillum 7\nNi 0\n");
    expect_error(render(dir, "glass.obj"), "glass.obj: material 'g': glass (illum 7) needs Ni > 0, got 0");

    write_file(dir + "/dup.json", R"({"materials": {"m": {"type": "diffuse"}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"},
                    {"type": "sphere", "center": [0, 0, 0], "radius": 1, "radius": 2, "material": "m"}]})");
    expect_error(render(dir, "dup.json"),
                 "dup.json: objects[1]: duplicate key \"radius\" (a JSON object takes each key once)");
    write_file(dir + "/dup2.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "materials": {"m": {"type": "diffuse"}}, "materials": {},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
    expect_error(render(dir, "dup2.json"), "dup2.json: top level: duplicate key \"materials\"");
}

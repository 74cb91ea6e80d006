// The Part 2 command lines: --bvh-view and --bvh-depth-image of the
// renderer, and the bench subcommands, on tiny inputs (exit codes, files
// written, one-line errors).
#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace {

struct Run {
    int code;            ///< exit code
    std::string output;  ///< stdout and stderr together
};

Run run(const std::string& command) {
    // ctest runs test cases in parallel processes: one log per process.
    const std::string log =
        std::string(PT_TEST_OUTPUT_DIR) + "/bvh_cli_" + std::to_string(getpid()) + ".log";
    int status = std::system((command + " > " + log + " 2>&1").c_str());
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

std::string bin(const std::string& name) {
    return std::string(PT_BIN_DIR) + "/" + name;
}
std::string out(const std::string& name) {
    return std::string(PT_TEST_OUTPUT_DIR) + "/" + name;
}
std::string scene(const std::string& name) {
    return std::string(PT_SOURCE_DIR) + "/assets/scenes/" + name;
}

bool exists(const std::string& path) {
    return std::ifstream(path).good();
}

int count_lines(const std::string& text) {
    int n = 0;
    for (char c : text)
        n += c == '\n';
    return n;
}

}  // namespace

TEST_CASE("pathtracer --bvh-view and --bvh-depth-image write their images") {
    std::remove(out("bvh_view.png").c_str());
    std::remove(out("bvh_depth.png").c_str());
    Run r = run(bin("pathtracer") + " -q -t 2 -r 48 36 --bvh-view RL -f " + out("bvh_view.png") +
                " --bvh-depth-image " + out("bvh_depth.png") + " " + scene("cbox_knot.json"));
    INFO(r.output);
    CHECK(r.code == 0);
    CHECK(exists(out("bvh_view.png")));
    CHECK(exists(out("bvh_depth.png")));
    CHECK(r.output.find("bvh view: node 'RL'") != std::string::npos);
    CHECK(r.output.find("nodes visited per camera ray") != std::string::npos);
}

TEST_CASE("pathtracer --bvh-view: bad paths are one-line errors with exit code 2") {
    for (const char* path : {"RX", "LLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLL"}) {
        Run r = run(bin("pathtracer") + " -q -r 8 6 --bvh-view " + path + " -f " +
                    out("bvh_bad.png") + " " + scene("cbox.json"));
        INFO(r.output);
        CHECK(r.code == 2);
        CHECK(r.output.find("error: --bvh-view") != std::string::npos);
    }
    Run r = run(bin("pathtracer") + " -q -r 8 6 --accel none --bvh-view R -f " +
                out("bvh_bad.png") + " " + scene("cbox.json"));
    CHECK(r.code == 2);
    r = run(bin("pathtracer") + " -q -r 8 6 --bvh-depth-image x.jpg " + scene("cbox.json"));
    CHECK(r.code == 2);
}

TEST_CASE("bench bvh prints its table; bad options exit with code 2") {
    Run r = run(bin("bench") + " bvh --budget 0.05 --kernel-seconds 0 -r 16 12 -t 1 --json " +
                out("bvh_bench.json") + " " + scene("cbox.json") + " --shared " +
                out("bvh_no_such_dir"));
    INFO(r.output);
    CHECK(r.code == 0);
    CHECK(r.output.find("| cbox") != std::string::npos);
    CHECK(r.output.find("no shared meshes in") != std::string::npos);
    CHECK(exists(out("bvh_bench.json")));
    for (const char* bad :
         {"bvh --bogus", "bvh -r 0 10", "bvh --budget x", "nonsense", "scaling --sizes 3"}) {
        Run b = run(bin("bench") + " " + bad);
        INFO(bad << ": " << b.output);
        CHECK(b.code == 2);
        CHECK(count_lines(b.output) == 1);
    }
}

TEST_CASE("bench scaling runs on small sizes") {
    Run r = run(bin("bench") + " scaling --sizes 200,2k --kernel-seconds 0 -r 16 12");
    INFO(r.output);
    CHECK(r.code == 0);
    CHECK(r.output.find("log2 n") != std::string::npos);
}

namespace {

std::string file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

/// "from_packets": N of a --stats file.
long from_packets(const std::string& stats_path) {
    std::string text = file_bytes(stats_path);
    size_t at = text.find("\"from_packets\":");
    if (at == std::string::npos) return -1;
    return std::atol(text.c_str() + at + std::string("\"from_packets\":").size());
}

}  // namespace

TEST_CASE("pathtracer --packets on gives --packets off's image bit for bit, with camera rays answered from packets") {
    // Partial packets (width 37), bounces, adaptive sampling (the split
    // rule's decision samples are not packed), the thin lens, a fisheye's
    // rays that see nothing, another sampler, two threads.
    const char* const cases[] = {
        "-r 37 21 -s 1 --integrator normals cbox.json",
        "-r 24 16 -s 4 -m 3 --integrator path cbox.json",
        "-r 24 16 -s 8 -a 4 0.05 -m 2 cbox_knot.json",
        "-r 24 16 -s 8 -a 4 0.05 --adaptive cs184 cbox.json",
        "-r 24 16 -s 4 -b 0.05 -d 3 -m 2 cbox_spheres.json",
        "-r 24 16 -s 2 camera_fisheye.json",
        "-r 24 16 -s 4 --sampler independent -t 2 -m 2 cbox.json",
    };
    for (const char* args : cases) {
        CAPTURE(args);
        std::string a(args);
        size_t space = a.rfind(' ');
        std::string flags = a.substr(0, space), file = scene(a.substr(space + 1));
        std::string images[2];
        long packed[2];
        for (int on = 0; on < 2; ++on) {
            std::string name = std::string("packets_") + (on ? "on" : "off");
            Run r = run(bin("pathtracer") + " -q " + flags + " --packets " + (on ? "on" : "off") + " -f " +
                        out(name + ".png") + " --hdr " + out(name + ".pfm") + " --stats " + out(name + ".json") +
                        " " + file);
            REQUIRE(r.code == 0);
            images[on] = file_bytes(out(name + ".pfm"));
            packed[on] = from_packets(out(name + ".json"));
        }
        CHECK(!images[0].empty());
        CHECK(images[0] == images[1]);
        CHECK(packed[0] == 0);
        CHECK(packed[1] > 0);
    }
}

TEST_CASE("--packets takes on or off; anything else is one line and exit code 2") {
    Run r = run(bin("pathtracer") + " -q -r 8 6 --packets maybe " + scene("cbox.json"));
    CHECK(r.code == 2);
    CHECK(r.output.find("--packets: expected one of on, off, got 'maybe'") != std::string::npos);
    CHECK(count_lines(r.output) == 1);
}

// Outputs that never lie (issue 22): every write is checked and atomic
// (core/atomic_file.h), every output path is checked before rendering, and
// no output may replace an input.
#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "test_util.h"

using namespace pt::test;

namespace {

const std::string kScene = source_path("assets/scenes/cbox.json");

std::string app(const std::string& name, const std::string& args) { return "'" + bin_path(name) + "' " + args; }

size_t lines(const std::string& s) {
    size_t n = size_t(std::count(s.begin(), s.end(), '\n'));
    return (!s.empty() && s.back() != '\n') ? n + 1 : n;
}

/// The names in a folder other than "." and "..", sorted, space-separated.
std::string listing(const std::string& dir, const std::string& scratch) {
    return run("ls -A '" + dir + "' | sort | tr '\\n' ' '", scratch).out;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// Runs `command` in a private mount namespace with a `kilobytes` tmpfs
/// mounted on `mount_point` (unshare -rm: as root, or as a user where user
/// namespaces are allowed). False when the tmpfs cannot be mounted here.
bool run_on_small_tmpfs(const std::string& mount_point, int kilobytes, const std::string& command,
                        const std::string& scratch, CommandResult* result) {
    CommandResult probe = run("unshare -rm sh -c 'mount -t tmpfs -o size=" + std::to_string(kilobytes) +
                                  "k tmpfs \"" + mount_point + "\"' 2>&1 && echo mounted",
                              scratch);
    if (!contains(probe.out, "mounted")) return false;
    std::string script = "mount -t tmpfs -o size=" + std::to_string(kilobytes) + "k tmpfs '" + mount_point +
                         "' && cd '" + mount_point + "' && " + command;
    // The script goes through a file: it is quoted for sh -c only once.
    write_file(scratch + "/tmpfs_script.sh", script + "\nstatus=$?\nls -A '" + mount_point +
                                                 "' > '" + scratch + "/tmpfs_listing.txt'\n"
                                                 "cat '" + mount_point + "/a.png' > '" + scratch +
                                                 "/tmpfs_a.txt' 2>/dev/null\nexit $status\n");
    *result = run("unshare -rm sh '" + scratch + "/tmpfs_script.sh'", scratch);
    return true;
}

}  // namespace

TEST_CASE("a write to /dev/full through a symbolic link exits 2 with the path and the reason") {
    std::string dir = scratch_dir("outputs_dev_full");
    REQUIRE(symlink("/dev/full", (dir + "/full.png").c_str()) == 0);
    REQUIRE(symlink("/dev/full", (dir + "/full.pfm").c_str()) == 0);
    REQUIRE(symlink("/dev/full", (dir + "/full.json").c_str()) == 0);
    struct Case {
        std::string command, message;
    };
    const std::string r = "-q -t 2 -r 16 12 ";
    const Case cases[] = {
        {app("pathtracer", r + "-f " + dir + "/full.png " + kScene), "cannot write " + dir + "/full.png"},
        {app("pathtracer", r + "-f " + dir + "/ok.png --hdr " + dir + "/full.pfm " + kScene),
         "cannot write " + dir + "/full.pfm"},
        {app("pathtracer", r + "-f " + dir + "/ok.png --stats " + dir + "/full.json " + kScene),
         "cannot write " + dir + "/full.json"},
        {app("make_sky", dir + "/full.pfm 8 4 30 0"), "cannot write " + dir + "/full.pfm"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.command);
        CommandResult result = run(c.command, dir);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.err, c.message + ": No space left on device"));
        CHECK(lines(result.err) == 1);
        CHECK_FALSE(contains(result.out, "wrote " + dir + "/full"));
    }
    // imgdiff's heat map, from two images the renders above left behind.
    REQUIRE(file_exists(dir + "/ok.png"));
    CommandResult diff = run(app("imgdiff", dir + "/ok.png " + dir + "/ok.png --heatmap " + dir + "/full.png"), dir);
    CHECK(diff.exit_code == 2);
    CHECK(contains(diff.err, "imgdiff: error: cannot write " + dir + "/full.png: No space left on device"));
    // The links are still links: nothing was renamed over them.
    struct stat st;
    REQUIRE(lstat((dir + "/full.png").c_str(), &st) == 0);
    CHECK(S_ISLNK(st.st_mode));
}

TEST_CASE("a full disk: exit 2 with the reason, the old file intact, no temporary left behind") {
    std::string dir = scratch_dir("outputs_full_disk");
    std::string mount_point = dir + "/small";
    REQUIRE(run("mkdir -p '" + mount_point + "'", dir).exit_code == 0);
    CommandResult r;
    // 16 KiB: room for the old 4-byte file, not for a 320x240 PNG of noise.
    bool mounted = run_on_small_tmpfs(
        mount_point, 16,
        "printf old > a.png && " + app("pathtracer", "-q -t 2 -r 320 240 -s 2 -f a.png --hdr b.pfm " + kScene), dir,
        &r);
    if (!mounted) {
        MESSAGE("skipped: cannot mount a tmpfs here (unshare -rm mount -t tmpfs failed); the /dev/full test still ran");
        return;
    }
    CHECK(r.exit_code == 2);
    CHECK(contains(r.err, "cannot write a.png: No space left on device"));
    CHECK(lines(r.err) == 1);
    // The old a.png is untouched, and neither a temporary nor b.pfm exists.
    CHECK(read_file(dir + "/tmpfs_a.txt") == "old");
    CHECK(read_file(dir + "/tmpfs_listing.txt") == "a.png\n");
}

TEST_CASE("an output that is one of the inputs is refused before rendering") {
    std::string dir = scratch_dir("outputs_inputs");
    CommandResult made = run(app("make_sky", dir + "/e.pfm 16 8 30 0"), dir);
    REQUIRE(made.exit_code == 0);
    std::string env = read_file(dir + "/e.pfm");
    CommandResult r = run(app("pathtracer", "-q -r 8 8 -e " + dir + "/e.pfm -f " + dir + "/x.png --hdr " + dir +
                                                "/e.pfm " + kScene),
                          dir);
    CHECK(r.exit_code == 2);
    CHECK(contains(r.err, "--hdr: " + dir + "/e.pfm is an input of this run; writing it would destroy the input"));
    CHECK(lines(r.err) == 1);
    CHECK(read_file(dir + "/e.pfm") == env);
    CHECK_FALSE(file_exists(dir + "/x.png"));

    // Another spelling of the same file is caught too (device and inode).
    write_file(dir + "/scene.json", R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "materials": {"m": {"type": "diffuse"}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
    r = run("cd '" + dir + "' && " + app("pathtracer", "-q -r 8 8 -f x.png --stats ./scene.json " + dir + "/scene.json"),
            dir);
    CHECK(r.exit_code == 2);
    CHECK(contains(r.err, "--stats: ./scene.json is the same file as " + dir + "/scene.json, an input of this run"));

    // imgdiff: the heat map may not replace either image, nor go into an input folder.
    run(app("pathtracer", "-q -r 8 8 -f " + dir + "/a.png " + kScene), dir);
    run(app("pathtracer", "-q -r 8 8 -s 2 -f " + dir + "/b.png " + kScene), dir);
    std::string a = read_file(dir + "/a.png");
    REQUIRE(!a.empty());
    r = run(app("imgdiff", dir + "/a.png " + dir + "/b.png --heatmap " + dir + "/a.png"), dir);
    CHECK(r.exit_code == 2);
    CHECK(contains(r.err, "--heatmap: " + dir + "/a.png is an input of this run"));
    CHECK(read_file(dir + "/a.png") == a);
    r = run(app("imgdiff", "--dir " + dir + " " + dir + " --heatmap-dir " + dir), dir);
    CHECK(r.exit_code == 2);
    CHECK(contains(r.err, "--heatmap-dir: " + dir + " is an input of this run"));
    CHECK(read_file(dir + "/a.png") == a);
}

TEST_CASE("every output path is checked before rendering") {
    std::string dir = scratch_dir("outputs_checked_first");
    struct Case {
        std::string args, message;
    };
    const Case cases[] = {
        {"--hdr /proc/x.pfm", "--hdr: cannot write /proc/x.pfm: "},
        {"--stats " + dir + "/missing/s.json", "--stats: cannot write " + dir + "/missing/s.json: No such file or directory"},
        {"--bvh-depth-image " + dir + "/missing/d.png", "--bvh-depth-image: cannot write " + dir + "/missing/d.png"},
        {"--stats " + dir, "--stats: cannot write " + dir + ": is a folder"},
        {"-a 4 0.1 -f " + dir + "/rate_dir.png", "-a (sample-rate image): cannot write " + dir + "/rate_dir_rate.png: is a folder"},
    };
    REQUIRE(run("mkdir -p '" + dir + "/rate_dir_rate.png'", dir).exit_code == 0);
    for (const Case& c : cases) {
        CAPTURE(c.args);
        std::string png = dir + "/out.png";
        std::string args = c.args.find("-f ") == std::string::npos ? "-f " + png + " " + c.args : c.args;
        CommandResult r = run(app("pathtracer", "-q -r 8 8 " + args + " " + kScene), dir);
        CHECK(r.exit_code == 2);
        CHECK(contains(r.err, c.message));
        CHECK(lines(r.err) == 1);
        CHECK_FALSE(contains(r.out, "effects:"));  // stopped before it planned the render
        CHECK_FALSE(file_exists(png));
        CHECK_FALSE(file_exists(dir + "/rate_dir.png"));
    }
    // bench checks its --json before measuring anything.
    CommandResult r = run(app("bench", "bvh " + kScene + " --json " + dir + "/missing/b.json"), dir);
    CHECK(r.exit_code == 2);
    CHECK(contains(r.err, "bvh: --json: cannot write " + dir + "/missing/b.json"));
    CHECK(r.out.empty());
    CHECK_FALSE(file_exists(dir + "/missing"));
}

TEST_CASE("a symbolic link to an output is followed; new files get the usual permissions") {
    std::string dir = scratch_dir("outputs_link");
    write_file(dir + "/target.png", "old");
    REQUIRE(symlink("target.png", (dir + "/link.png").c_str()) == 0);
    CommandResult r = run(app("pathtracer", "-q -r 8 8 -f " + dir + "/link.png " + kScene), dir);
    REQUIRE(r.exit_code == 0);
    struct stat st;
    REQUIRE(lstat((dir + "/link.png").c_str(), &st) == 0);
    CHECK(S_ISLNK(st.st_mode));
    CHECK(read_file(dir + "/target.png").substr(1, 3) == "PNG");
    CHECK(listing(dir, dir) == "link.png stderr.txt target.png ");
    // 0666 minus the umask, as fopen would give (mkstemp alone gives 0600).
    mode_t mask = umask(0);
    umask(mask);
    REQUIRE(stat((dir + "/target.png").c_str(), &st) == 0);
    CHECK((st.st_mode & 0777) == (0666 & ~mask));
}

TEST_CASE("--stats /dev/stdout writes into the pipe, not over a file") {
    std::string dir = scratch_dir("outputs_stdout");
    CommandResult r = run(app("pathtracer", "-q -r 4 4 -f " + dir + "/x.png --stats /dev/stdout " + kScene) + " | cat", dir);
    CHECK(r.exit_code == 0);
    CHECK(contains(r.out, "\"program\": \"pathtracer\""));
    CHECK(contains(r.out, "pathtracer: wrote " + dir + "/x.png"));
}

TEST_CASE("AtomicFile: the target changes only on commit, and a failed write names the file") {
    std::string base = scratch_dir("outputs_atomic_unit"), dir = base + "/files";
    REQUIRE(run("mkdir '" + dir + "'", base).exit_code == 0);
    write_file(dir + "/t.txt", "old");
    {
        pt::AtomicFile file(dir + "/t.txt");
        file.write("new, but never committed");
        CHECK(read_file(dir + "/t.txt") == "old");
    }  // destroyed without commit: the temporary goes, the target stays
    CHECK(read_file(dir + "/t.txt") == "old");
    CHECK(listing(dir, base) == "t.txt ");
    pt::write_file_atomically(dir + "/t.txt", "new");
    CHECK(read_file(dir + "/t.txt") == "new");
    CHECK(listing(dir, base) == "t.txt ");
    CHECK_THROWS_WITH_AS(pt::write_file_atomically(dir + "/no/t.txt", "x"),
                         doctest::Contains(("cannot write " + dir + "/no/t.txt: No such file or directory").c_str()),
                         pt::InputError);
    CHECK_THROWS_WITH_AS(pt::write_file_atomically(dir, "x"), doctest::Contains("is a folder"), pt::InputError);
    // Devices are written directly: /dev/null takes anything.
    CHECK_NOTHROW(pt::write_file_atomically("/dev/null", "x"));
}

// The command lines of imgdiff and grade: outputs and exit codes
// (DESIGN.md: 0 pass, 1 fail, 2 bad input).
#include <doctest/doctest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "image/image_io.h"

namespace {

std::string bin(const std::string& name) {
    return std::string(PT_BIN_DIR) + "/" + name;
}
// Each test case works in its own folder: ctest runs them in parallel.
std::string sandbox = "shared";
std::string out(const std::string& name) {
    return std::string(PT_TEST_OUTPUT_DIR) + "/cli_grading/" + sandbox + "/" + name;
}

/// Runs a command; returns its exit code and puts stdout+stderr in *output.
int run(const std::string& command, std::string* output = nullptr) {
    std::string log = out("last_command.txt");
    int status = std::system((command + " > " + log + " 2>&1").c_str());
    if (output) {
        std::ifstream in(log);
        std::stringstream s;
        s << in.rdbuf();
        *output = s.str();
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

pt::Image gradient(int w, int h, double shift = 0) {
    pt::Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            img.set(x, y, pt::Color(double(x) / w + shift, double(y) / h, 0.25));
    return img;
}

struct Files {
    explicit Files(const std::string& folder) {
        sandbox = folder;
        std::filesystem::create_directories(out("a"));
        std::filesystem::create_directories(out("b"));
        pt::write_png(gradient(16, 8), out("ref.png"));
        pt::write_png(gradient(16, 8), out("same.png"));
        pt::write_png(gradient(16, 8, 0.1), out("shifted.png"));
        pt::write_pfm(gradient(16, 8), out("ref.pfm"));
        pt::write_png(gradient(8, 8), out("small.png"));
        std::ofstream(out("text.png")) << "not an image";
        pt::write_png(gradient(16, 8), out("a/one.png"));
        pt::write_png(gradient(16, 8, 0.1), out("a/two.png"));
        pt::write_png(gradient(16, 8), out("b/one.png"));
        pt::write_png(gradient(16, 8), out("b/two.png"));
        pt::write_png(gradient(16, 8), out("b/three.png"));
    }
};

}  // namespace

TEST_CASE("imgdiff: metrics, heat map and exit codes 0, 1, 2") {
    Files files("imgdiff_pair");
    std::string text;
    CHECK(run(bin("imgdiff") + " " + out("same.png") + " " + out("ref.png") + " --max-relmse 0",
              &text) == 0);
    CHECK(text.find("relMSE             0") != std::string::npos);
    CHECK(text.find("inf dB") != std::string::npos);

    std::filesystem::remove(out("heat.png"));
    CHECK(run(bin("imgdiff") + " " + out("shifted.png") + " " + out("ref.png") + " --heatmap " +
                  out("heat.png") + " --max-relmse 1e-3",
              &text) == 1);
    CHECK(text.find("FAIL: relMSE") != std::string::npos);
    CHECK(text.find("pixels over") != std::string::npos);
    CHECK(pt::read_png(out("heat.png")).width() == 16);
    CHECK(run(bin("imgdiff") + " " + out("shifted.png") + " " + out("ref.png") +
              " --max-relmse 1") == 0);
    CHECK(run(bin("imgdiff") + " " + out("shifted.png") + " " + out("ref.png") +
              " --max-rmse 0.01") == 1);
    // PNG against PFM: the PNG is decoded to linear, so the two agree to quantisation.
    CHECK(run(bin("imgdiff") + " " + out("same.png") + " " + out("ref.pfm") + " --max-rmse 0.01") ==
          0);

    CHECK(run(bin("imgdiff") + " " + out("missing.png") + " " + out("ref.png"), &text) == 2);
    CHECK(text.find("no such file") != std::string::npos);
    CHECK(run(bin("imgdiff") + " " + out("small.png") + " " + out("ref.png"), &text) == 2);
    CHECK(text.find("sizes differ: 8x8 against 16x8") != std::string::npos);
    CHECK(run(bin("imgdiff") + " " + out("text.png") + " " + out("ref.png"), &text) == 2);
    CHECK(text.find("not a readable PNG") != std::string::npos);
    CHECK(run(bin("imgdiff") + " " + out("ref.png"), &text) == 2);
    CHECK(run(bin("imgdiff") + " a.png b.png --max-relmse x", &text) == 2);
    CHECK(text.find("--max-relmse") != std::string::npos);
}

TEST_CASE("imgdiff --dir: compares by file name and reports missing counterparts") {
    Files files("imgdiff_dir");
    std::string text;
    CHECK(run(bin("imgdiff") + " --dir " + out("a") + " " + out("b") +
                  " --max-relmse 1e-3 --heatmap-dir " + out("heat"),
              &text) == 1);
    CHECK(text.find("one.png") != std::string::npos);
    CHECK(text.find("missing in " + out("a")) != std::string::npos);
    CHECK(text.find("FAIL: relMSE") != std::string::npos);
    CHECK(std::filesystem::exists(out("heat/one.png")));
    CHECK(run(bin("imgdiff") + " --dir " + out("a") + " " + out("nope")) == 2);
}

TEST_CASE("grade: writes the three reports; exit 1 unless every task passes; 2 for bad flags") {
    sandbox = "grade";
    std::filesystem::create_directories(out(""));
    std::string dir = out("grade_report");
    std::filesystem::remove_all(dir);
    std::string text;
    int code = run(bin("grade") + " -q -t 2 --out " + dir + " --cache " +
                       std::string(PT_TEST_OUTPUT_DIR) + "/grade_cache",
                   &text);
    INFO(text);
    CHECK((code == 0 || code == 1));
    for (const char* f : {"report.md", "report.html", "report.json"})
        CHECK(std::filesystem::exists(dir + "/" + f));
    nlohmann::json j = nlohmann::json::parse(std::ifstream(dir + "/report.json"));
    size_t tasks = 0;  // every task of every part with a manifest
    for (int part = 1; part <= 9; ++part) {
        std::ifstream m(std::string(PT_SOURCE_DIR) + "/assignments/part" + std::to_string(part) +
                        "/grading.json");
        if (m) tasks += nlohmann::json::parse(m)["tasks"].size();
    }
    CHECK(tasks >= 22);
    CHECK(j["tasks"].size() == tasks);
    CHECK((code == 0) == j["all_passed"].get<bool>());
    bool handout = j["tasks"][0]["status"] == "not implemented";
    if (handout) {
        // This build is the handout: every task is "not implemented", 0 points.
        CHECK(code == 1);
        CHECK(j["points"] == 0);
        for (const auto& t : j["tasks"])
            CHECK(t["status"] == "not implemented");
    }
    CHECK(run(bin("grade") + " --seed x", &text) == 2);
    CHECK(run(bin("grade") + " --task part9.9 --out " + dir, &text) == 2);
    CHECK(text.find("part9.9") != std::string::npos);
    CHECK(run(bin("grade") + " --manifests " + out("nowhere") + " --out " + dir, &text) == 2);
    CHECK(run(bin("grade") + " --list-checks", &text) == 0);
    CHECK(text.find("intersect_sphere") != std::string::npos);
}

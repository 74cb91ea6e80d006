#include "apps/deliverables.h"

#include <chrono>
#include <filesystem>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/render_app.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/files.h"

namespace pt {
namespace {

struct Deliverable {
    std::string name;               ///< image file name without .png
    std::string caption;            ///< what the image must show, for the write-up
    std::vector<std::string> args;  ///< partN's flags and scene (paths relative to the project)
    double minutes = 0;             ///< measured time on 2 cores, shown in the handout and the page
};

std::vector<Deliverable> read_list(const std::string& path) {
    std::string text = read_small_file(path, "deliverables list", 1 << 20, "a deliverables list");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw InputError(path + ": not valid JSON (" + e.what() + ")");
    }
    if (!j.is_object() || !j.contains("deliverables") || !j["deliverables"].is_array())
        throw InputError(path + ": expected {\"deliverables\": [...]}");
    std::vector<Deliverable> list;
    for (size_t i = 0; i < j["deliverables"].size(); ++i) {
        const nlohmann::json& d = j["deliverables"][i];
        const std::string where = path + ": deliverables[" + std::to_string(i) + "]";
        if (!d.is_object() || !d.contains("name") || !d["name"].is_string() || !d.contains("caption") ||
            !d["caption"].is_string() || !d.contains("args") || !d["args"].is_array())
            throw InputError(where + ": expected \"name\", \"caption\" and \"args\"");
        Deliverable x{d["name"].get<std::string>(), d["caption"].get<std::string>(), {},
                      d.value("minutes_on_2_cores", 0.0)};
        for (const nlohmann::json& a : d["args"]) {
            if (!a.is_string()) throw InputError(where + ".args: expected strings");
            x.args.push_back(a.get<std::string>());
        }
        if (x.name.empty() || x.name.find_first_of("/\\. ") != std::string::npos)
            throw InputError(where + ".name: expected a plain file name without extension");
        list.push_back(x);
    }
    return list;
}

std::string html_escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '&') out += "&amp;";
        else out += c;
    }
    return out;
}

std::string command_line(const std::vector<std::string>& args) {
    std::string s;
    for (const std::string& a : args) s += (s.empty() ? "" : " ") + a;
    return s;
}

}  // namespace

int render_deliverables(int part, const std::string& dir, int threads) {
    const std::string program = "part" + std::to_string(part);
    std::string list_path = std::string(PT_STUDENT_DIR_PATH) + "/" + program + "/deliverables.json";
    if (!std::filesystem::exists(list_path))
        list_path = std::string(PT_SOURCE_DIR) + "/assignments/" + program + "/deliverables.json";
    std::vector<Deliverable> list = read_list(list_path);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw InputError("--deliverables " + dir + ": cannot create the folder (" + ec.message() + ")");
    std::ostringstream page;
    page << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>Part " << part
         << " write-up images</title>\n<style>body{font-family:sans-serif;max-width:60em;margin:auto}"
            "figure{margin:2em 0}img{max-width:100%;image-rendering:pixelated}code{background:#eee;"
            "padding:2px 4px}</style></head><body>\n<h1>Part "
         << part << ": the images of the write-up</h1>\n<p>Rendered with your code by <code>" << program
         << " --deliverables</code>.</p>\n";
    int status = 0;
    for (const Deliverable& d : list) {
        // The scene path (the last argument) is relative to the project.
        std::vector<std::string> args = d.args;
        std::vector<std::string> argv_text = {program};
        for (size_t i = 0; i < args.size(); ++i)
            argv_text.push_back(i + 1 == args.size() ? std::string(PT_SOURCE_DIR) + "/" + args[i] : args[i]);
        for (const std::string& extra : {std::string("-f"), dir + "/" + d.name + ".png", std::string("-q")})
            argv_text.push_back(extra);
        if (threads > 0) argv_text.push_back("-t"), argv_text.push_back(std::to_string(threads));
        std::vector<char*> argv;
        for (std::string& a : argv_text) argv.push_back(a.data());
        // An image left from an earlier run must not pass for this code's.
        const std::string image = dir + "/" + d.name + ".png", rate = dir + "/" + d.name + "_rate.png";
        std::filesystem::remove(image, ec);
        std::filesystem::remove(rate, ec);
        std::cerr << program << ": deliverable " << d.name << ": " << command_line(args) << "\n";
        auto start = std::chrono::steady_clock::now();
        int code = run_render_app(int(argv.size()), argv.data(), program, StageSet::of_part(part));
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (code != 0 && status == 0) status = code;
        const std::string shown = program + " " + command_line(args) + " -f " + d.name + ".png";
        page << "<figure>\n";
        if (code == 0) {
            page << "<img src=\"" << d.name << ".png\" alt=\"" << html_escape(d.caption) << "\">\n";
            // Adaptive sampling (-a) writes the sample-rate image beside it.
            if (std::filesystem::exists(rate))
                page << "<img src=\"" << d.name << "_rate.png\" alt=\"the sample rate of " << html_escape(d.name)
                     << "\">\n";
        } else {
            page << "<p><b>Not rendered</b> (exit code " << code
                 << (code == 3 ? ": a function is not implemented yet" : "") << ").</p>\n";
        }
        char time[64];
        std::snprintf(time, sizeof time, "%.1f s here", seconds);
        page << "<figcaption>" << html_escape(d.caption) << "<br><code>" << html_escape(shown) << "</code> ("
             << time;
        if (d.minutes > 0) page << "; about " << d.minutes << " min on 2 cores";
        page << ")</figcaption>\n</figure>\n";
    }
    page << "</body></html>\n";
    write_file_atomically(dir + "/index.html", page.str());
    std::cerr << program << ": wrote " << dir << "/index.html (" << list.size() << " images)\n";
    return status;
}

}  // namespace pt

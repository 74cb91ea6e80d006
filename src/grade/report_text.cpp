// report.md and report.json (report.h).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "grade/report.h"

namespace pt {

std::string format_points(double points) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", points);
    return buf;
}

std::string format_figure(const TaskResult& r) {
    if (r.status == TaskStatus::not_implemented || std::isnan(r.value)) return "-";
    char buf[128];
    std::snprintf(buf, sizeof buf, "%s %.4g %s %.4g", r.metric.c_str(), r.value,
                  r.comparison.c_str(), r.threshold);
    return buf;
}

namespace {

/// Table cells may not contain '|' or line breaks.
std::string md_cell(std::string s) {
    for (char& c : s)
        if (c == '|' || c == '\n') c = c == '|' ? '/' : ' ';
    return s;
}

const char* status_word(TaskStatus s) {
    switch (s) {
        case TaskStatus::pass:
            return "PASS";
        case TaskStatus::fail:
            return "FAIL";
        case TaskStatus::not_implemented:
            return "NOT IMPLEMENTED";
    }
    return "?";
}

}  // namespace

std::string markdown_report(const GradeReport& report) {
    std::string md = "# Grade report\n\n";
    md += "**Total: " + format_points(report.points()) + " / " +
          format_points(report.max_points()) + " points**";
    md += report.all_passed() ? " (every task passes)\n\n" : "\n\n";
    md += "- student code: `" + report.student_dir + "`\n";
    md += "- seed: " + std::to_string(report.seed) + ", graded " + report.date + " in ";
    char secs[32];
    std::snprintf(secs, sizeof secs, "%.1f s", report.seconds);
    md += std::string(secs) + "\n";
    for (const std::string& p : report.parts)
        md += "- graded: " + p + "\n";
    for (const std::string& n : report.notes)
        md += "- note: " + n + "\n";
    md += "\n| part | task | name | result | points | figure | message |\n";
    md += "|---|---|---|---|---|---|---|\n";
    for (const TaskResult& t : report.tasks) {
        md += "| " + std::to_string(t.part) + " | " + t.id + " | " + md_cell(t.name) + " | " +
              status_word(t.status) + " | " + format_points(t.points) + " / " +
              format_points(t.max_points) + " | " + md_cell(format_figure(t)) + " | " +
              md_cell(t.message) + " |\n";
    }
    for (const TaskResult& t : report.tasks) {
        if (t.details.empty() && t.images.empty()) continue;
        md += "\n## " + t.id + " " + t.name + ": " + status_word(t.status) + "\n\n";
        for (const std::string& d : t.details)
            md += "- " + d + "\n";
        for (const ImageCaseResult& c : t.images) {
            md += "\n### " + c.label + ": " + (c.pass ? "pass" : "FAIL") + "\n\n";
            if (!c.student_png.empty())
                md += "student `" + c.student_png + "`, reference `" + c.reference_png +
                      "`, heat map `" + c.heatmap_png + "`\n\n";
            for (const auto& [name, value] : c.numbers)
                md += "- " + name + ": " + value + "\n";
        }
    }
    return md;
}

nlohmann::json json_report(const GradeReport& report) {
    using nlohmann::json;
    json j;
    j["version"] = 1;
    j["student_dir"] = report.student_dir;
    j["seed"] = report.seed;
    j["date"] = report.date;
    j["seconds"] = report.seconds;
    j["points"] = report.points();
    j["max_points"] = report.max_points();
    j["all_passed"] = report.all_passed();
    j["parts"] = report.parts;
    j["notes"] = report.notes;
    j["tasks"] = json::array();
    for (const TaskResult& t : report.tasks) {
        json task = {{"part", t.part},
                     {"id", t.id},
                     {"name", t.name},
                     {"check", t.check},
                     {"type", to_string(t.type)},
                     {"status", to_string(t.status)},
                     {"points", t.points},
                     {"max_points", t.max_points},
                     {"metric", t.metric},
                     {"comparison", t.comparison},
                     {"threshold", t.threshold},
                     {"message", t.message},
                     {"details", t.details},
                     {"seconds", t.seconds}};
        // JSON has no NaN or infinity: an unmeasured figure is null.
        task["value"] = std::isfinite(t.value) ? json(t.value) : json(nullptr);
        if (!std::isfinite(t.threshold)) task["threshold"] = nullptr;
        task["images"] = json::array();
        for (const ImageCaseResult& c : t.images) {
            json numbers = json::object();
            for (const auto& [name, value] : c.numbers)
                numbers[name] = value;
            task["images"].push_back({{"label", c.label},
                                      {"pass", c.pass},
                                      {"message", c.message},
                                      {"student", c.student_png},
                                      {"reference", c.reference_png},
                                      {"reference_same_spp", c.reference_same_spp_png},
                                      {"heatmap", c.heatmap_png},
                                      {"numbers", numbers}});
        }
        j["tasks"].push_back(task);
    }
    return j;
}

void write_reports(const GradeReport& report, const std::string& out_dir) {
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    if (!std::filesystem::is_directory(out_dir))
        throw InputError("--out: cannot create the folder " + out_dir);
    auto write = [&](const std::string& name, const std::string& text) {
        std::ofstream out(out_dir + "/" + name);
        if (!(out << text)) throw InputError("--out: cannot write " + out_dir + "/" + name);
    };
    write("report.md", markdown_report(report));
    write("report.json", json_report(report).dump(2) + "\n");
    write("report.html", html_report(report, out_dir));
}

}  // namespace pt

// report.md and report.json (report.h).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "grade/report.h"
#include "grade/task_json.h"

namespace pt {

std::string format_points(double points) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", points);
    return buf;
}

std::string format_figure(const TaskResult& r) {
    if (r.status == TaskStatus::not_implemented || r.status == TaskStatus::not_submitted ||
        std::isnan(r.value))
        return "-";
    // The relation that holds, so that a failing figure reads "4.7 > 1e-06".
    bool at_most = r.comparison == "<=";
    bool holds = at_most ? r.value <= r.threshold : r.value >= r.threshold;
    const char* op = holds ? (at_most ? "<=" : ">=") : (at_most ? ">" : "<");
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s %.4g %s %.4g", r.metric.c_str(), r.value, op, r.threshold);
    return buf;
}

namespace {

/// Table cells may not contain line breaks, and '|' must be escaped.
std::string md_cell(const std::string& s) {
    std::string out;
    for (char c : s)
        out += c == '|' ? std::string("\\|") : std::string(1, c == '\n' ? ' ' : c);
    return out;
}

const char* status_word(TaskStatus s) {
    switch (s) {
        case TaskStatus::pass:
            return "PASS";
        case TaskStatus::fail:
            return "FAIL";
        case TaskStatus::not_implemented:
            return "NOT IMPLEMENTED";
        case TaskStatus::not_submitted:
            return "NOT SUBMITTED";
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
    for (const TaskResult& t : report.tasks)
        j["tasks"].push_back(task_to_json(t));
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

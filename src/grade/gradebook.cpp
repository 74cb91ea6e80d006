#include "grade/gradebook.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/files.h"
#include "grade/report.h"
#include "grade/task_json.h"

namespace pt {
namespace {

using nlohmann::json;

struct Column {
    int part = 0;
    int number = 0;
    std::string id, name;
    double max_points = 0;
};

/// Every task of any record, in course order (part, then task number).
std::vector<Column> columns_of(const std::vector<StudentRecord>& records) {
    std::map<std::pair<int, std::pair<int, std::string>>, Column> by_order;
    for (const StudentRecord& r : records)
        for (const TaskResult& t : r.tasks) {
            const size_t dot = t.id.rfind('.');
            int number = dot == std::string::npos ? 0 : std::atoi(t.id.c_str() + dot + 1);
            auto key = std::make_pair(t.part, std::make_pair(number, t.id));
            if (!by_order.count(key)) by_order[key] = Column{t.part, number, t.id, t.name, t.max_points};
        }
    std::vector<Column> out;
    for (const auto& [key, c] : by_order)
        out.push_back(c);
    return out;
}

const TaskResult* find_task(const StudentRecord& r, const std::string& id) {
    for (const TaskResult& t : r.tasks)
        if (t.id == id) return &t;
    return nullptr;
}

std::string csv_field(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s)
        out += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' || c == '\r' ? ' ' : c);
    return out + "\"";
}

std::string html_escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '&') out += "&amp;";
        else if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '"') out += "&quot;";
        else out += c;
    }
    return out;
}

std::string md_cell(const std::string& s) {
    std::string out;
    for (char c : s)
        out += c == '|' ? std::string("\\|") : std::string(1, c == '\n' ? ' ' : c);
    return out;
}

/// A failure message with its figures blanked ("845 of 13500 cases" ->
/// "# of # cases"), so that the same mistake with other numbers counts once.
std::string message_shape(const std::string& m) {
    std::string out;
    bool in_number = false;
    for (size_t i = 0; i < m.size(); ++i) {
        const char c = m[i];
        const bool digit = c >= '0' && c <= '9';
        const bool number_part = digit || (in_number && (c == '.' || c == 'e' || c == '-' || c == '+'));
        if (number_part) {
            if (!in_number) out += '#';
            in_number = true;
        } else {
            in_number = false;
            out += c;
        }
    }
    return out;
}

std::string shorten(const std::string& s, size_t n) {
    return s.size() <= n ? s : s.substr(0, n - 3) + "...";
}

std::string percent(size_t k, size_t n) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.0f%%", n ? 100.0 * double(k) / double(n) : 0.0);
    return buf;
}

struct TaskStats {
    Column column;
    size_t pass = 0, fail = 0, not_implemented = 0, not_submitted = 0, no_compile = 0;
    std::string common_failure;  ///< an example of the most common failure shape
    size_t common_count = 0;
};

std::vector<TaskStats> task_stats(const std::vector<StudentRecord>& records) {
    std::vector<TaskStats> out;
    for (const Column& c : columns_of(records)) {
        TaskStats s;
        s.column = c;
        std::map<std::string, std::pair<size_t, std::string>> shapes;
        for (const StudentRecord& r : records) {
            const TaskResult* t = find_task(r, c.id);
            if (r.outcome != "graded") {
                ++s.no_compile;
                continue;
            }
            if (!t || t->status == TaskStatus::not_submitted) {
                ++s.not_submitted;
                continue;
            }
            if (t->status == TaskStatus::pass) ++s.pass;
            if (t->status == TaskStatus::not_implemented) ++s.not_implemented;
            if (t->status == TaskStatus::fail) {
                ++s.fail;
                auto& entry = shapes[message_shape(t->message)];
                if (entry.first++ == 0) entry.second = t->message;
            }
        }
        for (const auto& [shape, entry] : shapes)  // ties: the first shape in byte order
            if (entry.first > s.common_count) {
                s.common_count = entry.first;
                s.common_failure = entry.second;
            }
        out.push_back(s);
    }
    return out;
}

/// Ten bins of the total as a share of the maximum: 0-9%, ..., 90-100%.
std::vector<size_t> histogram(const std::vector<StudentRecord>& records) {
    std::vector<size_t> bins(10, 0);
    for (const StudentRecord& r : records) {
        const double share = r.max_points() > 0 ? r.points() / r.max_points() : 0;
        bins[size_t(std::min(9.0, std::max(0.0, std::floor(share * 10 + 1e-9))))]++;
    }
    return bins;
}

std::string bin_label(size_t i) {
    return std::to_string(i * 10) + "-" + std::to_string(i == 9 ? 100 : i * 10 + 9) + "%";
}

struct Overview {
    size_t students = 0, graded = 0, no_compile = 0, failed = 0, partial = 0;
    double mean = 0, median = 0, max_points = 0;
};

Overview overview(const std::vector<StudentRecord>& records) {
    Overview o;
    o.students = records.size();
    std::vector<double> totals;
    for (const StudentRecord& r : records) {
        totals.push_back(r.points());
        o.max_points = std::max(o.max_points, r.max_points());
        if (r.outcome == "graded") ++o.graded;
        if (r.outcome == "does not compile") ++o.no_compile;
        if (r.outcome == "grading failed") ++o.failed;
        for (const TaskResult& t : r.tasks)
            if (t.status == TaskStatus::not_submitted) {
                ++o.partial;
                break;
            }
    }
    std::sort(totals.begin(), totals.end());
    for (double t : totals)
        o.mean += t / double(std::max<size_t>(1, totals.size()));
    if (!totals.empty())
        o.median = totals.size() % 2 ? totals[totals.size() / 2]
                                     : 0.5 * (totals[totals.size() / 2 - 1] + totals[totals.size() / 2]);
    return o;
}

std::string fixed1(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", v);
    return buf;
}

}  // namespace

double StudentRecord::points() const {
    double p = 0;
    for (const TaskResult& t : tasks)
        p += t.points;
    return p;
}

double StudentRecord::max_points() const {
    double p = 0;
    for (const TaskResult& t : tasks)
        p += t.max_points;
    return p;
}

void write_class_json(const StudentRecord& r, const std::string& student_out_dir) {
    json j = {{"student", r.name}, {"outcome", r.outcome}, {"note", r.note}};
    write_file_atomically(student_out_dir + "/class.json", j.dump(2) + "\n");
}

StudentRecord read_student_record(const std::string& dir) {
    StudentRecord r;
    const std::string class_path = dir + "/class.json", report_path = dir + "/report.json";
    try {
        json c = json::parse(read_small_file(class_path, "grade", 1 << 20, "a class.json"));
        r.name = c.at("student").get<std::string>();
        r.outcome = c.at("outcome").get<std::string>();
        r.note = c.at("note").get<std::string>();
    } catch (const json::exception& e) {
        throw InputError(class_path + ": not a class.json written by grade --class (" + e.what() + ")");
    }
    try {
        json rep = json::parse(read_small_file(report_path, "grade", 256 << 20, "a report.json"));
        for (const json& t : rep.at("tasks"))
            r.tasks.push_back(task_from_json(t));
    } catch (const json::exception& e) {
        throw InputError(report_path + ": not a report.json written by grade (" + e.what() + ")");
    }
    return r;
}

std::string gradebook_csv(const std::vector<StudentRecord>& records) {
    const std::vector<Column> columns = columns_of(records);
    std::string csv = "student";
    for (const Column& c : columns)
        csv += "," + csv_field(c.id);
    csv += ",total,max,outcome,note\n";
    for (const StudentRecord& r : records) {
        csv += csv_field(r.name);
        for (const Column& c : columns) {
            const TaskResult* t = find_task(r, c.id);
            csv += "," + (t ? format_points(t->points) : std::string("0"));
        }
        csv += "," + format_points(r.points()) + "," + format_points(r.max_points()) + "," +
               csv_field(r.outcome) + "," + csv_field(r.note) + "\n";
    }
    return csv;
}

std::string summary_markdown(const std::vector<StudentRecord>& records) {
    const Overview o = overview(records);
    std::string md = "# Class summary\n\n";
    md += "- students: " + std::to_string(o.students) + " (" + std::to_string(o.graded) + " graded, " +
          std::to_string(o.no_compile) + " do not compile, " + std::to_string(o.failed) +
          " grading failed; " + std::to_string(o.partial) + " submit only some parts)\n";
    md += "- total: mean " + fixed1(o.mean) + ", median " + fixed1(o.median) + " of " +
          format_points(o.max_points) + " points\n\n";
    md += "## Score histogram\n\n| total | students | |\n|---|---|---|\n";
    const std::vector<size_t> bins = histogram(records);
    for (size_t i = 0; i < bins.size(); ++i)
        md += "| " + bin_label(i) + " | " + std::to_string(bins[i]) + " | " + std::string(bins[i], '#') +
              " |\n";
    md += "\n## Tasks\n\n| task | name | points | pass | fail | not implemented | not submitted | "
          "no build | most common failure |\n|---|---|---|---|---|---|---|---|---|\n";
    for (const TaskStats& s : task_stats(records)) {
        md += "| " + s.column.id + " | " + md_cell(s.column.name) + " | " +
              format_points(s.column.max_points) + " | " + std::to_string(s.pass) + " (" +
              percent(s.pass, o.students) + ") | " + std::to_string(s.fail) + " | " +
              std::to_string(s.not_implemented) + " | " + std::to_string(s.not_submitted) + " | " +
              std::to_string(s.no_compile) + " | " +
              (s.common_count ? std::to_string(s.common_count) + " x: " +
                                    md_cell(shorten(s.common_failure, 200))
                              : std::string("-")) +
              " |\n";
    }
    bool any = false;
    for (const StudentRecord& r : records)
        if (r.outcome != "graded") {
            if (!any) md += "\n## Submissions not graded\n\n";
            any = true;
            md += "- " + r.name + ": " + r.outcome + (r.note.empty() ? "" : ": " + md_cell(r.note)) + "\n";
        }
    return md;
}

std::string summary_html(const std::vector<StudentRecord>& records) {
    const Overview o = overview(records);
    std::string h =
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>Class summary</title>\n<style>\n"
        "body { font: 15px/1.45 system-ui, sans-serif; margin: 24px auto; max-width: 1180px; padding: 0 16px; }\n"
        "table { border-collapse: collapse; width: 100%; margin: 10px 0; }\n"
        "th, td { border-bottom: 1px solid #d0d7de; padding: 4px 8px; text-align: left; vertical-align: top; }\n"
        "td.num { text-align: right; white-space: nowrap; }\n"
        ".bar { background: #2da44e; height: 14px; display: inline-block; }\n"
        ".rate { background: #eaeef2; width: 120px; height: 14px; display: inline-block; }\n"
        ".rate span { background: #2da44e; height: 14px; display: block; }\n"
        ".msg { color: #57606a; font-size: 13px; }\n</style></head><body>\n";
    h += "<h1>Class summary</h1>\n<p>" + std::to_string(o.students) + " students: " +
         std::to_string(o.graded) + " graded, " + std::to_string(o.no_compile) + " do not compile, " +
         std::to_string(o.failed) + " grading failed; " + std::to_string(o.partial) +
         " submit only some parts. Total: mean " + fixed1(o.mean) + ", median " + fixed1(o.median) +
         " of " + format_points(o.max_points) + " points. Per student: <a href=\"gradebook.csv\">gradebook.csv</a>, "
         "and <code>NAME/report.html</code>.</p>\n";
    h += "<h2>Score histogram</h2>\n<table><tr><th>total</th><th>students</th><th></th></tr>\n";
    const std::vector<size_t> bins = histogram(records);
    const size_t most = std::max<size_t>(1, *std::max_element(bins.begin(), bins.end()));
    for (size_t i = 0; i < bins.size(); ++i)
        h += "<tr><td>" + bin_label(i) + "</td><td class=\"num\">" + std::to_string(bins[i]) +
             "</td><td><span class=\"bar\" style=\"width:" + std::to_string(bins[i] * 400 / most) +
             "px\"></span></td></tr>\n";
    h += "</table>\n<h2>Tasks</h2>\n<table><tr><th>task</th><th>name</th><th>points</th><th>pass "
         "rate</th><th>fail</th><th>not implemented</th><th>not submitted</th><th>no "
         "build</th><th>most common failure</th></tr>\n";
    for (const TaskStats& s : task_stats(records)) {
        const size_t width = o.students ? s.pass * 120 / o.students : 0;
        h += "<tr><td>" + html_escape(s.column.id) + "</td><td>" + html_escape(s.column.name) +
             "</td><td class=\"num\">" + format_points(s.column.max_points) +
             "</td><td class=\"num\">" + std::to_string(s.pass) + " (" + percent(s.pass, o.students) +
             ") <span class=\"rate\"><span style=\"width:" + std::to_string(width) +
             "px\"></span></span></td><td class=\"num\">" + std::to_string(s.fail) +
             "</td><td class=\"num\">" + std::to_string(s.not_implemented) + "</td><td class=\"num\">" +
             std::to_string(s.not_submitted) + "</td><td class=\"num\">" + std::to_string(s.no_compile) +
             "</td><td class=\"msg\">" +
             (s.common_count ? std::to_string(s.common_count) + " &times; " +
                                   html_escape(shorten(s.common_failure, 300))
                             : std::string("-")) +
             "</td></tr>\n";
    }
    h += "</table>\n";
    bool any = false;
    for (const StudentRecord& r : records)
        if (r.outcome != "graded") {
            if (!any) h += "<h2>Submissions not graded</h2>\n<ul>\n";
            any = true;
            h += "<li><a href=\"" + html_escape(r.name) + "/report.html\">" + html_escape(r.name) +
                 "</a>: " + html_escape(r.outcome) + (r.note.empty() ? "" : ": " + html_escape(r.note)) +
                 "</li>\n";
        }
    if (any) h += "</ul>\n";
    return h + "</body></html>\n";
}

void write_class_outputs(std::vector<StudentRecord> records, const std::string& out_dir) {
    std::sort(records.begin(), records.end(),
              [](const StudentRecord& a, const StudentRecord& b) { return a.name < b.name; });
    write_file_atomically(out_dir + "/gradebook.csv", gradebook_csv(records));
    write_file_atomically(out_dir + "/summary.md", summary_markdown(records));
    write_file_atomically(out_dir + "/summary.html", summary_html(records));
}

}  // namespace pt

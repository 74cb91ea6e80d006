// report.html (report.h): one self-contained page, images embedded as
// base64 data URIs, so that it can be mailed or attached to an LMS as is.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "grade/report.h"
#include "image/colormap.h"

namespace pt {
namespace {

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&':
                out += "&amp;";
                break;
            case '<':
                out += "&lt;";
                break;
            case '>':
                out += "&gt;";
                break;
            case '"':
                out += "&quot;";
                break;
            default:
                out += c;
        }
    }
    return out;
}

std::string base64(const std::string& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 |
                     uint8_t(bytes[i + 2]);
        for (int k = 3; k >= 0; --k)
            out += table[(v >> (6 * k)) & 63];
    }
    if (i < bytes.size()) {
        uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

/// A data URI of the PNG at out_dir/relative, or "" when it is missing.
std::string data_uri(const std::string& out_dir, const std::string& relative) {
    if (relative.empty()) return "";
    std::ifstream in(out_dir + "/" + relative, std::ios::binary);
    if (!in) return "";
    std::stringstream s;
    s << in.rdbuf();
    return "data:image/png;base64," + base64(s.str());
}

const char* css_class(TaskStatus s) {
    switch (s) {
        case TaskStatus::pass:
            return "pass";
        case TaskStatus::fail:
            return "fail";
        case TaskStatus::not_implemented:
        case TaskStatus::not_submitted:
            return "todo";
    }
    return "";
}

const char* badge(TaskStatus s) {
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
    return "";
}

const char* kStyle = R"(
body { font: 15px/1.45 system-ui, -apple-system, "Segoe UI", sans-serif; margin: 24px auto; max-width: 1180px;
       padding: 0 16px; color: #1f2328; }
h1 { margin: 0 0 4px; font-size: 26px; }
h2 { margin: 32px 0 8px; font-size: 19px; border-bottom: 1px solid #d0d7de; padding-bottom: 4px; }
h3 { margin: 16px 0 6px; font-size: 16px; }
.total { font-size: 22px; font-weight: 600; margin: 4px 0 8px; }
.meta, .notes { color: #57606a; margin: 2px 0; }
table { border-collapse: collapse; width: 100%; margin: 10px 0; }
th, td { text-align: left; padding: 6px 8px; border-bottom: 1px solid #d0d7de; vertical-align: top; }
th { background: #f6f8fa; font-weight: 600; }
tr.pass td.result { background: #dafbe1; }
tr.fail td.result { background: #ffebe9; }
tr.todo td.result { background: #fff8c5; }
.badge { display: inline-block; padding: 1px 8px; border-radius: 10px; font-weight: 600; font-size: 12px;
         white-space: nowrap; color: #fff; }
.badge.pass { background: #1a7f37; } .badge.fail { background: #cf222e; } .badge.todo { background: #9a6700; }
td.num { white-space: nowrap; font-variant-numeric: tabular-nums; }
td.msg { font-size: 13px; color: #424a53; word-break: break-word; }
.row { display: flex; gap: 14px; flex-wrap: wrap; align-items: flex-start; }
figure { margin: 0; text-align: center; }
figure img { width: 256px; height: 256px; image-rendering: pixelated; border: 1px solid #d0d7de; background: #000; }
figcaption { font-size: 13px; color: #57606a; margin-top: 2px; }
.legend { width: 256px; height: 12px; border: 1px solid #d0d7de; margin-top: 4px; }
.legend-labels { width: 256px; display: flex; justify-content: space-between; font-size: 11px; color: #57606a; }
table.numbers { width: auto; font-size: 13px; }
table.numbers td:first-child { color: #57606a; padding-right: 18px; }
.case { border: 1px solid #d0d7de; border-radius: 6px; padding: 8px 14px 10px; margin: 12px 0; }
.case.pass { border-left: 6px solid #1a7f37; } .case.fail { border-left: 6px solid #cf222e; }
details { margin: 8px 0; font-size: 13px; } details li { font-family: ui-monospace, monospace; font-size: 12px; }
)";

std::string figure(const std::string& uri, const std::string& caption,
                   const std::string& extra = "") {
    if (uri.empty()) return "";
    return "<figure><img alt=\"" + escape(caption) + "\" src=\"" + uri + "\"><figcaption>" +
           escape(caption) + "</figcaption>" + extra + "</figure>\n";
}

std::string legend(const ImageCaseResult& c) {
    std::string stops;
    for (const std::string& s : viridis_hex_stops())
        stops += (stops.empty() ? "" : ", ") + s;
    std::string low = "low", high = "high";
    for (const auto& [name, value] : c.numbers) {
        if (name != "heat map scale") continue;
        size_t scale = value.find("log scale ");
        size_t dots = value.find(" .. ");
        if (scale != std::string::npos && dots != std::string::npos) {
            low = value.substr(scale + 10, dots - scale - 10);
            high = value.substr(dots + 4);
        }
    }
    return "<div class=\"legend\" style=\"background: linear-gradient(to right, " + stops +
           ")\"></div><div class=\"legend-labels\"><span>&le; " + escape(low) +
           "</span><span>per-pixel relMSE (log)</span><span>&ge; " + escape(high) + "</span></div>";
}

}  // namespace

std::string html_report(const GradeReport& report, const std::string& out_dir) {
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>Grade report: "
      << format_points(report.points()) << " / " << format_points(report.max_points())
      << "</title>\n<style>" << kStyle << "</style></head>\n<body>\n";
    h << "<h1>Grade report</h1>\n<p class=\"total\">" << format_points(report.points()) << " / "
      << format_points(report.max_points()) << " points"
      << (report.all_passed() ? " &mdash; every task passes" : "") << "</p>\n";
    char secs[32];
    std::snprintf(secs, sizeof secs, "%.1f s", report.seconds);
    h << "<p class=\"meta\">student code <code>" << escape(report.student_dir)
      << "</code> &middot; seed " << report.seed << " &middot; " << escape(report.date)
      << " &middot; " << secs << "</p>\n";
    for (const std::string& p : report.parts)
        h << "<p class=\"meta\">graded: " << escape(p) << "</p>\n";
    for (const std::string& n : report.notes)
        h << "<p class=\"notes\">note: " << escape(n) << "</p>\n";

    h << "<table "
         "class=\"tasks\"><tr><th>part</th><th>task</th><th>name</th><th>result</th><th>points</th>"
         "<th>figure</th><th>message</th></tr>\n";
    for (const TaskResult& t : report.tasks) {
        h << "<tr class=\"" << css_class(t.status) << "\"><td>" << t.part << "</td><td><a href=\"#"
          << escape(t.id) << "\">" << escape(t.id) << "</a></td><td>" << escape(t.name)
          << "</td><td class=\"result\"><span class=\"badge " << css_class(t.status) << "\">"
          << badge(t.status) << "</span></td><td class=\"num\">" << format_points(t.points) << " / "
          << format_points(t.max_points) << "</td><td class=\"num\">" << escape(format_figure(t))
          << "</td><td class=\"msg\">" << escape(t.message) << "</td></tr>\n";
    }
    h << "</table>\n";

    for (const TaskResult& t : report.tasks) {
        h << "<h2 id=\"" << escape(t.id) << "\">" << escape(t.id) << " " << escape(t.name)
          << " <span class=\"badge " << css_class(t.status) << "\">" << badge(t.status)
          << "</span></h2>\n";
        h << "<p class=\"msg\">" << escape(t.message) << "</p>\n";
        for (const ImageCaseResult& c : t.images) {
            h << "<div class=\"case " << (c.pass ? "pass" : "fail") << "\"><h3>" << escape(c.label)
              << " <span class=\"badge " << (c.pass ? "pass" : "fail") << "\">"
              << (c.pass ? "PASS" : "FAIL") << "</span></h3>\n<div class=\"row\">\n";
            h << figure(data_uri(out_dir, c.student_png), "student");
            h << figure(data_uri(out_dir, c.reference_png), "reference (converged)");
            h << figure(data_uri(out_dir, c.reference_same_spp_png), "reference at the same spp");
            h << figure(data_uri(out_dir, c.heatmap_png), "heat map: student against reference",
                        legend(c));
            h << "</div>\n<table class=\"numbers\">\n";
            for (const auto& [name, value] : c.numbers)
                h << "<tr><td>" << escape(name) << "</td><td>" << escape(value) << "</td></tr>\n";
            h << "</table>\n<p class=\"msg\">" << escape(c.message) << "</p></div>\n";
        }
        if (!t.details.empty()) {
            h << "<details" << (t.status == TaskStatus::fail ? " open" : "")
              << "><summary>details</summary><ul>\n";
            for (const std::string& d : t.details)
                h << "<li>" << escape(d) << "</li>\n";
            h << "</ul></details>\n";
        }
    }
    h << "</body></html>\n";
    return h.str();
}

}  // namespace pt

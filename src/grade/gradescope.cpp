#include "grade/gradescope.h"

#include "grade/report.h"

namespace pt {

nlohmann::json gradescope_results(const GradeReport& report, const std::string& summary) {
    using nlohmann::json;
    json tests = json::array();
    for (const TaskResult& t : report.tasks) {
        std::string output = std::string(to_string(t.status)) + ": " + t.message;
        for (const std::string& d : t.details)
            output += "\n" + d;
        const std::string figure = format_figure(t);
        if (figure != "-") output += "\n" + figure;
        tests.push_back({{"name", t.id + " " + t.name},
                         {"number", t.id},
                         {"score", t.points},
                         {"max_score", t.max_points},
                         {"status", t.status == TaskStatus::pass ? "passed" : "failed"},
                         {"output", output},
                         {"output_format", "text"},
                         {"visibility", "visible"}});
    }
    std::string output = "Total: " + format_points(report.points()) + " / " +
                         format_points(report.max_points()) + " points.";
    if (!summary.empty()) output += "\n" + summary;
    return {{"score", report.points()},
            {"output", output},
            {"visibility", "visible"},
            {"stdout_visibility", "hidden"},
            {"tests", tests}};
}

}  // namespace pt

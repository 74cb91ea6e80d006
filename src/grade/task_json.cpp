#include "grade/task_json.h"

#include <cmath>

namespace pt {

using nlohmann::json;

namespace {

json number_or_null(double v) {
    return std::isfinite(v) ? json(v) : json(nullptr);
}
double number_or_nan(const json& j) {
    return j.is_number() ? j.get<double>() : NAN;
}

TaskStatus parse_status(const std::string& s) {
    for (TaskStatus t : {TaskStatus::pass, TaskStatus::fail, TaskStatus::not_implemented,
                         TaskStatus::not_submitted})
        if (s == to_string(t)) return t;
    return TaskStatus::fail;
}

}  // namespace

json task_to_json(const TaskResult& t) {
    json task = {{"part", t.part},
                 {"id", t.id},
                 {"name", t.name},
                 {"check", t.check},
                 {"type", to_string(t.type)},
                 {"status", to_string(t.status)},
                 {"points", t.points},
                 {"max_points", t.max_points},
                 {"metric", t.metric},
                 {"value", number_or_null(t.value)},
                 {"comparison", t.comparison},
                 {"threshold", number_or_null(t.threshold)},
                 {"message", t.message},
                 {"details", t.details},
                 {"seconds", t.seconds},
                 {"images", json::array()}};
    for (const ImageCaseResult& c : t.images) {
        json numbers = json::array();
        for (const auto& [name, value] : c.numbers)
            numbers.push_back({{"name", name}, {"value", value}});
        task["images"].push_back({{"label", c.label},
                                  {"pass", c.pass},
                                  {"message", c.message},
                                  {"student", c.student_png},
                                  {"reference", c.reference_png},
                                  {"reference_same_spp", c.reference_same_spp_png},
                                  {"heatmap", c.heatmap_png},
                                  {"numbers", numbers}});
    }
    return task;
}

TaskResult task_from_json(const json& j) {
    TaskResult t;
    t.part = j.at("part").get<int>();
    t.id = j.at("id").get<std::string>();
    t.name = j.at("name").get<std::string>();
    t.check = j.at("check").get<std::string>();
    for (TaskType type : {TaskType::function, TaskType::image, TaskType::performance})
        if (j.at("type").get<std::string>() == to_string(type)) t.type = type;
    t.status = parse_status(j.at("status").get<std::string>());
    t.points = j.at("points").get<double>();
    t.max_points = j.at("max_points").get<double>();
    t.metric = j.at("metric").get<std::string>();
    t.value = number_or_nan(j.at("value"));
    t.comparison = j.at("comparison").get<std::string>();
    t.threshold = number_or_nan(j.at("threshold"));
    t.message = j.at("message").get<std::string>();
    t.details = j.at("details").get<std::vector<std::string>>();
    t.seconds = j.at("seconds").get<double>();
    for (const json& c : j.at("images")) {
        ImageCaseResult r;
        r.label = c.at("label").get<std::string>();
        r.pass = c.at("pass").get<bool>();
        r.message = c.at("message").get<std::string>();
        r.student_png = c.at("student").get<std::string>();
        r.reference_png = c.at("reference").get<std::string>();
        r.reference_same_spp_png = c.at("reference_same_spp").get<std::string>();
        r.heatmap_png = c.at("heatmap").get<std::string>();
        for (const json& n : c.at("numbers"))
            r.numbers.emplace_back(n.at("name"), n.at("value"));
        t.images.push_back(r);
    }
    return t;
}

}  // namespace pt

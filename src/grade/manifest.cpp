#include "grade/manifest.h"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "grade/check_registry.h"

namespace pt {
namespace {

using nlohmann::json;

void reject_unknown_keys(const json& object, const std::set<std::string>& allowed,
                         const std::string& where) {
    for (auto it = object.begin(); it != object.end(); ++it) {
        if (!allowed.count(it.key())) {
            std::string list;
            for (const std::string& k : allowed)
                list += (list.empty() ? "" : ", ") + k;
            throw InputError(where + ": unknown key \"" + it.key() +
                             "\" (expected one of: " + list + ")");
        }
    }
}

const json& require(const json& object, const std::string& key, json::value_t type,
                    const std::string& where) {
    auto it = object.find(key);
    if (it == object.end()) throw InputError(where + ": missing \"" + key + "\"");
    bool ok = it->type() == type || (type == json::value_t::number_float && it->is_number());
    if (!ok)
        throw InputError(where + "." + key + ": expected " + json(type).type_name() + ", got " +
                         it->dump());
    return *it;
}

TaskSpec read_task(const json& j, int part, const std::string& where, const std::string& path) {
    if (!j.is_object()) throw InputError(where + ": expected an object");
    reject_unknown_keys(j, {"id", "name", "check", "type", "points", "params", "comment"}, where);
    TaskSpec t;
    t.part = part;
    t.manifest = path;
    t.id = require(j, "id", json::value_t::string, where).get<std::string>();
    t.name = require(j, "name", json::value_t::string, where).get<std::string>();
    t.check = require(j, "check", json::value_t::string, where).get<std::string>();
    t.type = parse_task_type(require(j, "type", json::value_t::string, where).get<std::string>(),
                             where + ".type");
    t.points = require(j, "points", json::value_t::number_float, where).get<double>();
    if (!(t.points >= 0) || !std::isfinite(t.points))
        throw InputError(where + ".points: expected a non-negative number");
    if (j.contains("params")) {
        if (!j["params"].is_object()) throw InputError(where + ".params: expected an object");
        t.params = j["params"];
    }
    const CheckInfo* check = find_check(t.check);
    if (!check) {
        std::string list;
        for (const CheckInfo& c : all_checks())
            list += (list.empty() ? "" : ", ") + std::string(c.name);
        throw InputError(where + ".check: unknown check \"" + t.check + "\" (registered: " + list +
                         ")");
    }
    if (check->type != t.type)
        throw InputError(where + ".type: check \"" + t.check + "\" is a " + to_string(check->type) +
                         " check, not " + to_string(t.type));
    std::set<std::string> allowed(check->params.begin(), check->params.end());
    reject_unknown_keys(t.params, allowed, where + ".params");
    return t;
}

}  // namespace

PartManifest read_manifest(const std::string& path, int expected_part) {
    std::ifstream in(path);
    if (!in) throw InputError("cannot read manifest " + path);
    std::stringstream text;
    text << in.rdbuf();
    json j;
    try {
        j = json::parse(text.str());
    } catch (const json::parse_error& e) {
        throw InputError(path + ": not valid JSON: " + e.what());
    }
    if (!j.is_object()) throw InputError(path + ": expected a JSON object");
    reject_unknown_keys(j, {"part", "title", "tasks", "comment", "coverage_exclusions"}, path);
    PartManifest m;
    m.path = path;
    m.part = require(j, "part", json::value_t::number_unsigned, path).get<int>();
    if (m.part < kFirstPart || m.part > kLastPart)
        throw InputError(path + ".part: expected " + std::to_string(kFirstPart) + " to " +
                         std::to_string(kLastPart));
    if (expected_part != 0 && m.part != expected_part)
        throw InputError(path + ".part: is " + std::to_string(m.part) + " but the file is in part" +
                         std::to_string(expected_part) + "/");
    if (j.contains("title"))
        m.title = require(j, "title", json::value_t::string, path).get<std::string>();
    const json& tasks = require(j, "tasks", json::value_t::array, path);
    std::set<std::string> ids;
    for (size_t i = 0; i < tasks.size(); ++i) {
        std::string where = path + ": tasks[" + std::to_string(i) + "]";
        TaskSpec t = read_task(tasks[i], m.part, where, path);
        if (!ids.insert(t.id).second)
            throw InputError(where + ".id: \"" + t.id + "\" appears twice");
        m.tasks.push_back(std::move(t));
    }
    return m;
}

std::vector<PartManifest> read_manifests(const std::string& assignments_dir,
                                         std::vector<std::string>* notes) {
    std::vector<PartManifest> manifests;
    for (int part = kFirstPart; part <= kLastPart; ++part) {
        std::string path = assignments_dir + "/part" + std::to_string(part) + "/grading.json";
        if (!std::ifstream(path)) {
            if (notes)
                notes->push_back("Part " + std::to_string(part) + ": no manifest (" + path +
                                 "), so its tasks are not graded");
            continue;
        }
        manifests.push_back(read_manifest(path, part));
    }
    return manifests;
}

}  // namespace pt

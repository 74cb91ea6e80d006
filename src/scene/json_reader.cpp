#include "scene/json_reader.h"

#include <cmath>
#include <set>
#include <sstream>

#include "core/error.h"

namespace pt {

using nlohmann::json;

std::string describe_json(const json& v) {
    if (v.is_null()) return "null";
    if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
    if (v.is_number()) {
        std::ostringstream s;
        s << v.get<double>();
        return s.str();
    }
    if (v.is_string()) return "the string \"" + v.get<std::string>() + "\"";
    if (v.is_array()) return "an array of " + std::to_string(v.size());
    return "an object";
}

JsonReader::JsonReader(const json& node, std::string file, std::string path)
    : node_(node), file_(std::move(file)), path_(std::move(path)) {
    if (!node_.is_object()) {
        throw InputError(file_ + ": " + (path_.empty() ? "top level" : path_) +
                         ": expected an object, got " + describe_json(node_));
    }
}

std::string JsonReader::path_of(const std::string& key) const {
    if (key.empty()) return path_.empty() ? "top level" : path_;
    return path_.empty() ? key : path_ + "." + key;
}

void JsonReader::fail(const std::string& key, const std::string& message) const {
    throw InputError(file_ + ": " + path_of(key) + ": " + message);
}

void JsonReader::allow_only(std::initializer_list<const char*> allowed) const {
    for (auto it = node_.begin(); it != node_.end(); ++it) {
        bool known = false;
        for (const char* k : allowed) known = known || it.key() == k;
        if (known) continue;
        std::string list;
        for (const char* k : allowed) list += (list.empty() ? "" : ", ") + std::string(k);
        fail(it.key(), "unknown key (expected one of: " + list + ")");
    }
}

bool JsonReader::has(const std::string& key) const { return node_.contains(key); }

bool JsonReader::is_array(const std::string& key) const { return has(key) && node_.at(key).is_array(); }

const json& JsonReader::child(const std::string& key) const {
    auto it = node_.find(key);
    if (it == node_.end()) fail("", "missing key '" + key + "'");
    return *it;
}

JsonReader JsonReader::object(const std::string& key) const {
    return JsonReader(child(key), file_, path_of(key));
}

std::vector<JsonReader> JsonReader::object_array(const std::string& key) const {
    const json& a = child(key);
    if (!a.is_array()) fail(key, "expected an array, got " + describe_json(a));
    std::vector<JsonReader> items;
    for (size_t i = 0; i < a.size(); ++i)
        items.emplace_back(a[i], file_, path_of(key) + "[" + std::to_string(i) + "]");
    return items;
}

std::vector<std::pair<std::string, JsonReader>> JsonReader::object_map(const std::string& key) const {
    const json& m = child(key);
    if (!m.is_object()) fail(key, "expected an object, got " + describe_json(m));
    std::vector<std::pair<std::string, JsonReader>> items;
    for (auto it = m.begin(); it != m.end(); ++it)
        items.emplace_back(it.key(), JsonReader(it.value(), file_, path_of(key) + "." + it.key()));
    return items;
}

std::string JsonReader::string(const std::string& key) const {
    const json& v = child(key);
    if (!v.is_string()) fail(key, "expected a string, got " + describe_json(v));
    return v.get<std::string>();
}

double JsonReader::to_number(const json& v, const std::string& where_key) const {
    if (!v.is_number()) fail(where_key, "expected a number, got " + describe_json(v));
    double d = v.get<double>();
    if (!std::isfinite(d)) fail(where_key, "expected a finite number, got " + describe_json(v));
    return d;
}

double JsonReader::number(const std::string& key) const { return to_number(child(key), key); }

double JsonReader::number(const std::string& key, double fallback) const {
    return has(key) ? number(key) : fallback;
}

double JsonReader::number_in(const std::string& key, double lo, double hi, double fallback) const {
    double v = number(key, fallback);
    if (v < lo || v > hi) {
        std::ostringstream s;
        s << "expected a number in [" << lo << ", " << hi << "], got " << v;
        fail(key, s.str());
    }
    return v;
}

double JsonReader::positive(const std::string& key) const {
    double v = number(key);
    if (!(v > 0)) {
        std::ostringstream s;
        s << "expected a number > 0, got " << v;
        fail(key, s.str());
    }
    return v;
}

double JsonReader::positive(const std::string& key, double fallback) const {
    return has(key) ? positive(key) : fallback;
}

int JsonReader::integer(const std::string& key, int lo, int hi) const {
    double v = number(key);
    if (v != std::floor(v) || v < lo || v > hi) {
        std::ostringstream s;
        s << "expected a whole number in [" << lo << ", " << hi << "], got " << v;
        fail(key, s.str());
    }
    return int(v);
}

int JsonReader::integer(const std::string& key, int lo, int hi, int fallback) const {
    return has(key) ? integer(key, lo, hi) : fallback;
}

std::vector<double> JsonReader::numbers(const std::string& key, size_t count) const {
    const json& a = child(key);
    if (!a.is_array() || a.size() != count)
        fail(key, "expected an array of " + std::to_string(count) + " numbers, got " + describe_json(a));
    std::vector<double> out;
    for (size_t i = 0; i < count; ++i) out.push_back(to_number(a[i], key + "[" + std::to_string(i) + "]"));
    return out;
}

Vec3 JsonReader::vec3(const std::string& key) const {
    std::vector<double> v = numbers(key, 3);
    return {v[0], v[1], v[2]};
}

Vec3 JsonReader::vec3(const std::string& key, const Vec3& fallback) const {
    return has(key) ? vec3(key) : fallback;
}

Color JsonReader::color(const std::string& key, const Color& fallback, double max_value) const {
    if (!has(key)) return fallback;
    std::vector<double> v = numbers(key, 3);
    for (double c : v) {
        if (c < 0 || c > max_value) {
            std::ostringstream s;
            if (max_value < 1e300)
                s << "expected components in [0, " << max_value << "], got " << c;
            else
                s << "expected components >= 0, got " << c;
            fail(key, s.str());
        }
    }
    return {v[0], v[1], v[2]};
}

namespace {

/// Where the parser is, as the JsonReader paths spell it ("objects[2].radius"),
/// kept from the parser's events: each open object knows its keys so far.
class JsonPathTracker {
public:
    explicit JsonPathTracker(std::string file) : file_(std::move(file)) {}

    bool on_event(json::parse_event_t event, const json& parsed) {
        using E = json::parse_event_t;
        if (event == E::object_start || event == E::array_start || event == E::value) enter_value();
        if (event == E::object_start || event == E::array_start) stack_.push_back(Level{event == E::object_start, {}, {}, -1});
        if (event == E::object_end || event == E::array_end) stack_.pop_back();
        if (event == E::key) {
            Level& object = stack_.back();
            object.key = parsed.get<std::string>();
            if (!object.keys.insert(object.key).second) {
                std::string where = path();
                throw InputError(file_ + ": " + (where.empty() ? "top level" : where) + ": duplicate key \"" +
                                 object.key + "\" (a JSON object takes each key once)");
            }
        }
        return true;
    }

private:
    struct Level {
        bool object;
        std::set<std::string> keys;
        std::string key;   ///< the current key, in an object
        long index = -1;   ///< the current element, in an array
    };

    void enter_value() {
        if (!stack_.empty() && !stack_.back().object) ++stack_.back().index;
    }

    /// The path of the current key's parent object.
    std::string path() const {
        std::string p;
        for (size_t i = 0; i + 1 < stack_.size(); ++i) {
            const Level& l = stack_[i];
            if (l.object) p += (p.empty() ? "" : ".") + l.key;
            else p += "[" + std::to_string(l.index) + "]";
        }
        return p;
    }

    std::string file_;
    std::vector<Level> stack_;
};

}  // namespace

json parse_json_strictly(const std::string& text, const std::string& file) {
    JsonPathTracker tracker(file);
    try {
        return json::parse(text, [&](int, json::parse_event_t event, json& parsed) {
            return tracker.on_event(event, parsed);
        });
    } catch (const json::exception& e) {
        // Syntax errors and number overflow (1e999); nlohmann's message
        // already carries "at line L, column C" where it applies.
        std::string what = e.what();
        size_t colon = what.find(": ");
        throw InputError(file + ": malformed JSON: " + (colon == std::string::npos ? what : what.substr(colon + 2)));
    }
}

}  // namespace pt

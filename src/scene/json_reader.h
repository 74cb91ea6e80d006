// JsonReader: strict, self-describing access to one JSON object of a scene
// file. Every accessor knows the file and the JSON path it reads, so every
// error names both: "cbox.json: objects[2].radius: expected a number > 0, got -1".
//
// Strictness is the point: an unknown key is an error (a typo never becomes
// a silent default), numbers must be finite, arrays must have the right length.
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/color.h"
#include "core/vec3.h"

namespace pt {

class JsonReader {
public:
    JsonReader(const nlohmann::json& node, std::string file, std::string path);

    /// Throws when the object has a key outside `allowed`.
    void allow_only(std::initializer_list<const char*> allowed) const;
    bool has(const std::string& key) const;
    bool is_array(const std::string& key) const;
    /// The child object `key` (which must be a JSON object).
    JsonReader object(const std::string& key) const;
    /// The child array `key`, element by element (each must be an object).
    std::vector<JsonReader> object_array(const std::string& key) const;
    /// Every (key, object) pair of the child object `key`.
    std::vector<std::pair<std::string, JsonReader>> object_map(const std::string& key) const;

    std::string string(const std::string& key) const;
    double number(const std::string& key) const;
    double number(const std::string& key, double fallback) const;
    /// A number in [lo, hi]; `what` describes the range in the error.
    double number_in(const std::string& key, double lo, double hi, double fallback) const;
    double positive(const std::string& key) const;
    double positive(const std::string& key, double fallback) const;
    int integer(const std::string& key, int lo, int hi) const;
    int integer(const std::string& key, int lo, int hi, int fallback) const;
    std::vector<double> numbers(const std::string& key, size_t count) const;
    Vec3 vec3(const std::string& key) const;
    Vec3 vec3(const std::string& key, const Vec3& fallback) const;
    /// A colour with every component >= 0 (and <= max_value).
    Color color(const std::string& key, const Color& fallback, double max_value = 1e300) const;

    /// Throws InputError "file: path.key: message".
    [[noreturn]] void fail(const std::string& key, const std::string& message) const;
    const std::string& file() const { return file_; }
    std::string path_of(const std::string& key) const;

private:
    const nlohmann::json& child(const std::string& key) const;
    double to_number(const nlohmann::json& v, const std::string& where_key) const;

    const nlohmann::json& node_;
    std::string file_;
    std::string path_;
};

/// The JSON type name of a value for error messages ("a string", "an array").
std::string describe_json(const nlohmann::json& v);

/// Parses a JSON document strictly: a syntax error, or a key given twice in
/// one object (nlohmann's parser silently keeps the last), throws InputError
/// "file: malformed JSON: ..." or "file: materials.white: duplicate key
/// \"albedo\"".
nlohmann::json parse_json_strictly(const std::string& text, const std::string& file);

}  // namespace pt

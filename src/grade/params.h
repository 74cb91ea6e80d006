// Reading a check's parameters from its manifest entry, with the check's
// default when the instructor leaves one out, and a clear error naming the
// manifest and the key when the value has the wrong type.
#pragma once

#include <string>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "grade/task.h"

namespace pt {

/// spec.params[key] as T, or `fallback` when absent; InputError when the
/// value is not a T.
template <typename T>
T param(const TaskSpec& spec, const std::string& key, const T& fallback) {
    auto it = spec.params.find(key);
    if (it == spec.params.end()) return fallback;
    auto bad = [&] {
        return InputError(spec.manifest + ": task " + spec.id + ": params." + key +
                          ": unexpected value " + it->dump());
    };
    if constexpr (std::is_same_v<T, bool>) {
        if (!it->is_boolean()) throw bad();
    } else if constexpr (std::is_arithmetic_v<T>) {
        if (!it->is_number()) throw bad();
    }
    try {
        return it->template get<T>();
    } catch (const nlohmann::json::exception&) {
        throw bad();
    }
}

}  // namespace pt

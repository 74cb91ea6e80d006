// One fuzz input for the scene loaders: the first byte picks the format
// (even: JSON scene, odd: OBJ mesh), the rest is the file's content.
// Shared by the libFuzzer target and the corpus replay test, so both feed
// the loaders the same way.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "scene/scene_loader.h"

namespace pt::fuzz {

/// Loads the input; returns true when it is a valid scene, false when the
/// loader rejected it with an InputError. Anything else escapes (a bug).
inline bool load_fuzz_input(const uint8_t* data, size_t size, const std::string& scratch_dir) {
    if (size == 0) return false;
    std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    try {
        if (data[0] % 2 == 0) {
            parse_json_scene(text, scratch_dir + "/fuzz.json");
        } else {
            std::string path = scratch_dir + "/fuzz_" + std::to_string(getpid()) + ".obj";
            std::FILE* f = std::fopen(path.c_str(), "wb");
            if (!f) return false;
            std::fwrite(text.data(), 1, text.size(), f);
            std::fclose(f);
            load_scene(path);
        }
        return true;
    } catch (const InputError&) {
        return false;
    }
}

}  // namespace pt::fuzz

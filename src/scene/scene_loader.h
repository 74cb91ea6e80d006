// Loading scenes: the JSON scene format of DESIGN.md, or a bare OBJ file
// (camera framed on its bounding box, materials from its MTL, no lights
// added). Every bad input throws InputError naming the file, the JSON path
// and what was expected.
#pragma once

#include <string>

#include "scene/scene.h"

namespace pt {

/// Loads a .json scene or a bare .obj mesh, by extension.
Scene load_scene(const std::string& path);
Scene load_json_scene(const std::string& path);
Scene load_obj_scene(const std::string& path);
/// Parses a scene from JSON text; `path` names it in errors and anchors relative paths.
Scene parse_json_scene(const std::string& text, const std::string& path);

}  // namespace pt

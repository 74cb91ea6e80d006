// partN: the renderer with part N's stages switched to student code
// (PT_PART is defined per executable by the build).
#include <string>

#include "apps/render_app.h"

int main(int argc, char** argv) {
    return pt::run_render_app(argc, argv, "part" + std::to_string(PT_PART), pt::StageSet::of_part(PT_PART));
}

// pathtracer: the renderer, all stages reference by default.
#include "apps/render_app.h"

int main(int argc, char** argv) { return pt::run_render_app(argc, argv, "pathtracer", pt::StageSet::none()); }

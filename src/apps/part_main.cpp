// partN: the renderer with part N's stages switched to student code
// (PT_PART is defined per executable by the build). `partN --deliverables
// DIR [-t N]` renders the part's write-up images instead (apps/deliverables.h).
#include <iostream>
#include <string>
#include <vector>

#include "apps/deliverables.h"
#include "apps/render_app.h"
#include "core/error.h"

int main(int argc, char** argv) {
    const std::string program = "part" + std::to_string(PT_PART);
    std::vector<std::string> args(argv + 1, argv + argc);
    for (const std::string& a : args) {
        if (a != "--deliverables") continue;
        try {
            std::string dir;
            int threads = 0;
            for (size_t i = 0; i < args.size(); ++i) {
                if (args[i] == "--deliverables" && i + 1 < args.size()) {
                    dir = args[++i];
                } else if (args[i] == "-t" && i + 1 < args.size()) {
                    threads = std::stoi(args[++i]);
                    if (threads < 1) throw pt::InputError("-t: expected a whole number >= 1");
                } else {
                    throw pt::InputError("--deliverables DIR takes only -t N beside it, got '" + args[i] + "'");
                }
            }
            if (dir.empty()) throw pt::InputError("--deliverables: expected a folder");
            return pt::render_deliverables(PT_PART, dir, threads);
        } catch (const pt::InputError& e) {
            std::cerr << program << ": error: " << e.what() << "\n";
            return pt::kExitBadInput;
        } catch (const std::exception& e) {
            std::cerr << program << ": error: " << e.what() << "\n";
            return pt::kExitBadInput;
        }
    }
    return pt::run_render_app(argc, argv, program, pt::StageSet::of_part(PT_PART));
}

// `partN --deliverables DIR`: renders the images a part's write-up must
// show (assignments/partN/deliverables.json, listed in its handout) with
// the student's code into DIR, and writes DIR/index.html with each image,
// its caption and the exact command that made it.
#pragma once

#include <string>

namespace pt {

/// Renders part `part`'s deliverables into `dir` with `threads` threads (0:
/// all cores); returns the exit code: 0 when every image was rendered, else
/// the first failing render's (3: a stub not implemented yet). Bad input
/// (the list, the folder) throws InputError.
int render_deliverables(int part, const std::string& dir, int threads);

}  // namespace pt

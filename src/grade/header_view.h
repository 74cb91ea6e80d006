// A headers-only view of the project's src/ for the sandboxed compile of a
// submission (grade --class, docs/grading.md "How a submission is built").
//
// The compile needs the project's headers (the contracts the student
// implements) but must not read its .cpp files: `#include
// "../../src/stages/bvh_traverse.cpp"` would hand a student the reference
// implementation under another name. So trusted code copies every header
// of src/ (and nothing else) into a folder of the grader's, and bubblewrap
// binds that folder read-only at src/'s own path (sandbox.h): include paths,
// compiler messages and dependency files stay as they were, and a .cpp of
// src/ does not exist inside the sandbox.
#pragma once

#include <filesystem>
#include <string>

namespace pt {

/// Whether `path` names a C++ header by its extension (.h, .hh, .hpp,
/// .hxx, .inl, .ipp): what the view holds and what a compile may read
/// from the project's src/.
bool is_header(const std::filesystem::path& path);

/// Makes `view` hold a copy of every regular file under `src` that is a
/// header, at the same relative path and with the same modification time
/// (so make sees the objects that depend on them up to date), and nothing
/// else; a previous view is replaced. Symbolic links in `src` are not
/// followed. Returns the number of headers copied; throws
/// std::runtime_error naming the file when a copy fails.
size_t make_header_view(const std::string& src, const std::string& view);

}  // namespace pt

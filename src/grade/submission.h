// One student's submission in a class folder (`grade --class`): a copy of
// assignments/ or of some of its parts. A part counts as submitted when its
// folder partN/ holds at least one .cpp file; the tasks of the other parts
// are "not submitted" and are not run. The files compiled for it are the
// submission's own part*/*.cpp, with the handout's stub for every handout
// file it lacks, so that a partial submission links (never a wall of
// linker errors for what it did not hand in).
#pragma once

#include <string>
#include <vector>

namespace pt {

struct Submission {
    std::string name;        ///< the folder's name: the student, in the gradebook
    std::string dir;         ///< absolute; where its part folders are
    std::vector<int> parts;  ///< the parts it submits, ascending
};

/// Looks into `dir`: its part folders, or those of its only subfolder (a
/// submission zipped with its assignments/ folder inside).
Submission inspect_submission(const std::string& name, const std::string& dir);

/// Every subfolder of `class_dir` (not starting with '.'), sorted by name
/// (byte order). Throws InputError when `class_dir` is not a folder or
/// holds no subfolder.
std::vector<Submission> list_submissions(const std::string& class_dir);

/// The first symbolic link in `s`'s folder (its path relative to it, and
/// where it points), "" when there is none. A link could show the compiler
/// any file the grader can read (a reference .cpp of src/ included as a
/// header): `grade --class` refuses a submission that holds one, sandbox
/// or not. Looks at most at 100,000 entries (a larger folder is refused too).
std::string first_symlink(const Submission& s);

/// The absolute paths of the .cpp files to compile for `s`: its own
/// part*/*.cpp, and for every file of `handout_dir`/part*/*.cpp it lacks,
/// the handout's stub. Sorted.
std::vector<std::string> submission_sources(const Submission& s, const std::string& handout_dir);

}  // namespace pt

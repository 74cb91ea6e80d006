#!/usr/bin/env python3
"""The report of scripts/coverage.sh: lines and branches of the student's
files that no graded case ran, per task and function.

Usage: coverage_report.py BUILD_DIR STUDENT_DIR ASSIGNMENTS_DIR [SOLUTION_DIR]

STUDENT_DIR is the folder that was built (the handout's files overlaid with
the solution's); with SOLUTION_DIR, only the files the solution writes are
reported (the handout's stubs of later parts are not the solution's code).

Reads the gcov counters of every student object under BUILD_DIR (gcov's JSON
format), maps functions to tasks through the manifests (a function check's
"check" is the function it grades; an image task's "student_functions";
Part 2's performance task all four functions; part3.7's check both
heuristics; part7.4's whole "bdpt" stage its three functions, part8.5's
"photon" stage its four), and drops the lines the
manifests' "coverage_exclusions" list ({"function", "line", "reason"}: the
line's text, stripped). Branches gcov marks as exception paths ("throw")
are not counted: they are the compiler's unwinding edges, not the student's;
nor is a function's closing "}" when the function returns before it (at -O0
that line holds only the unwinding of its locals, run by an exception).
Exit code 1 when anything is left uncovered. With PT_COVERAGE_TASKS (a
comma list of task ids, as scripts/coverage.sh passes to grade) only those
tasks are reported.
"""
import glob
import gzip
import json
import os
import subprocess
import sys


# Checks that grade more than the one function their name says.
CHECK_FUNCTIONS = {
    "bvh_performance": ["construct_bvh", "bbox_intersect", "bvh_intersect", "bvh_has_intersection"],
    "mis_heuristics": ["power_heuristic", "balance_heuristic"],
}

# Image tasks whose "student_functions" name a whole stage (no "."): every
# function of that stage runs with the student's code.
STAGE_FUNCTIONS = {
    "bdpt": ["random_walk", "connect", "mis_weight"],
    "photon": ["emit_photon", "build_kdtree", "k_nearest", "density_estimate"],
}


def tasks_of_functions(assignments):
    owners, exclusions = {}, []
    for path in sorted(glob.glob(os.path.join(assignments, "part*", "grading.json"))):
        manifest = json.load(open(path))
        for ex in manifest.get("coverage_exclusions", []):
            exclusions.append(ex)
        for task in manifest["tasks"]:
            names = []
            if task["check"] == "image":
                for s in task["params"]["student_functions"]:
                    names += STAGE_FUNCTIONS.get(s, [s.split(".")[-1]])
            elif task["check"] in CHECK_FUNCTIONS:
                names = CHECK_FUNCTIONS[task["check"]]
            else:
                names = [task["check"]]
            for n in names:
                owners.setdefault(n, []).append(task["id"])
    return owners, exclusions


def gcov_json(gcda):
    out = subprocess.run(["gcov", "--json-format", "--stdout", "--branch-probabilities",
                          "--object-directory", os.path.dirname(gcda), gcda],
                         capture_output=True, check=True, cwd=os.path.dirname(gcda)).stdout
    for line in out.decode().splitlines():
        line = line.strip()
        if line.startswith("{"):
            yield json.loads(line)


def short_name(demangled):
    # "pt::student::bbox_intersect(BBox const&, ...)" -> "bbox_intersect"
    head = demangled.split("(")[0]
    return head.split("::")[-1]


def main():
    build, solution, assignments = (os.path.realpath(a) for a in sys.argv[1:4])
    solution = os.path.realpath(solution)
    written = None  # relative paths of the files the solution writes
    if len(sys.argv) > 4:
        own = os.path.realpath(sys.argv[4])
        written = {os.path.relpath(os.path.join(d, f), own)
                   for d, _, files in os.walk(own) for f in files if f.endswith(".cpp")}
    owners, exclusions = tasks_of_functions(assignments)
    gcdas = [g for g in glob.glob(os.path.join(build, "**", "*.gcda"), recursive=True)]
    if not gcdas:
        print("coverage: no gcov counters found under " + build, file=sys.stderr)
        return 2
    report = {}  # function -> {"lines": [...], "branches": [...], "total_lines", "total_branches"}
    sources = {}
    for gcda in gcdas:
        for data in gcov_json(gcda):
            for f in data.get("files", []):
                path = os.path.realpath(os.path.join(data.get("current_working_directory", ""), f["file"]))
                if not path.startswith(solution):
                    continue
                if written is not None and os.path.relpath(path, solution) not in written:
                    continue
                if path not in sources:
                    sources[path] = open(path).read().splitlines()
                text = sources[path]
                spans = [(fn["start_line"], fn["end_line"], short_name(fn["demangled_name"]))
                         for fn in f.get("functions", []) if "student::" in fn["demangled_name"]]
                for line in f.get("lines", []):
                    n = line["line_number"]
                    owner = next((name for (a, b, name) in spans if a <= n <= b), None)
                    if owner is None:
                        continue
                    entry = report.setdefault(owner, {"file": os.path.relpath(path, solution), "lines": [],
                                                      "branches": [], "total_lines": 0, "total_branches": 0})
                    src = text[n - 1].strip() if n - 1 < len(text) else ""
                    if src == "}" and line["count"] == 0 and any(
                            a <= n <= b and n == b for (a, b, _) in spans):
                        continue  # the unwinding of a function that returns before its end
                    excluded = next((ex for ex in exclusions if ex["function"] == owner and ex["line"] == src), None)
                    if excluded:
                        entry.setdefault("excluded", []).append((n, src, excluded["reason"]))
                        continue
                    entry["total_lines"] += 1
                    if line["count"] == 0:
                        entry["lines"].append((n, src))
                    for i, b in enumerate(line.get("branches", [])):
                        if b.get("throw"):
                            continue
                        entry["total_branches"] += 1
                        if b["count"] == 0:
                            entry["branches"].append((n, i, src))
    missing = 0
    by_task = {}
    for name, entry in report.items():
        for task in owners.get(name, ["(no task grades it)"]):
            by_task.setdefault(task, []).append(name)
    only = [t for t in os.environ.get("PT_COVERAGE_TASKS", "").split(",") if t]
    for task in sorted(by_task):
        if only and task not in only:
            continue
        print(task)
        for name in sorted(by_task[task]):
            e = report[name]
            lines_run = e["total_lines"] - len(e["lines"])
            branches_run = e["total_branches"] - len(e["branches"])
            print("  %s (%s): lines %d of %d, branches %d of %d" % (
                name, e["file"], lines_run, e["total_lines"], branches_run, e["total_branches"]))
            for n, src in e["lines"]:
                print("    line %d not run: %s" % (n, src))
            for n, i, src in e["branches"]:
                print("    line %d branch %d never taken: %s" % (n, i, src))
            for n, src, reason in e.get("excluded", []):
                print("    line %d excluded (%s): %s" % (n, reason, src))
            missing += len(e["lines"]) + len(e["branches"])
    print("coverage: %s" % ("every line and branch ran" if missing == 0 else
                            "%d lines or branches never ran" % missing))
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Generates a class of submissions with known grades, grades it with
`grade --class`, and checks the gradebook against the known answers
(docs/grading.md, "Measured: a class").

    scripts/grade_class_check.py [--students 50] [--jobs 2] [--part 1,2]
                                 [--grade BUILD/bin/grade] [--out DIR]

The class, made from the TODO-steps solution (tests/grading/solution):
  correct   the solution                                  full marks
  camera    ray directions not normalised                 part1.1 fails
  flip      the pixel loop flips the y axis               part1.2 fails
  triangle  intersect_triangle ignores t_min              part1.3 fails
  sphere    intersect_sphere tries the far root first     part1.4 fails
  syntax    a syntax error in part1/camera.cpp            does not compile
  link      part2/bvh.cpp calls a function never defined  does not compile (linker)
  partial   part1/ only                                   Part 2 not submitted
Each student's kind is a function of its number, so a run is reproducible.
Prints the time of the whole run and the load (uptime) before and after.
Exit code 0 when every row matches, 1 otherwise, 2 on bad arguments.
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SOLUTION = os.path.join(ROOT, "tests", "grading", "solution")

# kind -> (file, text to find, replacement, failing task)
BUGS = {
    "camera": ("part1/camera.cpp", "camera.to_world(sensor).unit()", "camera.to_world(sensor)", "part1.1"),
    "flip": ("part1/camera.cpp", "v = 1 - (y + p.y) / h", "v = (y + p.y) / h", "part1.2"),
    "triangle": ("part1/intersect.cpp", "if (t < ray.t_min || t > ray.t_max) return std::nullopt;",
                 "if (t > ray.t_max) return std::nullopt;", "part1.3"),
    "sphere": ("part1/intersect.cpp", "double t = (-b - std::sqrt(disc)) / (2 * a);",
               "double t = (-b + std::sqrt(disc)) / (2 * a);", "part1.4"),
}
# Out of every 10 students: 4 correct, one of each bug, syntax, link, partial (the
# two bugs left over alternate by decade).
PATTERN = ["correct", "camera", "correct", "flip", "syntax", "correct", "triangle", "partial",
           "correct", "sphere"]


def kind_of(i):
    k = PATTERN[i % 10]
    if k == "syntax" and (i // 10) % 2 == 1:
        return "link"
    return k


def make_submission(path, kind, parts):
    shutil.copytree(SOLUTION, path, ignore=shutil.ignore_patterns("README.md"))
    for p in os.listdir(path):
        if p.startswith("part") and int(p[4:]) not in parts:
            shutil.rmtree(os.path.join(path, p))
    if kind in BUGS:
        f, old, new, _ = BUGS[kind]
        text = open(os.path.join(path, f)).read()
        assert old in text, f"{f} no longer holds {old!r}"
        open(os.path.join(path, f), "w").write(text.replace(old, new, 1))
    elif kind == "syntax":
        with open(os.path.join(path, "part1/camera.cpp"), "a") as out:
            out.write("\nint broken(\n")
    elif kind == "link":
        with open(os.path.join(path, "part2/bvh.cpp"), "a") as out:
            out.write("\nnamespace pt { int never_defined(); int uses_it() { return never_defined(); } }\n")
    elif kind == "partial":
        for p in os.listdir(path):
            if p != "part1":
                shutil.rmtree(os.path.join(path, p))


def expected_row(kind, tasks, points):
    """task -> expected points, outcome, a fragment of the note."""
    row = {}
    for t in tasks:
        ok = True
        if kind in BUGS and BUGS[kind][3] == t:
            ok = False
        if kind in ("syntax", "link"):
            ok = False
        if kind == "partial" and not t.startswith("part1."):
            ok = False
        row[t] = points[t] if ok else 0
    outcome = "does not compile" if kind in ("syntax", "link") else "graded"
    note = {"syntax": "part1/camera.cpp:", "link": "undefined reference", "partial": "not submitted: part2"}
    return row, outcome, note.get(kind, "")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--students", type=int, default=50)
    ap.add_argument("--jobs", "-j", type=int, default=2)
    ap.add_argument("--part", default="1,2")
    ap.add_argument("--grade", default=os.path.join(ROOT, "build", "bin", "grade"))
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "class_check"))
    ap.add_argument("--no-sandbox", action="store_true")
    a = ap.parse_args()
    parts = [int(p) for p in a.part.split(",")]
    if a.students < 1 or not os.access(a.grade, os.X_OK) or not set(parts) <= {1, 2}:
        print("grade_class_check: need --students >= 1, an executable --grade, --part within 1,2",
              file=sys.stderr)
        return 2
    subs = os.path.join(a.out, "submissions")
    reports = os.path.join(a.out, "reports")
    shutil.rmtree(a.out, ignore_errors=True)
    os.makedirs(subs)
    kinds = {}
    for i in range(a.students):
        name = f"student{i:03d}"
        kinds[name] = kind_of(i)
        make_submission(os.path.join(subs, name), kinds[name], parts)
    load_before = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    start = time.time()
    cmd = [a.grade, "--class", subs, "--out", reports, "-j", str(a.jobs), "--part", a.part]
    if a.no_sandbox:
        cmd.append("--no-sandbox")
    r = subprocess.run(cmd)
    seconds = time.time() - start
    load_after = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    if r.returncode != 0:
        print(f"grade_class_check: grade --class exited {r.returncode}", file=sys.stderr)
        return 1
    with open(os.path.join(reports, "gradebook.csv")) as f:
        rows = list(csv.DictReader(f))
    header = list(rows[0].keys())
    tasks = header[1:header.index("total")]
    # Task points from a correct student's report (the manifests are the instructor's).
    points = {}
    for t in tasks:
        points[t] = max(float(row[t]) for row in rows)
    wrong = 0
    for row in rows:
        kind = kinds[row["student"]]
        want, outcome, note = expected_row(kind, tasks, points)
        got = {t: float(row[t]) for t in tasks}
        if got != want or row["outcome"] != outcome or note not in row["note"] or \
                float(row["total"]) != sum(want.values()):
            wrong += 1
            print(f"MISMATCH {row['student']} ({kind}): got {got} {row['outcome']!r} {row['note']!r}; "
                  f"want {want} {outcome!r} note containing {note!r}")
    if len(rows) != a.students:
        wrong += 1
        print(f"MISMATCH: {len(rows)} rows for {a.students} students")
    counts = {}
    for k in kinds.values():
        counts[k] = counts.get(k, 0) + 1
    print(f"grade_class_check: {a.students} submissions ({', '.join(f'{v} {k}' for k, v in sorted(counts.items()))}), "
          f"parts {a.part}, -j {a.jobs}{' --no-sandbox' if a.no_sandbox else ''}: {seconds:.0f} s "
          f"({seconds / a.students:.1f} s per submission); {len(rows) - wrong if wrong <= len(rows) else 0} "
          f"of {len(rows)} rows as expected")
    print(f"  load before: {load_before}\n  load after:  {load_after}")
    return 0 if wrong == 0 else 1


if __name__ == "__main__":
    sys.exit(main())

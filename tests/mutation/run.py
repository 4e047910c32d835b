#!/usr/bin/python3
"""The mutation run: realistic one-line bugs, each put into the source alone, built, and run
against the fast tier; a mutant is killed when a test fails. The source is restored after each
(and on any exit), then built once more.

    tests/mutation/run.py [--build build] [--labels REGEX] [--jobs 3] [--only ID]

Each mutant runs against the fast tier's tests of its layer (ctest labels): `renderer` for ao/
(the AO bench's tests need OpenGL), `unit|harness|python` for the rest; --labels sets one set
for all. ctest stops at the first failure.

Mutants are in tests/mutation/mutants.tsv: id, file, the original text (exactly once in the file),
its replacement, and the bug it stands for. The outcome is printed as a Markdown table
(docs/testing.md keeps the last one). Exit 1 when under 90 % are killed.
"""
import argparse
import pathlib
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]


def unescape(s):
    return s.encode().decode("unicode_escape")


def mutants():
    out = []
    for line in (ROOT / "tests/mutation/mutants.tsv").read_text().splitlines():
        if line.startswith("#") or not line.strip():
            continue
        mid, file, original, replacement, why = line.split("\t")
        out.append((mid, file, unescape(original), unescape(replacement), why))
    return out


def build(build_dir):
    return subprocess.run(["cmake", "--build", build_dir, "-j", "2"], cwd=ROOT,
                          stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)


def first_failure(output):
    for line in output.splitlines():
        if "***Failed" in line or "(Failed)" in line or "***Exception" in line \
                or "***Timeout" in line:
            return line.split(":", 1)[-1].split("...")[0].strip()
    return ""


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--build", default="build")
    p.add_argument("--labels", help="ctest labels for every mutant (default: by layer)")
    p.add_argument("--jobs", default="3", help="ctest -j (the tests wait on processes)")
    p.add_argument("--only", action="append", default=[])
    a = p.parse_args()
    rows, killed, total = [], 0, 0
    for mid, file, original, replacement, why in mutants():
        if a.only and mid not in a.only:
            continue
        path = ROOT / file
        source = path.read_text()
        if source.count(original) != 1:
            sys.exit(f"{file}: mutant {mid}'s original text is there "
                     f"{source.count(original)} times, not once")
        start = time.monotonic()
        try:
            path.write_text(source.replace(original, replacement))
            b = build(a.build)
            if b.returncode != 0:
                sys.exit(f"{file}: mutant {mid} does not build:\n{b.stderr[-2000:]}")
            # Without the last runs' costs ctest goes in test order (the quick unit tests
            # first), not longest first: the same verdicts, sooner.
            (ROOT / a.build / "Testing/Temporary/CTestCostData.txt").unlink(missing_ok=True)
            labels = a.labels or ("renderer" if file.startswith("ao/") else "unit|harness|python")
            t = subprocess.run(["ctest", "--test-dir", a.build, "-j", a.jobs, "-L", labels,
                                "--stop-on-failure", "--output-on-failure"],
                               cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               text=True)
        finally:
            path.write_text(source)
        total += 1
        dead = t.returncode != 0
        killed += dead
        by = first_failure(t.stdout) if dead else "survived"
        seconds = time.monotonic() - start
        shown = labels.replace("|", "\\|")  # a Markdown table's cell
        rows.append(f"| {mid} | `{file}` | {why} | `{shown}` | {by} | {seconds:.0f} s |")
        print(rows[-1], flush=True)
    if build(a.build).returncode != 0:
        sys.exit("the restored source does not build")
    print("\n| mutant | file | the bug | labels | first test that failed | time |\n"
          "| --- | --- | --- | --- | --- | --- |")
    print("\n".join(rows))
    share = 100.0 * killed / max(total, 1)
    print(f"\n{killed} of {total} mutants killed ({share:.0f} %)")
    return 0 if total and share >= 90 else 1


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/python3
"""No tracked file names a path that only some machines have, so that a clone builds and tests
itself anywhere: the work folder of the machines this project grew on, or a `shared` folder
beside the checkout. docs/ and bench/README.md may name them: they record where measurements
were made.

    tests/lint/check_paths.py SOURCE_DIR      exit 0 clean, 1 with file:line of each use,
                                              77 (CTest's skip) when SOURCE_DIR is no git checkout
"""
import subprocess
import sys

# Spelt in two pieces so that this file does not name them itself.
PATTERNS = [b"/" + b"work/", b"../" + b"shared"]
ALLOWED = ("docs/", "bench/README.md")


def main():
    root = sys.argv[1]
    try:
        listing = subprocess.run(["git", "-C", root, "ls-files", "-z"], check=True,
                                 capture_output=True).stdout
    except (OSError, subprocess.CalledProcessError) as e:
        print(f"SKIPPED: {root} is not a git checkout ({e})", file=sys.stderr)
        sys.exit(77)
    found = []
    for name in listing.decode().split("\0"):
        if not name or name.startswith(ALLOWED):
            continue
        try:
            with open(f"{root}/{name}", "rb") as f:
                lines = f.read().split(b"\n")
        except (FileNotFoundError, IsADirectoryError):  # deleted, not committed yet; submodule
            continue
        for number, line in enumerate(lines, 1):
            if any(p in line for p in PATTERNS):
                found.append(f"{name}:{number}: {line.decode(errors='replace').strip()[:120]}")
    for f in found:
        print(f)
    if found:
        print(f"{len(found)} lines name a path only some machines have (only docs/ and "
              "bench/README.md may)", file=sys.stderr)
    sys.exit(1 if found else 0)


if __name__ == "__main__":
    main()

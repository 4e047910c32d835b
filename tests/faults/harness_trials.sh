#!/usr/bin/env bash
# The harness's fault trials (issues 29 and 42). The `build` tier runs a few of each
# (tests/CMakeLists.txt: fault_trials); docs/reliability.md gives the full counts and results.
#   kill:        bless of a two-image case killed with SIGKILL after a delay (a fixed sequence of
#                10-99 ms); then the case's goldens must be all one set (a mix is a failure).
#   concurrent:  two checks of two suites into one report folder, each command copying its own
#                image; a run that exits 0 for an image it did not judge is a false PASS.
#   recreated:   the same, each run preceded by `rm -rf R`, the second started 0.1-0.9 s later
#                (the lock must hold by path, not by the deleted folder's inode).
#   processes:   checks of a command that leaves a setsid daemon and a double-forked orphan,
#                ended by exit, timeout, TERM, INT to the group, SIGKILL, or SIGKILL to the
#                group; any process of the command still alive afterwards is a leftover.
#   special:     a suite whose files entry, golden (links followed or not) or input links to /dev/zero, /dev/urandom or
#                a FIFO: each must be an ERROR naming it, within 1 GiB of peak memory.
# Exits 1 if any trial went wrong.
# Usage: tests/faults/harness_trials.sh AOSUITE_BIN [KILLS] [CONCURRENT] [RECREATED] [PROCESS_RUNS]
set -euo pipefail
bin=$(realpath "$1") kills=${2:-100} concurrent=${3:-20} recreated=${4:-20} runs=${5:-30}
failed=0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
mkdir -p s/shots
python3 - <<'EOF'
import os, random, struct, zlib
def png(path, w, h, pixel):
    raw = b"".join(b"\0" + b"".join(pixel(x, y) for x in range(w)) for y in range(h))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0))
                           + chunk(b"IDAT", zlib.compress(raw, 1)) + chunk(b"IEND", b""))
for k in range(2):
    rnd = random.Random(k)
    png(f"s/a{k}.png", 8, 6, lambda x, y: bytes([255 * k, 255 - 255 * k, 0, 255]))
    png(f"s/b{k}.png", 512, 512, lambda x, y: bytes(rnd.randrange(256) for _ in range(4)))
EOF
printf '[[case]]\nname = "two"\nfiles = ["shots/a.png", "shots/b.png"]\n' >s/two.toml
show() { cp "s/a$1.png" s/shots/a.png; cp "s/b$1.png" s/shots/b.png; }
which() {
  for k in 0 1; do
    if cmp -s "s/a$k.png" s/goldens/two/two/a.png && cmp -s "s/b$k.png" s/goldens/two/two/b.png; then
      echo "$k"
      return
    fi
  done
  echo mixed
}

show 0
"$bin" bless s/two.toml >/dev/null
mixed=0
for i in $(seq "$kills"); do
  k=$(which)
  show $((1 - k))
  "$bin" bless s/two.toml >/dev/null 2>&1 &
  p=$!
  sleep "0.0$((i * 37 % 90 + 10))"
  kill -9 "$p" 2>/dev/null || true
  wait "$p" 2>/dev/null || true
  [ "$(which)" = mixed ] && mixed=$((mixed + 1))
done
echo "kill: $kills blesses killed, $mixed mixed cases"
[ "$mixed" = 0 ] || failed=1

cp s/a0.png s/red.png && cp s/a1.png s/green.png
for s in A B; do
  printf '[[case]]\nname = "c"\ncommand = ["sh", "-c", "sleep 1; cp {suite_dir}/%s {out}/x.png"]\noutputs = ["x.png"]\n' \
    "$([ $s = A ] && echo red.png || echo green.png)" >"s/$s.toml"
done
cp s/a0.png s/expect.png
mkdir -p s/goldens/A/c s/goldens/B/c
cp s/a0.png s/goldens/A/c/x.png  # A's command draws red: PASS is right
cp s/a0.png s/goldens/B/c/x.png  # B's draws green: only a FAIL is right
# Two runs into one report folder, B's started `delay` seconds after A's, each after `prepare`.
# Counts a false PASS (B exits 0: its command draws green against a red golden).
pairs() {
  local n=$1 prepare=$2 false_pass=0 refused=0
  for i in $(seq "$n"); do
    (eval "$prepare"; "$bin" check s/A.toml --report R --no-reuse >/dev/null 2>&1) &
    a=$!
    sleep "0.$((i * 3 % 9 + 1))"
    set +e
    (eval "$prepare"; "$bin" check s/B.toml --report R --no-reuse >/dev/null 2>&1)
    rb=$?
    wait "$a"
    set -e
    [ "$rb" = 0 ] && false_pass=$((false_pass + 1))
    [ "$rb" = 2 ] && refused=$((refused + 1))
  done
  echo "$false_pass false PASS, $refused second runs refused (in use)"
  [ "$false_pass" = 0 ]
}
line=$(pairs "$concurrent" :) || failed=1
echo "concurrent: $concurrent pairs into one report folder, $line"
line=$(pairs "$recreated" 'rm -rf R 2>/dev/null || true') || failed=1
echo "recreated: $recreated pairs, each after rm -rf of the folder, $line"

cat >s/tree.sh <<'SH'
#!/bin/sh
setsid sh -c 'exec sleep 3001' &
( sleep 3002 & )
if [ -e "$1/hang" ]; then sleep 3003; fi
cp "$1/red.png" "$2/x.png"
SH
printf '[[case]]\nname = "tree"\ncommand = ["sh", "{suite_dir}/tree.sh", "{suite_dir}", "{out}"]\noutputs = ["x.png"]\ntimeout = 1\n' >s/tree.toml
left=0
for i in $(seq "$runs"); do
  how=$((i % 6))
  rm -f s/hang
  [ "$how" != 0 ] && touch s/hang
  set +e
  case $how in
    0 | 1) "$bin" check s/tree.toml --report T --no-reuse >/dev/null 2>&1 ;;  # exit; timeout
    *)
      setsid "$bin" check s/tree.toml --report T --no-reuse >/dev/null 2>&1 &
      p=$!
      sleep 0.3
      case $how in
        2) kill -TERM "$p" ;; 3) kill -INT -- "-$p" ;; 4) kill -KILL "$p" ;; 5) kill -KILL -- "-$p" ;;
      esac
      wait "$p" 2>/dev/null
      ;;
  esac
  set -e
  # Up to 5 s for the reaper to end what is left (a loaded machine is slow, never wrong).
  for _ in $(seq 50); do
    pgrep -f '^sleep 300[123]$' >/dev/null || break
    sleep 0.1
  done
  n=$( (pgrep -f '^sleep 300[123]$' || true) | wc -l)
  left=$((left + n))
  pkill -f '^sleep 300[123]$' || true
done
echo "processes: $runs runs ended by exit, timeout, TERM, INT, KILL, KILL to the group; $left processes left"
[ "$left" = 0 ] || failed=1

# A command's exit status, peak memory (KiB) and first ERROR line (or stderr's first line).
peak() {
  python3 -c 'import resource, subprocess, sys
r = subprocess.run(sys.argv[1:], capture_output=True, text=True)
lines = [l for l in r.stdout.splitlines() if " ERROR " in l] + r.stderr.splitlines()
print(r.returncode, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss, (lines or [""])[0])' "$@"
}
mkfifo s/fifo
special_bad=0 special=0
for target in /dev/zero /dev/urandom "$PWD/s/fifo"; do
  for where in files golden followed input; do
    rm -rf sp && mkdir -p sp/g/c && cp s/a0.png sp/x.png
    case $where in
      files) ln -s "$target" sp/y.png; f=y.png; extra= named=y.png ;;
      golden | followed) f=x.png; extra=; ln -s "$target" sp/g/c/x.png; named=g/c/x.png ;;
      input) f=x.png; ln -s "$target" sp/in.bin; extra='inputs = ["in.bin"]' named=in.bin ;;
    esac
    if [ "$where" = input ]; then
      printf '[[case]]\nname = "c"\ncommand = ["cp", "{suite_dir}/x.png", "{out}/x.png"]\noutputs = ["x.png"]\n%s\n' "$extra" >sp/s.toml
    else
      printf '[[case]]\nname = "c"\nfiles = ["%s"]\n' "$f" >sp/s.toml
    fi
    # Links followed by choice: the device or FIFO behind the golden is still refused.
    [ "$where" = followed ] && sed -i '1i follow_links = true' sp/s.toml
    [ -L sp/g/c/x.png ] || cp s/a0.png "sp/g/c/x.png"
    read -r rc kib line < <(peak timeout 60 "$bin" check sp/s.toml --goldens sp/g --report sp/R --no-reuse)
    special=$((special + 1))
    [ -n "${TRIALS_VERBOSE:-}" ] && echo "special: $where -> $target: exit $rc, peak $kib KiB: $line"
    if [ "$rc" != 2 ] || [ "$kib" -gt 1048576 ] || [[ "$line" != *"$named"* ]]; then
      special_bad=$((special_bad + 1))
      echo "special: $where -> $target: exit $rc, peak $kib KiB: $line" >&2
    fi
  done
done
echo "special: $special links to devices and FIFOs, $special_bad not refused by name within 1 GiB"
[ "$special_bad" = 0 ] || failed=1
exit "$failed"

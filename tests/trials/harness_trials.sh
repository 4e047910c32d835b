#!/usr/bin/env bash
# The harness's fault trials (issue 29), for people, not CI: they kill at random moments.
#   kill:        bless of a two-image case killed with SIGKILL after a random delay; then the
#                case's goldens must be all one set (a mix is a failure).
#   concurrent:  two checks of two suites into one report folder, each command copying its own
#                image; a run that exits 0 for an image it did not judge is a false PASS.
#   processes:   checks of a command that leaves a setsid daemon and a double-forked orphan,
#                ended by exit, timeout, TERM, INT to the group, or SIGKILL; any process of the
#                command still alive afterwards is a leftover.
# Usage: tests/trials/harness_trials.sh AOSUITE_BIN [KILLS] [CONCURRENT] [PROCESS_RUNS]
set -euo pipefail
bin=$(realpath "$1") kills=${2:-100} concurrent=${3:-20} runs=${4:-25}
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
    if cmp -s "s/a$k.png" goldens/two/two/a.png && cmp -s "s/b$k.png" goldens/two/two/b.png; then
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
  sleep "0.0$((RANDOM % 90 + 10))"
  kill -9 "$p" 2>/dev/null || true
  wait "$p" 2>/dev/null || true
  [ "$(which)" = mixed ] && mixed=$((mixed + 1))
done
echo "kill: $kills blesses killed at random, $mixed mixed cases"

cp s/a0.png s/red.png && cp s/a1.png s/green.png
for s in A B; do
  printf '[[case]]\nname = "c"\ncommand = ["sh", "-c", "sleep 0.3; cp {suite_dir}/%s {out}/x.png"]\noutputs = ["x.png"]\n' \
    "$([ $s = A ] && echo red.png || echo green.png)" >"s/$s.toml"
done
cp s/a0.png s/expect.png
mkdir -p goldens/A/c goldens/B/c
cp s/a0.png goldens/A/c/x.png  # A's command draws red: PASS is right
cp s/a0.png goldens/B/c/x.png  # B's draws green: only a FAIL is right
false_pass=0 refused=0
for i in $(seq "$concurrent"); do
  "$bin" check s/A.toml --report R --no-reuse >/dev/null 2>&1 &
  a=$!
  set +e
  "$bin" check s/B.toml --report R --no-reuse >/dev/null 2>&1
  rb=$?
  wait "$a"
  set -e
  [ "$rb" = 0 ] && false_pass=$((false_pass + 1))
  [ "$rb" = 2 ] && refused=$((refused + 1))
done
echo "concurrent: $concurrent pairs into one report folder, $false_pass false PASS, $refused second runs refused (in use)"

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
  how=$((i % 5))
  rm -f s/hang
  [ "$how" != 0 ] && touch s/hang
  set +e
  case $how in
    0 | 1) "$bin" check s/tree.toml --report T --no-reuse >/dev/null 2>&1 ;;  # exit; timeout
    *)
      setsid "$bin" check s/tree.toml --report T --no-reuse >/dev/null 2>&1 &
      p=$!
      sleep 0.3
      case $how in 2) kill -TERM "$p" ;; 3) kill -INT -- "-$p" ;; 4) kill -KILL "$p" ;; esac
      wait "$p"
      ;;
  esac
  set -e
  sleep 0.5
  n=$( (pgrep -f '^sleep 300[123]$' || true) | wc -l)
  left=$((left + n))
  pkill -f '^sleep 300[123]$' || true
done
echo "processes: $runs runs ended by exit, timeout, TERM, INT, KILL; $left processes left"

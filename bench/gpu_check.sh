#!/usr/bin/env bash
# Issue 44's GPU check: which OpenGL device renders and in which pipeline by default, then the
# per-pass table of every technique in both pipelines (fragment draws, compute dispatches) at
# 1920x1080 and 3840x2160, then the compute pipeline over the depth-only G-buffer, for
# bench/README.md's GPU section.
#
#   bench/gpu_check.sh [BUILD_DIR] [RUNS]        # defaults: build, 20
#
# EGL unless AOSUITE_GL says otherwise; GPU_CHECK_SIZES replaces the sizes (a smoke test on
# llvmpipe: GPU_CHECK_SIZES=64x36 bench/gpu_check.sh build 1). 28 renders of one warm-up and
# RUNS timed frames each, every output read back: from the H200's earlier frame times (25 ms
# at 1080p, 125 ms at 4K with read-back) about 2 minutes at RUNS=20, start-ups included.
set -euo pipefail
build=${1:-build}
runs=${2:-20}
sizes=${GPU_CHECK_SIZES:-1920x1080,3840x2160}
bench=$(cd "$(dirname "$0")" && pwd)
export AOSUITE_GL=${AOSUITE_GL:-egl}
start=$SECONDS
"$build/aosuite" gl-info
for pipeline in fragment compute; do
  python3 "$bench/pass_table.py" --bin "$build/aosuite" --runs "$runs" --sizes "$sizes" \
    --pipeline "$pipeline"
done
echo
echo "The compute pipeline over the depth-only G-buffer (--gbuffer depth):"
python3 "$bench/pass_table.py" --bin "$build/aosuite" --runs "$runs" --sizes "$sizes" \
  --pipeline compute -- --gbuffer depth
echo
echo "gpu_check.sh: $((SECONDS - start)) s"

#!/usr/bin/env bash
# Installs the build into a temporary prefix and uses it as a user and a C++ project would:
# from another directory, with only the prefix on PATH, the installed aosuite compares, renders
# and checks a folder; the bless command check prints runs as printed; `cpack -G DEB` packs
# usr/bin/aosuite; examples/renderer_test builds against the installed package and passes.
# Usage: tests/install_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
src=$1 build=$2 work=$3
rm -rf "$work"
mkdir -p "$work/elsewhere/actual" "$work/elsewhere/expected"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
export PATH="$work/prefix/bin:$PATH"
cd "$work/elsewhere"

golden="$src/examples/renderer_test/goldens/disc.png"
cp "$golden" actual/disc.png
cp "$golden" expected/disc.png
aosuite compare actual/disc.png expected/disc.png
aosuite render --scene plane --width 64 --height 48 --out rendered >/dev/null
test -s rendered/plane_above_alchemy_with_ao.png
aosuite check --actual actual --expected expected --report report

# A changed image fails, and the command check prints to accept it works as printed.
cp rendered/plane_above_alchemy_with_ao.png actual/disc.png
if aosuite check --actual actual --expected expected --report report >check.txt; then
  echo "install_test: a changed image passed" >&2
  exit 1
fi
bless=$(grep -o "aosuite bless --actual actual --expected expected --filter '[^']*'" check.txt)
eval "$bless"
cmp actual/disc.png expected/disc.png
aosuite check --actual actual --expected expected --report report >/dev/null

# The Debian package.
(cd "$build" && cpack -G DEB -B "$work/deb" >/dev/null)
deb=$(ls "$work"/deb/aosuite_*.deb)
contents=$(dpkg-deb -c "$deb")
grep -q '\./usr/bin/aosuite$' <<<"$contents"
grep -q '\./usr/lib/aosuite/libaosuite_check.so$' <<<"$contents"
grep -q libspng <<<"$(dpkg-deb -f "$deb" Depends)"

# A C++ consumer of the installed package.
cmake -S "$src/examples/renderer_test" -B "$work/example" -DCMAKE_PREFIX_PATH="$work/prefix" \
  >/dev/null
cmake --build "$work/example" -j "$(nproc)" >/dev/null
ctest --test-dir "$work/example" --output-on-failure
echo "install_test: installed aosuite, its .deb and the example consumer work"

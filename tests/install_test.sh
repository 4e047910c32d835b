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

# The Debian packages, one per thing users install (cmake/Install.cmake): lintian finds no
# error in any, and the image tool's Depends name nothing of the AO bench.
# (CPack's developer warnings that the plugins have no soname for a shlibs file go to its log.)
(cd "$build" && cpack -G DEB -B "$work/deb" >"$work/cpack.log" 2>&1) || { cat "$work/cpack.log" >&2; exit 1; }
for p in aosuite aosuite-oiio libaosuite-dev; do test -f "$work/deb/${p}_"*.deb; done
deb=$(ls "$work"/deb/aosuite_*.deb)
contents=$(dpkg-deb -c "$deb")
grep -q '\./usr/bin/aosuite$' <<<"$contents"
grep -q '\./usr/lib/[a-z0-9_-]*-linux-gnu/aosuite/libaosuite_check.so$' <<<"$contents"
grep -q '\./usr/share/doc/aosuite/copyright$' <<<"$contents"
depends=$(dpkg-deb -f "$deb" Depends)
grep -q libspng <<<"$depends"
if grep -Ei 'mesa|egl|libgl|embree|opencv|assimp|openimageio' <<<"$depends"; then
  echo "install_test: the image tool's package depends on the AO bench: $depends" >&2
  exit 1
fi
if command -v lintian >/dev/null; then
  lintian --fail-on error "$work"/deb/*.deb
else
  echo "install_test: lintian not installed (scripts/setup.sh installs it): packages not linted"
fi

# The aosuite package alone, unpacked in a scratch root: folder mode on PNG, JPEG and EXR works
# and loads no GL, EGL, Embree, assimp, OpenCV or OpenImageIO library.
dpkg-deb -x "$deb" "$work/root"
mkdir -p "$work/formats/actual" "$work/formats/expected"
cp "$golden" "$work/formats/actual/same.png"
cp "$src/fuzz/corpus/codecs/rgb_9x6.jpg" "$work/formats/actual/photo.jpg"
cp "$src/fuzz/corpus/exr/rgb_small.exr" "$work/formats/actual/light.exr"
cp "$work/formats/actual/"* "$work/formats/expected/"
cp rendered/plane_above_alchemy_with_ao.png "$work/formats/expected/changed.png"
cp "$golden" "$work/formats/actual/changed.png"
set +e
(cd "$work/formats" && LD_DEBUG=files "$work/root/usr/bin/aosuite" check --actual actual \
  --expected expected --report report >out.txt 2>ld.txt)
rc=$?
set -e
grep -q '4 images: 3 unchanged, 1 changed, 0 new, 0 deleted, 0 errors' "$work/formats/out.txt" ||
  { cat "$work/formats/out.txt" >&2; exit 1; }
[ "$rc" = 1 ]
grep -q 'file=.*libaosuite_exr.so' "$work/formats/ld.txt"
grep -q "file=$work/root/usr/lib/.*/aosuite/libaosuite_check.so" "$work/formats/ld.txt"
if grep -Ei 'file=[^ ]*(libEGL|libGL|libembree|libopencv|libassimp|libOpenImageIO)' \
  "$work/formats/ld.txt"; then
  echo "install_test: folder mode loaded a library of the AO bench" >&2
  exit 1
fi

# The same run in a root that holds nothing but the aosuite package and the libraries its
# binary and plugins link (ldd's closure): no GL, EGL, Embree, assimp, OpenCV or OpenImageIO
# library exists there at all. Run in new user, mount and pid namespaces (unshare -r).
lib_dirs="$work/root/usr/lib/$(dpkg-architecture -qDEB_HOST_MULTIARCH)"
lib_dirs="$lib_dirs:$lib_dirs/aosuite"
find "$work/root" -type f \( -name '*.so*' -o -path '*/bin/*' \) -print0 |
  xargs -0 -n1 env LD_LIBRARY_PATH="$lib_dirs" ldd |
  awk '/=> \//{print $3} /^\t\//{print $1}' | sort -u | grep -v "^$work/root" >"$work/closure.txt"
while read -r lib; do cp -L --parents "$lib" "$work/root/"; done <"$work/closure.txt"
if find "$work/root" | grep -Ei '(libEGL|libGL|libembree|libopencv|libassimp|libOpenImageIO)'; then
  echo "install_test: the scratch root holds a library of the AO bench" >&2
  exit 1
fi
if unshare -r true 2>/dev/null; then
  mkdir -p "$work/root/tmp" "$work/root/proc"
  cp -r "$work/formats" "$work/root/formats"
  rm -rf "$work/root/formats/report"
  set +e
  unshare -r -m -p -f --mount-proc --root="$work/root" --wd=/formats /usr/bin/aosuite check \
    --actual actual --expected expected --report report >"$work/root.txt" 2>&1
  rc=$?
  set -e
  grep -q '4 images: 3 unchanged, 1 changed, 0 new, 0 deleted, 0 errors' "$work/root.txt" ||
    { cat "$work/root.txt" >&2; exit 1; }
  [ "$rc" = 1 ]
  echo "install_test: folder mode ran in a root of the package and $(wc -l <"$work/closure.txt") libraries"
else
  echo "install_test: unshare -r is refused here (no user namespaces): the scratch-root run is" \
    "left out; the LD_DEBUG check above stands"
fi

# A C++ consumer of the installed package.
cmake -S "$src/examples/renderer_test" -B "$work/example" -DCMAKE_PREFIX_PATH="$work/prefix" \
  >/dev/null
cmake --build "$work/example" -j "$(nproc)" >/dev/null
ctest --test-dir "$work/example" --output-on-failure
echo "install_test: installed aosuite, its .deb and the example consumer work"

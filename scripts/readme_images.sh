#!/usr/bin/env bash
# Makes the README's pictures from a real failing case: the default suite's village-street GTAO
# golden against the same view rendered with a doubled radius, as golden | new | diff
# (docs/images/golden_new_diff.png), and the report that check writes for it, in headless
# Chromium (docs/images/report.png). Needs a build (scripts/setup.sh) and Debian's python3-pil.
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
golden=goldens/default/village-street-gtao-320x180/with_ao.png
build/aosuite render --scene village --view street --technique gtao --width 320 --height 180 \
  --param radius=1 --out "$work/new" >/dev/null
new="$work/new/village_street_gtao_with_ao.png"
build/aosuite compare "$golden" "$new" --diff "$work/diff.png" || true
/usr/bin/python3 - "$golden" "$new" "$work/diff.png" docs/images/golden_new_diff.png <<'PY'
import sys
from PIL import Image, ImageDraw
panels = [Image.open(p).convert("RGB") for p in sys.argv[1:4]]
w, h = panels[0].size
out = Image.new("RGB", (3 * w + 8, h + 20), "white")
draw = ImageDraw.Draw(out)
for i, (img, label) in enumerate(zip(panels, ["golden", "new (radius 1)", "diff"])):
    out.paste(img, (i * (w + 4), 20))
    draw.text((i * (w + 4) + 4, 4), label, fill="black")
out.save(sys.argv[4])
PY
mkdir -p "$work/actual" "$work/expected"
cp "$golden" "$work/expected/village-street.png"
cp "$new" "$work/actual/village-street.png"
cp goldens/default/corner-front-sao-320x180/with_ao.png "$work/expected/corner-front.png"
cp goldens/default/corner-front-sao-320x180/with_ao.png "$work/actual/corner-front.png"
(cd "$work" && "$OLDPWD/build/aosuite" check --actual actual --expected expected --report report \
  >/dev/null) || true
chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1280,720 \
  --screenshot="$work/report.png" "file://$work/report/index.html" 2>/dev/null
/usr/bin/python3 -c "from PIL import Image; Image.open('$work/report.png').convert('RGB').save('docs/images/report.png', optimize=True)"
echo "wrote docs/images/golden_new_diff.png and docs/images/report.png"

#!/usr/bin/env bash
# Regenerates the pictures of the README's Examples table into docs/img/gallery/: runs
# each example of the table (below, in the table's order) into a temporary folder and
# photographs the 3D view of its report.html in headless Chromium (Debian's
# /usr/bin/chromium driven by playwright-core from report/node_modules, as
# scripts/tutorial_pictures.sh does; no browser download), coloured by the maximum
# principal stretch, or by pressure (mmHg) for the compression and pressure examples
# (the sliding pants: by the tangential force above the friction limit).
#
#   simulate rows:  tightfit simulate SCENE --out DIR
#   optimize rows:  tightfit optimize SCENE --out DIR --time-limit 30
#                   (a short run of 30 s, not the example's full run: the pictures show
#                   where a short optimization gets, not the paper's result)
#   the pose row:   tightfit pose writes only the posed bodies (OBJ files), so the
#                   picture is the report of tightfit simulate on the same scene, shown in
#                   its "toe_off" pose, from the side (the report carries the garment into
#                   every pose)
#   the grading row: tightfit grade grading/left_leg.json grading/bodies_full.json
#                   --out DIR; the picture is its nest.svg (rsvg-convert), the cut lines
#                   only, one colour per body: regular blue, athletic orange, overweight
#                   green, child red
#
# Not run: the wetsuit's grade (the row's picture is its 30 s optimize run), because it
# runs the wetsuit's full optimization (1629 iterations, hours) on each of four bodies.
# The whole script takes about 10 minutes on two cores.
#
# A row with one scene gets a 360x270 picture; a row with two scenes gets two 180x270
# pictures side by side (the view zoomed out to keep the whole fit in the narrow frame).
# The pictures are quantized with pngquant when it is installed (it is not required).
#
# Usage: scripts/gallery_pictures.sh [TIGHTFIT_BINARY [NAME...]]
#   (default build/release/tightfit; NAME... regenerates only those pictures, e.g.
#   cover_sphere optimize_mask_pressure)
# Needs: node, chromium, rsvg-convert (librsvg2-bin), report/node_modules
# (scripts/install-deps.sh installs them).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
tightfit="$(realpath "${1:-$root/build/release/tightfit}")"
shift || true
only=("$@")
out="$root/docs/img/gallery"
time_limit=30
work="$(mktemp -d "${TMPDIR:-/tmp}/tightfit-gallery-pictures.XXXXXX")"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# One line per scene: SCENE COMMAND COLOURING WIDTH [pose=POSE] [turn=DEGREES]. SCENE is
# the scene's file in examples/ without .json, and the picture's NAME is SCENE with "_"
# for "/" (grading_left_leg); COLOURING is "stretch", "pressure" or
# "sliding"; WIDTH is 360 for a row of one scene and 180 for each scene of a row of two;
# pose= shows the fit in one of the scene's poses; turn= turns the camera about the
# vertical from the report's view (the cylinders, along z, are seen from their side).
examples=(
  "sleeve_two_panels simulate stretch 360 turn=55"
  "sleeve_soft_cylinder simulate pressure 180 turn=55"
  "sleeve_rigid_cylinder simulate pressure 180 turn=55"
  "sleeve_measured_knit simulate pressure 180 turn=55"
  "optimize_calf_sleeve_measured optimize pressure 180"
  "cover_sphere simulate stretch 180"
  "cover_sphere_three_pieces simulate stretch 180"
  "pants_legs simulate stretch 360"
  "left_leg_anchored_regular simulate stretch 180"
  "left_leg_anchored_child simulate stretch 180"
  "poses_legs_stride simulate stretch 360 pose=toe_off turn=70"
  "optimize_sleeve_stretch optimize stretch 180 turn=55"
  "optimize_sleeve_soft optimize stretch 180 turn=55"
  "optimize_cylinder_tapered optimize stretch 180 turn=55"
  "optimize_cylinder_hourglass optimize stretch 180 turn=55"
  "optimize_pants_stretch optimize stretch 360"
  "optimize_pants_seam_traction optimize stretch 360"
  "optimize_pants_shape optimize pressure 360"
  "optimize_pants_sliding optimize sliding 360"
  "optimize_sphere_pressure optimize pressure 360"
  "optimize_sphere_seam_stiffness optimize stretch 360"
  "optimize_mask_pressure optimize pressure 360"
  "optimize_stocking_graduated optimize pressure 360"
  "optimize_wetsuit_regular optimize stretch 360"
  "grading/left_leg grade nest 360"
)

wanted() {
  [ ${#only[@]} -eq 0 ] && return 0
  local n
  for n in "${only[@]}"; do [ "$n" = "$1" ] && return 0; done
  return 1
}

# 1. Run the examples one after the other (relative paths in a scene resolve against its
# folder, so the scenes are run where they are) and list the pictures to take.
jobs="$work/jobs.txt"
: > "$jobs"
made=()
for line in "${examples[@]}"; do
  read -r scene command coloring width options <<< "$line"
  name="${scene//\//_}"
  wanted "$name" || continue
  scene="$root/examples/$scene.json"
  dir="$work/$name"
  start=$SECONDS
  case "$command" in
    simulate) "$tightfit" simulate "$scene" --out "$dir" > "$work/$name.log" 2>&1 ;;
    optimize) "$tightfit" optimize "$scene" --out "$dir" --time-limit "$time_limit" > "$work/$name.log" 2>&1 ;;
    grade) "$tightfit" grade "$scene" "$root/examples/grading/bodies_full.json" --out "$dir" > "$work/$name.log" 2>&1 ;;
  esac || { echo "tightfit $command $name failed:"; tail -20 "$work/$name.log"; exit 1; }
  echo "$name: tightfit $command, $((SECONDS - start)) s"
  made+=("$name")
  if [ "$command" = grade ]; then
    # The nest of every size's pieces: cut lines 3 mm wide, one colour per body (the
    # pieces' groups are named piece-PIECE_BODY), nothing else.
    cat > "$work/nest.css" <<'CSS'
.sew, .notches, .grain, text, #test-square { display: none !important; }
.cut { stroke-width: 3 !important; }
g[id$="_regular"] .cut { stroke: #1f77b4 !important; }
g[id$="_athletic"] .cut { stroke: #ff7f0e !important; }
g[id$="_overweight"] .cut { stroke: #2ca02c !important; }
g[id$="_child"] .cut { stroke: #d62728 !important; }
CSS
    rsvg-convert -w "$width" -h 270 --keep-aspect-ratio -b white -s "$work/nest.css" "$dir/nest.svg" -o "$out/$name.png"
    echo "$name: ${out#"$root"/}/$name.png"
    continue
  fi
  echo "$name $dir/report.html $out/$name.png $coloring $width ${options:-}" >> "$jobs"
done

# 2. The 3D view of each report.html with the legend of its colouring under it.
cat > "$work/gallery.mjs" <<'JS'
import { createRequire } from 'node:module';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
const [root, jobsFile] = process.argv.slice(2);
const require = createRequire(path.join(root, 'report', 'package.json'));
const { chromium } = require('playwright-core');
const COLORINGS = { stretch: 'Max principal stretch', pressure: 'mmHg', sliding: 'Sliding' };
const HEIGHT = 270, LEGEND = 40;  // picture and legend heights (px)
const jobs = fs.readFileSync(jobsFile, 'utf8').trim().split('\n').filter((l) => l)
  .map((l) => { const [name, html, png, coloring, width, ...options] = l.split(' ');
    return { name, html, png, coloring, width: Number(width),
      ...Object.fromEntries(options.map((o) => o.split('='))) }; });
const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'tightfit-chromium-'));
const context = await chromium.launchPersistentContext(userDataDir, {
  executablePath: '/usr/bin/chromium',
  headless: true,
  viewport: { width: 1000, height: 700 },
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
try {
  const page = context.pages()[0] ?? await context.newPage();
  for (const job of jobs) {
    await page.goto(pathToFileURL(path.resolve(job.html)).href);
    await page.waitForFunction(() => window.tightfitReport && window.tightfitReport.ready === true, null, { timeout: 60000 });
    if (job.pose) {
      const poses = await page.locator('#pose option').allTextContents();
      const k = poses.indexOf(job.pose);
      if (k < 0) throw new Error(`${job.name}: no pose ${job.pose} among ${poses}`);
      await page.selectOption('#pose', String(k - 1));
      await page.waitForFunction((i) => window.tightfitReport.pose === i, k - 1);
    }
    const options = await page.locator('#coloring option').allTextContents();
    const coloring = options.findIndex((o) => o.includes(COLORINGS[job.coloring]));
    if (coloring < 0) throw new Error(`${job.name}: no ${job.coloring} colouring among ${options}`);
    await page.selectOption('#coloring', String(coloring));
    await page.waitForFunction((i) => window.tightfitReport.coloring === i, coloring);
    // The view and, under it, the legend (smaller, without its note and lift-off swatch) in a frame of the
    // picture's size at the top left of the page.
    const scale = Math.min(0.7, (job.width - 24) / 260);  // the legend's bar is 260 px
    await page.addStyleTag({ content: `
      #gallery-shot { position: fixed; left: 0; top: 0; z-index: 10; width: ${job.width}px;
        height: ${HEIGHT}px; background: rgb(238,240,243); overflow: hidden; }
      #gallery-shot #view3d { width: ${job.width}px; height: ${HEIGHT - LEGEND}px; }
      #gallery-shot #legend { transform: scale(${scale}); transform-origin: left top;
        width: ${Math.floor((job.width - 12) / scale)}px; margin: 2px 0 0 12px; flex-wrap: wrap;
        gap: 0 8px; min-height: 0; }
      #gallery-shot #legend .hint, #gallery-shot #legend > .cat { display: none; }` });
    await page.evaluate(() => {
      const shot = document.createElement('div');
      shot.id = 'gallery-shot';
      shot.append(document.getElementById('view3d'), document.getElementById('legend'));
      document.body.appendChild(shot);
    });
    await page.waitForFunction((w) => document.querySelector('#view3d canvas').width === w * devicePixelRatio, job.width);
    const view = page.locator('#view3d');
    const box = await view.boundingBox();
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    if (job.turn) {
      // OrbitControls: a drag of dx pixels turns the camera by 2 pi dx / the view's height.
      const before = await page.evaluate(() => window.tightfitReport.renderCount);
      await page.mouse.down();
      await page.mouse.move(box.x + box.width / 2 - Number(job.turn) / 360 * box.height, box.y + box.height / 2, { steps: 4 });
      await page.mouse.up();
      await page.waitForFunction((n) => window.tightfitReport.renderCount > n, before);
    }
    if (job.width < box.height) {
      // The report frames the fit for the view's height; a narrow view zooms out by the
      // aspect ratio (OrbitControls: a wheel step of 100 dollies by 1/0.95) to show it all.
      const before = await page.evaluate(() => window.tightfitReport.renderCount);
      await page.mouse.wheel(0, 100 * Math.log(box.height / job.width) / -Math.log(0.95));
      await page.waitForFunction((n) => window.tightfitReport.renderCount > n, before);
    }
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    await page.locator('#gallery-shot').screenshot({ path: job.png });
    console.log(`${job.name}: ${path.relative(root, job.png)}`);
  }
} finally {
  await context.close();
  fs.rmSync(userDataDir, { recursive: true, force: true });
}
JS
if [ -s "$jobs" ]; then (cd "$work" && node gallery.mjs "$root" "$jobs"); fi

# 3. Smaller files when pngquant is at hand.
if command -v pngquant > /dev/null; then
  for name in "${made[@]}"; do
    pngquant --force --skip-if-larger --quality 60-90 --strip --output "$out/$name.png" "$out/$name.png" || true
  done
fi
ls -l "$out"
du -ch "$out"/*.png | tail -1

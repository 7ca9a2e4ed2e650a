#!/usr/bin/env bash
# Regenerates the pictures of docs/tutorial.md into docs/img/ from the tutorial's own
# commands: runs them (tests/docs/tutorial_test.py --keep), then converts their outputs —
# pattern.svg with rsvg-convert, a page of pattern_a4.pdf with pdftoppm, and report.html
# in headless Chromium (Debian's /usr/bin/chromium driven by playwright-core from
# report/node_modules, as tests/report/report_browser_check.mjs does; no browser download).
# Usage: scripts/tutorial_pictures.sh [TIGHTFIT_BINARY]   (default build/release/tightfit)
# Needs: python3, rsvg-convert (librsvg2-bin), pdftoppm (poppler-utils), node, chromium,
# report/node_modules (scripts/install-deps.sh installs all of them).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
tightfit="$(realpath "${1:-$root/build/release/tightfit}")"
img="$root/docs/img"
work="$(mktemp -d "${TMPDIR:-/tmp}/tightfit-tutorial-pictures.XXXXXX")"
trap 'rm -rf "$work"' EXIT
mkdir -p "$img"

# 1. Every command of the tutorial, in a folder we keep.
python3 "$root/tests/docs/tutorial_test.py" --tightfit "$tightfit" --keep "$work/run"
run="$work/run/calf"

# 2. Patterns: 1:1 SVG -> PNG, 900 px wide, on white.
svg_png() { rsvg-convert -w 900 -b white "$1" -o "$2"; }
svg_png "$run/layout/pattern.svg" "$img/layout_pattern.png"
svg_png "$run/layout_drawn/pattern.svg" "$img/layout_drawn_pattern.png"
svg_png "$run/optimized/pattern.svg" "$img/optimized_pattern.png"

# 3. The first page of the tiled A4 PDF (grid label, alignment marks), 60 dpi.
pdftoppm -png -r 60 -f 1 -l 1 -singlefile "$run/optimized/pattern_a4.pdf" "$img/pattern_a4_page1"

# 4. report.html in headless Chromium: the top of the page with the 3D view coloured by
# pressure, and the region table with the histogram.
cat > "$work/shots.mjs" <<'JS'
import { createRequire } from 'node:module';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
const [root, html, outDir] = process.argv.slice(2);
const require = createRequire(path.join(root, 'report', 'package.json'));
const { chromium } = require('playwright-core');
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
  await page.goto(pathToFileURL(path.resolve(html)).href);
  await page.waitForFunction(() => window.tightfitReport && window.tightfitReport.ready === true, null, { timeout: 60000 });
  const options = await page.locator('#coloring option').allTextContents();
  const pressure = options.findIndex((o) => o.includes('mmHg'));
  if (pressure < 0) throw new Error(`no pressure colouring among ${options}`);
  await page.selectOption('#coloring', String(pressure));
  await page.waitForFunction((i) => window.tightfitReport.coloring === i, pressure);
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.screenshot({ path: path.join(outDir, 'report_top.png') });
  const regions = page.locator('section.block', { has: page.locator('#regions') });
  await regions.screenshot({ path: path.join(outDir, 'report_regions.png') });
  const history = page.locator('section.block', { has: page.locator('#history') });
  await history.screenshot({ path: path.join(outDir, 'report_history.png') });
} finally {
  await context.close();
  fs.rmSync(userDataDir, { recursive: true, force: true });
}
JS
(cd "$work" && node shots.mjs "$root" "$run/optimized/report.html" "$work")

for name in report_top report_regions report_history; do cp "$work/$name.png" "$img/$name.png"; done
ls -l "$img"

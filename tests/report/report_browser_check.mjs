// Opens report.html in headless Chromium (Debian's /usr/bin/chromium, driven by npm
// playwright-core from report/node_modules; no browser download) and checks that it
// works offline: no console errors, no network requests, a WebGL canvas that is not
// blank, that switching the colour map changes the 3D picture and the pattern, and
// (fits with poses) that switching the pose moves the 3D picture.
// Usage: node report_browser_check.mjs REPORT.html OUT_DIR
// Writes OUT_DIR/{view_initial,view_switched,page}.png and prints a JSON summary;
// exits 0 when every check passes, 1 otherwise, 2 when the browser cannot run.
import { createRequire } from 'node:module';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const reportDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../report');
const require = createRequire(path.join(reportDir, 'package.json'));
const [htmlPath, outDir] = process.argv.slice(2);
if (!htmlPath || !outDir) {
  console.error('usage: node report_browser_check.mjs REPORT.html OUT_DIR');
  process.exit(2);
}
const CHROMIUM = '/usr/bin/chromium';
if (!fs.existsSync(CHROMIUM)) {
  console.error(`${CHROMIUM} is missing (Debian package chromium; run scripts/install-deps.sh)`);
  process.exit(2);
}
let chromium;
try {
  ({ chromium } = require('playwright-core'));
} catch (e) {
  console.error(`playwright-core is not installed in ${reportDir}/node_modules (run scripts/install-deps.sh): ${e.message}`);
  process.exit(2);
}

// Decodes two PNG screenshots in the page and compares them: the share of pixels of A
// away from the background, and of pixels that differ between A and B.
async function comparePixels(page, a, b, bg) {
  return page.evaluate(async ({ a, b, bg }) => {
    const decode = async (b64) => {
      const img = new Image();
      img.src = 'data:image/png;base64,' + b64;
      await img.decode();
      const c = document.createElement('canvas');
      c.width = img.width;
      c.height = img.height;
      const ctx = c.getContext('2d');
      ctx.drawImage(img, 0, 0);
      return ctx.getImageData(0, 0, c.width, c.height);
    };
    const A = await decode(a);
    const B = await decode(b);
    let notBackground = 0;
    let changed = 0;
    const n = A.width * A.height;
    for (let i = 0; i < n; ++i) {
      const o = 4 * i;
      const dBg = Math.abs(A.data[o] - bg[0]) + Math.abs(A.data[o + 1] - bg[1]) + Math.abs(A.data[o + 2] - bg[2]);
      if (dBg > 24) notBackground++;
      const dAB = Math.abs(A.data[o] - B.data[o]) + Math.abs(A.data[o + 1] - B.data[o + 1]) + Math.abs(A.data[o + 2] - B.data[o + 2]);
      if (dAB > 24) changed++;
    }
    return { width: A.width, height: A.height, notBackground: notBackground / n, changed: changed / n,
      sameSize: A.width === B.width && A.height === B.height };
  }, { a: a.toString('base64'), b: b.toString('base64'), bg });
}

fs.mkdirSync(outDir, { recursive: true });
const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'tightfit-chromium-'));
const failures = [];
const consoleErrors = [];
const externalRequests = [];
const summary = {};
let context;
try {
  context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: CHROMIUM,
    headless: true,
    viewport: { width: 1280, height: 900 },
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--use-angle=swiftshader',
      '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  const page = context.pages()[0] ?? await context.newPage();
  page.on('console', (m) => { if (m.type() === 'error') consoleErrors.push(m.text()); });
  page.on('pageerror', (e) => consoleErrors.push(`page error: ${e.message}`));
  await page.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith('file:') || url.startsWith('data:') || url.startsWith('blob:')) return route.continue();
    externalRequests.push(url);
    return route.abort();
  });

  // Stop at the first uncaught page error instead of waiting for a page that never gets ready.
  const pageFailed = new Promise((_, reject) => page.on('pageerror', (e) => reject(new Error(`page error: ${e.message}`))));
  pageFailed.catch(() => {});
  await page.goto(pathToFileURL(path.resolve(htmlPath)).href);
  await Promise.race([
    page.waitForFunction(() => window.tightfitReport && window.tightfitReport.ready === true, null, { timeout: 30000 }),
    pageFailed,
  ]);
  summary.webgl = await page.evaluate(() => {
    const gl = document.createElement('canvas').getContext('webgl2');
    return gl ? gl.getParameter(gl.VERSION) : null;
  });
  const canvas = page.locator('#view3d canvas');
  const background = await page.evaluate(() => window.tightfitReport.background);
  const options = await page.locator('#coloring option').allTextContents();
  summary.colorings = options;

  const settle = async () => {
    const count = await page.evaluate(() => window.tightfitReport.renderCount);
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    return count;
  };
  await settle();
  const shotA = await canvas.screenshot({ path: path.join(outDir, 'view_initial.png') });
  const fillsA = await page.locator('#pattern path[fill]').evaluateAll((els) => els.map((e) => e.getAttribute('fill')));
  const legendA = await page.locator('#legend').textContent();

  // Switch to the pressure map (or the second one) through the page's own control.
  const target = options.findIndex((o) => o.includes('mmHg'));
  const index = target >= 0 ? target : 1;
  await page.selectOption('#coloring', String(index));
  await page.waitForFunction((i) => window.tightfitReport.coloring === i, index);
  await settle();
  const shotB = await canvas.screenshot({ path: path.join(outDir, 'view_switched.png') });
  const fillsB = await page.locator('#pattern path[fill]').evaluateAll((els) => els.map((e) => e.getAttribute('fill')));
  const legendB = await page.locator('#legend').textContent();
  await page.screenshot({ path: path.join(outDir, 'page.png'), fullPage: true });

  const pixels = await comparePixels(page, shotA, shotB, background);
  summary.pixels = pixels;
  summary.patternTriangles = fillsA.length;
  summary.patternFillsChanged = fillsA.filter((f, i) => f !== fillsB[i]).length;
  summary.legend = [legendA, legendB];
  summary.statsRows = await page.locator('#stats tbody tr').count();
  summary.statsText = await page.locator('#stats').textContent();
  summary.regionRows = await page.locator('#regions tbody tr').count();
  summary.regionsText = await page.locator('#regions').textContent();
  summary.shapeSectionVisible = await page.locator('#shape-section').isVisible();
  // Per silhouette view: the share of non-white pixels and the number of distinct
  // colours among them (the three translucent layers and their overlaps).
  summary.silhouettes = await page.locator('#silhouettes canvas').evaluateAll((canvases) => canvases.map((c) => {
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let filled = 0;
    const colours = new Set();
    for (let i = 0; i < d.length; i += 4) {
      if (d[i] > 250 && d[i + 1] > 250 && d[i + 2] > 250) continue;
      ++filled;
      colours.add((d[i] >> 4) * 256 + (d[i + 1] >> 4) * 16 + (d[i + 2] >> 4));
    }
    return { view: c.dataset.view, filled: filled / (c.width * c.height), colours: colours.size };
  }));
  summary.seamRows = await page.locator('#seams tbody tr').count();
  summary.seamsText = await page.locator('#seams').textContent();
  summary.measurementRows = await page.locator('#measurements tbody tr').count();
  summary.measurementsText = await page.locator('#measurements').textContent();
  summary.fabricCurves = await page.locator('#fabric polyline.curve').count();
  summary.fabricPoints = await page.locator('#fabric circle.working-point').count();
  summary.fabricRows = await page.locator('#fabric-working-points tbody tr').count();
  summary.fabricText = await page.locator('#fabric').textContent();
  summary.histogramBars = await page.locator('#histogram rect.bar').count();
  summary.liftoffBars = await page.locator('#histogram rect.bar.liftoff').count();
  summary.targetLines = await page.locator('#histogram line.target').count();
  summary.pressureWarnings = await page.locator('#histogram .pressure-warning').count();
  summary.initialOutlines = await page.locator('#pattern polygon.initial-outline').count();
  summary.seamEdges = await page.locator('#pattern polyline.seam-edge').count();
  summary.pinnedEdges = await page.locator('#pattern polyline.pinned-edge').count();
  summary.edgeLabels = await page.locator('#pattern text.edge-label').allTextContents();
  summary.historyCurves = await page.locator('#history polyline.history-curve').evaluateAll((els) => els.map((e) => e.getAttribute('data-term')));
  summary.historyTicks = await page.locator('#history text.ytick-label').allTextContents();
  summary.summaryText = await page.locator('#summary').textContent();
  summary.title = await page.title();
  // The colour scale: percentiles by default, the data's own range on request.
  await page.check('#full-range');
  await settle();
  summary.legendFullRange = await page.locator('#legend').textContent();
  // Seams and edges in 3D, and the colouring by piece.
  summary.edges = await page.evaluate(() => window.tightfitReport.edges);
  const pieceOption = options.indexOf('Piece');
  if (pieceOption >= 0) {
    await page.selectOption('#coloring', String(pieceOption));
    await page.waitForFunction((i) => window.tightfitReport.coloring === i, pieceOption);
    await settle();
    summary.legendPiece = await page.locator('#legend').textContent();
  }

  // The pose switch (fits with poses): the garment and body move into the pose.
  summary.poses = await page.locator('#pose option').allTextContents();
  summary.poseSwitchVisible = await page.locator('#pose-label').isVisible();
  if (summary.poses.length > 1) {
    await settle();
    const neutral = await canvas.screenshot({ path: path.join(outDir, 'view_neutral_pose.png') });
    await page.selectOption('#pose', '0');
    await page.waitForFunction(() => window.tightfitReport.pose === 0);
    await settle();
    const posed = await canvas.screenshot({ path: path.join(outDir, 'view_pose.png') });
    summary.poseHint = await page.locator('#pose-hint').textContent();
    summary.posePixelsChanged = (await comparePixels(page, neutral, posed, background)).changed;
    if (summary.posePixelsChanged < 0.01) failures.push(`switching the pose changed only ${(100 * summary.posePixelsChanged).toFixed(2)} % of the 3D view`);
  }

  if (consoleErrors.length > 0) failures.push(`console errors: ${consoleErrors.join(' | ')}`);
  if (externalRequests.length > 0) failures.push(`network requests: ${externalRequests.join(' ')}`);
  if (!summary.webgl) failures.push('no WebGL 2 context in this browser');
  if (pixels.width < 100 || pixels.height < 100) failures.push(`canvas too small: ${pixels.width}x${pixels.height}`);
  if (pixels.notBackground < 0.05) failures.push(`3D view looks blank: ${(100 * pixels.notBackground).toFixed(2)} % non-background pixels`);
  if (!pixels.sameSize || pixels.changed < 0.02) failures.push(`switching the colour map changed only ${(100 * pixels.changed).toFixed(2)} % of the 3D view`);
  if (fillsA.length === 0) failures.push('the pattern view has no coloured triangles');
  if (summary.patternFillsChanged < fillsA.length / 4) failures.push(`switching the colour map changed only ${summary.patternFillsChanged} of ${fillsA.length} pattern triangles`);
  if (legendA === legendB) failures.push('the legend did not change with the colour map');
  if (!/scale: 1st–99th percentile/.test(legendB)) failures.push(`the legend does not state its scale: ${legendB}`);
  if (!/scale: full data range/.test(summary.legendFullRange)) failures.push(`the full-range switch did not change the legend: ${summary.legendFullRange}`);
} catch (e) {
  failures.push(`browser check failed: ${e.stack ?? e}`);
} finally {
  if (context) await context.close();
  fs.rmSync(userDataDir, { recursive: true, force: true });
}
console.log(JSON.stringify({ ...summary, consoleErrors, externalRequests, failures }, null, 2));
process.exit(failures.length === 0 ? 0 : 1);

// tightfit report viewer: reads the fit data embedded in report.html (see
// src/tightfit/report/data.hpp for its layout) and draws the 3D view (three.js),
// the legend, the pattern pieces, the statistics, the history and the parameters.
// Exposes window.tightfitReport = {ready, renderCount, background, coloring, setColoring,
// pose, setPose}
// for the browser test (tests/report/report_browser_check.mjs).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const data = JSON.parse(document.getElementById('tightfit-data').textContent);
const BACKGROUND = [238, 240, 243];
const NO_VALUE = [153, 153, 153];
const SVG_NS = 'http://www.w3.org/2000/svg';
const report = { ready: false, renderCount: 0, background: BACKGROUND, coloring: -1, setColoring: null,
  pose: -1, setPose: null };
window.tightfitReport = report;

// ---- decoding --------------------------------------------------------------------

function typedArray(text) {
  const [kind, b64] = [text.slice(0, 4), text.slice(4)];
  const binary = atob(b64);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  if (kind === 'f32:') return new Float32Array(bytes.buffer);
  if (kind === 'u32:') return new Uint32Array(bytes.buffer);
  throw new Error('unknown array encoding ' + kind);
}

const garment = { positions: typedArray(data.garment.positions), indices: typedArray(data.garment.indices),
  normals: data.garment.normals ? typedArray(data.garment.normals) : null };
const body = data.body ? { positions: typedArray(data.body.positions), indices: typedArray(data.body.indices) } : null;
// Each colouring keeps its robust range (percentiles) and can switch to the data's own.
const colorings = data.colorings.map((c) => ({
  ...c, values: typedArray(c.values), robust: [c.lo, c.hi], fixed: c.range_rule === 'fixed',
}));
let fullRange = false;
// Colour by piece: a categorical colouring made here from the pieces' faces.
const PIECE_COLORS = [[31, 119, 180], [255, 127, 14], [44, 160, 44], [214, 39, 40], [148, 103, 189],
  [140, 86, 75], [227, 119, 194], [127, 127, 127], [188, 189, 34], [23, 190, 207]];
if (data.pieces.length > 0 && data.pieces.length <= 64) {
  const values = new Float32Array(garment.indices.length / 3).fill(NaN);
  data.pieces.forEach((p, k) => { for (const f of typedArray(p.faces)) values[f] = k; });
  colorings.push({ field: 'piece', label: 'Piece', unit: '', values, fixed: true,
    categories: data.pieces.map((p, k) => ({ value: k, label: p.name, color: PIECE_COLORS[k % PIECE_COLORS.length] })) });
}
// Poses: the garment carried into each pose of the scene, the posed body, and per face
// the tangential force above the friction limit there (the "sliding" colouring shows
// the worst pose in the neutral view).
const poses = (data.poses || []).map((p) => ({
  ...p, garment: typedArray(p.garment), normals: typedArray(p.normals), body: typedArray(p.body),
  sliding_excess: typedArray(p.sliding_excess),
}));
const slidingColoring = colorings.find((c) => c.field === 'sliding_excess_n') || null;
const neutralSliding = slidingColoring ? slidingColoring.values : null;
const pieces = data.pieces.map((p) => ({
  ...p, rest: typedArray(p.rest), triangles: typedArray(p.triangles), faces: typedArray(p.faces),
  initial: p.initial_outline ? typedArray(p.initial_outline) : null,
}));

// ---- numbers ---------------------------------------------------------------------

function fmt(v, digits = 3) {
  if (v === null || v === undefined || Number.isNaN(v)) return '–';
  if (v === 0) return '0';
  const a = Math.abs(v);
  if (a >= 1e5 || a < 1e-3) return v.toExponential(digits - 1);
  return Number(v.toPrecision(digits)).toString();
}

function percent(v) { return v === null || v === undefined ? '–' : (100 * v).toFixed(1) + ' %'; }

// ---- colours ---------------------------------------------------------------------

/// sRGB bytes of a value under a colouring (same rule as fit_colormap.hpp).
function colorOf(coloring, value) {
  if (Number.isNaN(value)) return NO_VALUE;
  if (coloring.categories) {
    const k = Math.min(Math.max(Math.round(value), 0), coloring.categories.length - 1);
    return coloring.categories[k].color;
  }
  if (coloring.negative_color && value < 0) return coloring.negative_color;
  let t = (value - coloring.lo) / (coloring.hi - coloring.lo);
  t = Math.min(Math.max(t, 0), 1);
  const i = Math.round(t * 255) * 3;
  return [coloring.lut[i], coloring.lut[i + 1], coloring.lut[i + 2]];
}

function cssColor(rgb) { return `rgb(${rgb[0]},${rgb[1]},${rgb[2]})`; }

// ---- 3D view ---------------------------------------------------------------------

const container = document.getElementById('view3d');
const renderer = new THREE.WebGLRenderer({ antialias: true });
renderer.setPixelRatio(window.devicePixelRatio);
container.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color().setRGB(...BACKGROUND.map((b) => b / 255), THREE.SRGBColorSpace);
scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8f99, 2.0));
const camera = new THREE.PerspectiveCamera(35, 1, 0.001, 100);
const headlight = new THREE.DirectionalLight(0xffffff, 1.2);
camera.add(headlight);
scene.add(camera);

// Display lift: the garment and its body are both triangulations of the same limit
// surface, so where the garment's triangles are longer their chords sag below the
// body's and the body would show through. The garment is drawn lifted along the body's
// outward normal by a tenth of its mean edge (stated under the view); the numbers are
// the simulated positions.
const garmentEdge = (() => {
  let sum = 0;
  const p = garment.positions, t = garment.indices;
  for (let f = 0; f < t.length; f += 3)
    for (let k = 0; k < 3; ++k) {
      const a = 3 * t[f + k], b = 3 * t[f + (k + 1) % 3];
      sum += Math.hypot(p[a] - p[b], p[a + 1] - p[b + 1], p[a + 2] - p[b + 2]);
    }
  return t.length > 0 ? sum / t.length : 0;
})();
const displayLift = garment.normals ? 0.1 * garmentEdge : 0;
// Garment vertex positions lifted by `factor` display lifts along `normals`.
function liftedPositions(positions, normals, factor) {
  const out = new Float32Array(positions.length);
  for (let i = 0; i < out.length; ++i) out[i] = positions[i] + (normals ? factor * displayLift * normals[i] : 0);
  return out;
}

// Garment: one vertex per face corner so that every face shows its own colour.
const garmentGeometry = new THREE.BufferGeometry();
function setGarmentPositions(positions, normals) {
  const lifted = liftedPositions(positions, normals, 1);
  const n = garment.indices.length;
  const corners = new Float32Array(3 * n);
  for (let i = 0; i < n; ++i) {
    const v = garment.indices[i];
    corners.set(lifted.subarray(3 * v, 3 * v + 3), 3 * i);
  }
  garmentGeometry.setAttribute('position', new THREE.BufferAttribute(corners, 3));
  garmentGeometry.computeVertexNormals();
}
setGarmentPositions(garment.positions, garment.normals);
garmentGeometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(3 * garment.indices.length), 3));
const garmentMesh = new THREE.Mesh(garmentGeometry,
  new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide }));
scene.add(garmentMesh);

// Body: grey and smooth. The garment lies on the body's surface; the body is drawn with
// a polygon offset (pushed away in depth) so that the garment is never hidden by it.
let bodyMesh = null;
if (body) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(body.positions, 3));
  geometry.setIndex(new THREE.BufferAttribute(body.indices, 1));
  geometry.computeVertexNormals();
  bodyMesh = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({
    color: 0xb9bcc2, polygonOffset: true, polygonOffsetFactor: 2, polygonOffsetUnits: 4,
  }));
  scene.add(bodyMesh);
}

// Seams (edges between faces of two pieces), pinned edges (both ends held on the body:
// cuffs, waistbands) and free garment edges, drawn as lines a little above the garment.
const faceCount = garment.indices.length / 3;
const facePiece = new Int32Array(faceCount).fill(-1);
pieces.forEach((p, k) => { for (const f of p.faces) facePiece[f] = k; });
const pinned = new Set(Array.isArray(data.pinned) ? data.pinned : []);
const edgeLines = { seam: [], pinned: [], free: [] };
{
  const faceOfEdge = new Map();
  const t = garment.indices;
  for (let f = 0; f < faceCount; ++f)
    for (let k = 0; k < 3; ++k) {
      const a = t[3 * f + k], b = t[3 * f + (k + 1) % 3];
      const key = a < b ? `${a},${b}` : `${b},${a}`;
      const other = faceOfEdge.get(key);
      if (other === undefined) { faceOfEdge.set(key, f); continue; }
      faceOfEdge.set(key, -1 - other);  // seen twice
      if (facePiece[other] !== facePiece[f]) edgeLines.seam.push(a, b);
    }
  for (const [key, f] of faceOfEdge) {
    if (f < 0) continue;
    const [a, b] = key.split(',').map(Number);
    (pinned.has(a) && pinned.has(b) ? edgeLines.pinned : edgeLines.free).push(a, b);
  }
}
const edgeGroup = new THREE.Group();
// The edge lines of every kind at garment positions `positions` (lifted 1.5 display lifts).
function setEdgePositions(positions, normals) {
  const lifted = liftedPositions(positions, normals, 1.5);
  for (const lines of edgeGroup.children) {
    const ends = edgeLines[lines.name];
    const out = new Float32Array(3 * ends.length);
    ends.forEach((v, i) => out.set(lifted.subarray(3 * v, 3 * v + 3), 3 * i));
    lines.geometry.setAttribute('position', new THREE.BufferAttribute(out, 3));
  }
}
for (const [kind, color] of [['seam', 0x111111], ['pinned', 0xd42a2a], ['free', 0x5b6570]]) {
  if (edgeLines[kind].length === 0) continue;
  const lines = new THREE.LineSegments(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color }));
  lines.name = kind;
  edgeGroup.add(lines);
}
setEdgePositions(garment.positions, garment.normals);
scene.add(edgeGroup);
report.edges = { seam: edgeLines.seam.length / 2, pinned: edgeLines.pinned.length / 2, free: edgeLines.free.length / 2 };
document.getElementById('view-hint').textContent +=
  ` Lines: black seams, red pinned edges (cuffs, waistbands), grey free edges. The garment is drawn ${fmt(1000 * displayLift, 2)} mm above the body (a tenth of its mean edge) so that the body never shows through; the numbers are the simulated positions.`;

const controls = new OrbitControls(camera, renderer.domElement);
{
  garmentGeometry.computeBoundingSphere();
  const sphere = garmentGeometry.boundingSphere.clone();
  if (bodyMesh) {
    bodyMesh.geometry.computeBoundingSphere();
    sphere.union(bodyMesh.geometry.boundingSphere);
  }
  const radius = Math.max(sphere.radius, 1e-3);
  const distance = radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 1.1;
  controls.target.copy(sphere.center);
  camera.position.copy(sphere.center).add(new THREE.Vector3(0.35, 0.25, 1).normalize().multiplyScalar(distance));
  camera.near = distance / 100;
  camera.far = distance * 10;
  camera.updateProjectionMatrix();
  controls.update();
}

function render() {
  renderer.render(scene, camera);
  report.renderCount += 1;
}

function resize() {
  const w = Math.max(container.clientWidth, 1);
  const h = Math.max(container.clientHeight, 1);
  renderer.setSize(w, h, false);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  render();
}
controls.addEventListener('change', render);
new ResizeObserver(resize).observe(container);

document.getElementById('show-edges').addEventListener('change', (e) => {
  edgeGroup.visible = e.target.checked;
  render();
});
document.getElementById('show-body').addEventListener('change', (e) => {
  if (bodyMesh) bodyMesh.visible = e.target.checked;
  render();
});

// ---- legend ----------------------------------------------------------------------

function drawLegend(coloring) {
  const legend = document.getElementById('legend');
  legend.replaceChildren();
  const unit = coloring.unit ? ` (${coloring.unit})` : ' (–)';
  const title = document.createElement('strong');
  title.textContent = coloring.label + (coloring.categories ? '' : unit);
  legend.appendChild(title);
  if (coloring.categories) {
    for (const c of coloring.categories) {
      const item = document.createElement('span');
      item.className = 'cat';
      item.innerHTML = `<span class="swatch" style="background:${cssColor(c.color)}"></span>`;
      item.appendChild(document.createTextNode(c.label));
      legend.appendChild(item);
    }
    return;
  }
  const box = document.createElement('div');
  const canvas = document.createElement('canvas');
  canvas.width = 260;
  canvas.height = 14;
  const ctx = canvas.getContext('2d');
  for (let x = 0; x < canvas.width; ++x) {
    const i = Math.round((x / (canvas.width - 1)) * 255) * 3;
    ctx.fillStyle = cssColor([coloring.lut[i], coloring.lut[i + 1], coloring.lut[i + 2]]);
    ctx.fillRect(x, 0, 1, canvas.height);
  }
  const ticks = document.createElement('div');
  ticks.className = 'ticks';
  // Enough digits that neighbouring ticks differ: the range's span sets the last digit.
  const span = coloring.hi - coloring.lo;
  const magnitude = Math.max(Math.abs(coloring.lo), Math.abs(coloring.hi));
  const digits = Math.min(8, Math.max(3, Math.ceil(Math.log10(magnitude / span)) + 2));
  const clampedLow = coloring.data_min < coloring.lo, clampedHigh = coloring.data_max > coloring.hi;
  // Ends, middle and zero (when inside the range), leaving out ticks that would overlap.
  const candidates = [coloring.lo, coloring.hi];
  if (coloring.lo < 0 && coloring.hi > 0) candidates.push(0);
  candidates.push((coloring.lo + coloring.hi) / 2);
  const values = [];
  for (const v of candidates) {
    const t = (v - coloring.lo) / (coloring.hi - coloring.lo);
    if (values.every((w) => Math.abs((w - coloring.lo) / (coloring.hi - coloring.lo) - t) > 0.15)) values.push(v);
  }
  for (const v of values) {
    const t = (v - coloring.lo) / (coloring.hi - coloring.lo);
    const tick = document.createElement('span');
    tick.style.left = `${Math.min(Math.max(t, 0.04), 0.96) * 100}%`;
    const prefix = v === coloring.lo && clampedLow ? '≤ ' : v === coloring.hi && clampedHigh ? '≥ ' : '';
    tick.textContent = prefix + fmt(v, digits);
    if (prefix) tick.className = 'clamped';
    ticks.appendChild(tick);
  }
  box.append(canvas, ticks);
  legend.appendChild(box);
  if (coloring.negative_color) {
    const item = document.createElement('span');
    item.className = 'cat';
    item.innerHTML = `<span class="swatch" style="background:${cssColor(coloring.negative_color)}"></span>`;
    item.appendChild(document.createTextNode('lift-off (< 0)'));
    legend.appendChild(item);
  }
  const note = document.createElement('span');
  note.className = 'hint';
  const rule = coloring.fixed ? 'fixed range'
    : fullRange ? 'full data range' : '1st–99th percentile of the faces';
  const outside = clampedLow || clampedHigh
    ? ` (data ${fmt(coloring.data_min, digits)} to ${fmt(coloring.data_max, digits)}; ≤/≥ ends are clamped)` : '';
  note.textContent = `scale: ${rule}${coloring.include_zero ? ', with 0' : ''}${outside}; grey: no value`;
  legend.appendChild(note);
}

// ---- pattern pieces --------------------------------------------------------------

const patternTriangles = [];  // [{element, face}]

/// A stable colour per seam name, so that the two sides of a seam match across pieces.
const SEAM_COLORS = ['#1f77b4', '#2ca02c', '#9467bd', '#8c564b', '#e377c2', '#17becf', '#bcbd22', '#ff7f0e'];
function seamColor(name) {
  let h = 0;
  for (const ch of name) h = (h * 31 + ch.codePointAt(0)) >>> 0;
  return SEAM_COLORS[h % SEAM_COLORS.length];
}

function drawPattern() {
  const host = document.getElementById('pattern');
  if (pieces.length === 0) {
    host.textContent = 'No pattern pieces.';
    return;
  }
  const gap = 0.03;  // m between pieces
  let x0 = 0;
  let top = -Infinity;
  let bottom = Infinity;
  const placed = [];
  for (const p of pieces) {
    let minX = Infinity, maxX = -Infinity, minY = Infinity, maxY = -Infinity;
    for (const xy of [p.rest, p.initial ?? []]) {
      for (let i = 0; i < xy.length; i += 2) {
        minX = Math.min(minX, xy[i]); maxX = Math.max(maxX, xy[i]);
        minY = Math.min(minY, xy[i + 1]); maxY = Math.max(maxY, xy[i + 1]);
      }
    }
    if (!Number.isFinite(minX)) { minX = maxX = minY = maxY = 0; }
    placed.push({ p, dx: x0 - minX, minX, maxX, minY, maxY });
    x0 += maxX - minX + gap;
    top = Math.max(top, maxY);
    bottom = Math.min(bottom, minY);
  }
  const width = Math.max(x0 - gap, 1e-3);
  const labelSpace = 0.05;  // m below the pieces for names and the scale bar
  const height = Math.max(top - bottom, 1e-3) + labelSpace;
  const margin = 0.01;
  const svg = document.createElementNS(SVG_NS, 'svg');
  svg.setAttribute('viewBox', `${-margin} ${-top - margin} ${width + 2 * margin} ${height + 2 * margin}`);
  svg.setAttribute('role', 'img');
  const stroke = width / 600;
  for (const { p, dx, minX, maxX, minY, maxY } of placed) {
    const g = document.createElementNS(SVG_NS, 'g');
    g.setAttribute('data-piece', p.name);
    const pt = (v) => [p.rest[2 * v] + dx, -p.rest[2 * v + 1]];
    for (let t = 0; t < p.triangles.length / 3; ++t) {
      const path = document.createElementNS(SVG_NS, 'path');
      const [a, b, c] = [0, 1, 2].map((k) => pt(p.triangles[3 * t + k]));
      path.setAttribute('d', `M${a[0]} ${a[1]}L${b[0]} ${b[1]}L${c[0]} ${c[1]}Z`);
      path.setAttribute('stroke-width', stroke / 2);
      g.appendChild(path);
      patternTriangles.push({ element: path, face: p.faces[t] });
    }
    if (p.initial && p.initial.length >= 6) {
      // The outline before the optimization, dashed, above the fill and below the new one.
      const before = document.createElementNS(SVG_NS, 'polygon');
      const points = [];
      for (let i = 0; i < p.initial.length; i += 2) points.push(`${p.initial[i] + dx},${-p.initial[i + 1]}`);
      before.setAttribute('points', points.join(' '));
      before.setAttribute('class', 'initial-outline');
      before.setAttribute('fill', 'none');
      before.setAttribute('stroke', '#c2410c');
      before.setAttribute('stroke-width', stroke * 1.2);
      before.setAttribute('stroke-dasharray', `${stroke * 6} ${stroke * 4}`);
      g.appendChild(before);
    }
    // Seam sides (each seam its own colour, named at its middle) and pinned edges (red).
    for (const e of p.edges ?? []) {
      if (e.vertices.length < 2) continue;
      const line = document.createElementNS(SVG_NS, 'polyline');
      line.setAttribute('points', e.vertices.map((v) => pt(v).join(',')).join(' '));
      line.setAttribute('fill', 'none');
      line.setAttribute('class', e.kind === 'pinned' ? 'pinned-edge' : 'seam-edge');
      line.setAttribute('stroke', e.kind === 'pinned' ? '#d42a2a' : seamColor(e.name));
      line.setAttribute('stroke-width', stroke * 4);
      line.setAttribute('stroke-linecap', 'round');
      const tip = document.createElementNS(SVG_NS, 'title');
      tip.textContent = `${e.kind === 'pinned' ? 'pinned' : 'seam'}: ${e.name}`;
      line.appendChild(tip);
      g.appendChild(line);
      // The name inside the piece: from the edge's middle towards the piece's centre.
      const [ex, ey] = pt(e.vertices[Math.floor(e.vertices.length / 2)]);
      const [ox, oy] = [(minX + maxX) / 2 + dx - ex, -(minY + maxY) / 2 - ey];
      const reach = Math.min(Math.hypot(ox, oy), labelSpace * 0.12);
      const scale = reach / (Math.hypot(ox, oy) || 1);
      const label = document.createElementNS(SVG_NS, 'text');
      label.setAttribute('x', ex + ox * scale);
      label.setAttribute('y', ey + oy * scale);
      label.setAttribute('class', 'edge-label');
      label.setAttribute('font-size', labelSpace * 0.18);
      label.setAttribute('text-anchor', Math.abs(ox) > Math.abs(oy) ? (ox > 0 ? 'start' : 'end') : 'middle');
      label.setAttribute('dominant-baseline', 'middle');
      label.setAttribute('paint-order', 'stroke');
      label.setAttribute('stroke', '#ffffff');
      label.setAttribute('stroke-width', stroke * 3);
      label.textContent = e.name;
      g.appendChild(label);
    }
    // The outer outline and the openings' rims.
    for (const loop of [p.boundary, ...(p.holes ?? [])]) {
      if (loop.length < 2) continue;
      const outline = document.createElementNS(SVG_NS, 'polygon');
      outline.setAttribute('points', loop.map((v) => pt(v).join(',')).join(' '));
      outline.setAttribute('fill', 'none');
      outline.setAttribute('stroke', '#1d232b');
      outline.setAttribute('stroke-width', stroke * 1.5);
      if (loop !== p.boundary) outline.setAttribute('class', 'opening-outline');
      g.appendChild(outline);
    }
    // Grain line through the piece's centre.
    const cx = (minX + maxX) / 2 + dx;
    const cy = -(minY + top) / 2;
    const len = Math.min(maxX - minX, top - minY) * 0.3;
    const [gx, gy] = [p.grain[0] * len, -p.grain[1] * len];
    const grain = document.createElementNS(SVG_NS, 'path');
    const head = len * 0.15;
    const ux = gx / (len || 1), uy = gy / (len || 1);
    grain.setAttribute('d', `M${cx - gx / 2} ${cy - gy / 2}L${cx + gx / 2} ${cy + gy / 2}` +
      `M${cx + gx / 2 - head * (ux - uy * 0.5)} ${cy + gy / 2 - head * (uy + ux * 0.5)}L${cx + gx / 2} ${cy + gy / 2}` +
      `L${cx + gx / 2 - head * (ux + uy * 0.5)} ${cy + gy / 2 - head * (uy - ux * 0.5)}`);
    grain.setAttribute('stroke', '#1d232b');
    grain.setAttribute('stroke-width', stroke);
    grain.setAttribute('fill', 'none');
    const halo = grain.cloneNode();
    halo.setAttribute('stroke', '#ffffff');
    halo.setAttribute('stroke-width', stroke * 3);
    g.append(halo, grain);
    const label = document.createElementNS(SVG_NS, 'text');
    label.setAttribute('x', cx);
    label.setAttribute('y', -bottom + labelSpace * 0.4);
    label.setAttribute('text-anchor', 'middle');
    label.setAttribute('font-size', labelSpace * 0.32);
    label.textContent = p.name;
    g.appendChild(label);
    svg.appendChild(g);
  }
  if (pieces.some((p) => (p.edges ?? []).length > 0)) {
    document.getElementById('pattern-hint').textContent +=
      ' Coloured edges are seams (both sides of a seam in one colour, with its name), red edges are pinned to the body (cuffs, waistbands).';
  }
  if (pieces.some((p) => p.initial)) {
    document.getElementById('pattern-hint').textContent +=
      ' Dashed orange: the outline before the optimization; solid black: the optimized outline (same frame, so the overlay shows how each edge moved).';
  }
  const bar = document.createElementNS(SVG_NS, 'path');
  const barY = -bottom + labelSpace * 0.8;
  bar.setAttribute('d', `M0 ${barY}h0.1M0 ${barY - 0.005}v0.01M0.1 ${barY - 0.005}v0.01`);
  bar.setAttribute('stroke', '#1d232b');
  bar.setAttribute('stroke-width', stroke);
  svg.appendChild(bar);
  const barLabel = document.createElementNS(SVG_NS, 'text');
  barLabel.setAttribute('x', 0.105);
  barLabel.setAttribute('y', barY + labelSpace * 0.1);
  barLabel.setAttribute('font-size', labelSpace * 0.28);
  barLabel.textContent = '10 cm';
  svg.appendChild(barLabel);
  host.appendChild(svg);
}

// ---- colouring -------------------------------------------------------------------

function applyColoring(index) {
  const colors = garmentGeometry.getAttribute('color');
  const coloring = colorings[index];
  const color = new THREE.Color();
  const nFaces = garment.indices.length / 3;
  for (let f = 0; f < nFaces; ++f) {
    const rgb = coloring ? colorOf(coloring, coloring.values[f]) : [200, 200, 200];
    color.setRGB(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255, THREE.SRGBColorSpace);
    for (let k = 0; k < 3; ++k) colors.setXYZ(3 * f + k, color.r, color.g, color.b);
  }
  colors.needsUpdate = true;
  for (const { element, face } of patternTriangles) {
    const css = cssColor(coloring ? colorOf(coloring, coloring.values[face]) : [200, 200, 200]);
    element.setAttribute('fill', css);
    element.setAttribute('stroke', css);
  }
  if (coloring) drawLegend(coloring);
  report.coloring = index;
  render();
}
report.setColoring = applyColoring;

// ---- tables and plot -------------------------------------------------------------

function cell(row, text, cls) {
  const td = document.createElement('td');
  td.textContent = text;
  if (cls) td.className = cls;
  row.appendChild(td);
}

function drawStats() {
  const s = data.stats;
  const table = document.createElement('table');
  table.innerHTML = '<thead><tr><th class="name" rowspan="2">piece</th><th rowspan="2">area (cm²)</th>' +
    '<th colspan="3">pressure (mmHg)</th><th colspan="3">pressure (Pa)</th><th colspan="2">max stretch (–)</th>' +
    '<th colspan="3">share of area</th><th colspan="2">lift-off (p &lt; 0)</th></tr>' +
    '<tr><th>min</th><th>median</th><th>max</th><th>min</th><th>median</th><th>max</th><th>median</th><th>max</th>' +
    '<th>slack</th><th>wrinkled</th><th>taut</th><th>area (cm²)</th><th>share</th></tr></thead>';
  const tbody = document.createElement('tbody');
  const rows = [...s.pieces, { ...s.garment, total: true }];
  for (const r of rows) {
    const tr = document.createElement('tr');
    if (r.total) tr.className = 'total';
    cell(tr, r.total ? 'whole garment' : r.name, 'name');
    cell(tr, fmt(r.area_m2 * 1e4));
    for (const k of ['min', 'median', 'max']) cell(tr, fmt(r.pressure_mmhg[k]));
    for (const k of ['min', 'median', 'max']) cell(tr, fmt(r.pressure_pa[k]));
    cell(tr, fmt(r.stretch_max.median));
    cell(tr, fmt(r.stretch_max.max));
    for (const k of ['slack', 'wrinkled', 'taut']) cell(tr, percent(r.regime_share[k]));
    const lift = r.liftoff_area_m2;
    cell(tr, lift === null ? '–' : fmt(lift * 1e4), lift > 0 ? 'liftoff' : '');
    cell(tr, percent(r.liftoff_share), lift > 0 ? 'liftoff' : '');
    tbody.appendChild(tr);
  }
  table.appendChild(tbody);
  document.getElementById('stats').appendChild(table);
}

/// RAL-GZ 387 compression classes (mmHg), as in src/tightfit/report/pressure_statistics.hpp.
const PRESSURE_CLASSES = [
  { label: 'I', lo: 18, hi: 21 }, { label: 'II', lo: 23, hi: 32 },
  { label: 'III', lo: 34, hi: 46 }, { label: 'IV', lo: 49, hi: Infinity },
];

/// A table in the element `hostId`: `headerHtml` (a <thead>), then one row per item
/// filled by `fillRow(tr, item)`; `emptyText` instead when there are no items.
function drawTable(hostId, items, emptyText, headerHtml, fillRow) {
  const host = document.getElementById(hostId);
  if (!Array.isArray(items) || items.length === 0) {
    host.textContent = emptyText;
    return;
  }
  const table = document.createElement('table');
  table.innerHTML = headerHtml;
  const tbody = document.createElement('tbody');
  for (const item of items) {
    const tr = document.createElement('tr');
    fillRow(tr, item);
    tbody.appendChild(tr);
  }
  table.appendChild(tbody);
  host.appendChild(table);
}

function drawRegions() {
  drawTable('regions', data.pressure_regions, 'No pressure regions in this scene ("pressure": {"regions": [...]}).',
    '<thead><tr><th class="name" rowspan="2">region</th><th colspan="2">target (mmHg)</th>' +
    '<th rowspan="2">area (cm²)</th><th colspan="5">pressure (mmHg)</th><th rowspan="2">in target</th>' +
    '<th rowspan="2">lift-off</th><th rowspan="2">RAL-GZ 387 class (median)</th><th rowspan="2">burn scar 15–25</th>' +
    '<th rowspan="2">face mask 20–32</th></tr>' +
    '<tr><th>min</th><th>max</th><th>min</th><th>median</th><th>mean</th><th>std</th><th>max</th></tr></thead>',
    (tr, r) => {
      cell(tr, r.name, 'name');
      cell(tr, fmt(r.target_mmhg.min));
      cell(tr, fmt(r.target_mmhg.max));
      cell(tr, fmt(r.area_m2 * 1e4));
      for (const k of ['min', 'median', 'mean', 'std', 'max']) cell(tr, r.pressure_mmhg ? fmt(r.pressure_mmhg[k]) : '–');
      cell(tr, percent(r.share_in_target));
      cell(tr, percent(r.lift_off_share), r.lift_off_share > 0 ? 'liftoff' : '');
      cell(tr, r.ral_gz_387_class ?? '–');
      cell(tr, r.burn_scar_range === null ? '–' : (r.burn_scar_range ? 'yes' : 'no'));
      cell(tr, r.face_mask_range === null ? '–' : (r.face_mask_range ? 'yes' : 'no'));
    });
}

/// The fabric: for a measured knit its course and wale curves (loading solid, worn
/// dashed) with each region's working point; for every fabric a table of the working
/// strains (and tensions, measured knits).
function drawFabric() {
  const f = data.fabric;
  if (!f || typeof f !== 'object') return;
  document.getElementById('fabric-section').hidden = false;
  const host = document.getElementById('fabric');
  const escape = (t) => String(t).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c]));
  const title = document.createElement('p');
  title.textContent = f.model === 'measured'
    ? `${f.name} (measured knit, ${fmt(f.thickness_m * 1e3)} mm; coupling ${fmt(f.coupling)}, shear ${fmt(f.shear_n_per_m)} N/m` +
      (f.relaxation > 0 ? `, relaxation ${percent(f.relaxation)}` : '') + ')'
    : `${f.name ? f.name + ': ' : ''}isotropic knit, E ${fmt(f.youngs_modulus_pa_simulated / 1e6)} MPa worn` +
      (f.relaxation > 0 ? ` (${fmt(f.youngs_modulus_pa_new / 1e6)} MPa new, relaxation ${percent(f.relaxation)})` : '') +
      `, ν ${fmt(f.poisson_ratio)}, ${fmt(f.thickness_m * 1e3)} mm`;
  host.appendChild(title);
  const points = Array.isArray(f.working_points) ? f.working_points : [];
  const colors = { course: '#2a6fdb', wale: '#e08a1e' };
  if (f.model === 'measured' && f.curves) {
    const W = 640, H = 300, L = 56, R = 96, T = 14, B = 40;
    const dirs = ['course', 'wale'];
    const xMax = Math.max(...dirs.map((d) => f.curves[d].sampled.strain.at(-1))) || 1;
    const yMax = Math.max(...dirs.flatMap((d) => f.curves[d].sampled.loading.concat(f.curves[d].sampled.worn))) || 1;
    const sx = (x) => L + (x / xMax) * (W - L - R);
    const sy = (y) => H - B - (y / yMax) * (H - T - B);
    let body = `<rect x="${L}" y="${T}" width="${W - L - R}" height="${H - T - B}" fill="#f7f8fa" stroke="#d5dae0"/>`;
    for (const d of dirs) {
      const c = f.curves[d].sampled;
      const line = (ys) => c.strain.map((x, k) => `${sx(x).toFixed(1)},${sy(ys[k]).toFixed(1)}`).join(' ');
      body += `<polyline class="curve ${d}" points="${line(c.loading)}" fill="none" stroke="${colors[d]}" stroke-width="2"><title>${d} loading</title></polyline>`;
      if (c.worn.some((v, k) => Math.abs(v - c.loading[k]) > 1e-9 * yMax))
        body += `<polyline class="curve ${d} worn" points="${line(c.worn)}" fill="none" stroke="${colors[d]}" stroke-width="2" stroke-dasharray="6 4"><title>${d} unloading (worn)</title></polyline>`;
      body += `<text x="${W - R + 6}" y="${sy(c.loading.at(-1)) + 4}" font-size="11" fill="${colors[d]}">${d}</text>`;
      for (const p of points) {
        const w = p[d];
        if (!w || typeof w.strain !== 'number' || typeof w.tension_n_per_m !== 'number') continue;
        body += `<circle class="working-point" cx="${sx(Math.max(w.strain, 0))}" cy="${sy(w.tension_n_per_m)}" r="4" fill="#fff" stroke="${colors[d]}" stroke-width="2">` +
          `<title>${escape(p.region)}, ${d}: strain ${percent(w.strain)}, ${fmt(w.tension_n_per_m)} N/m</title></circle>`;
      }
    }
    for (const v of [0, xMax / 2, xMax])
      body += `<text x="${sx(v)}" y="${H - B + 14}" text-anchor="middle" font-size="11">${percent(v)}</text>`;
    body += `<text x="${(L + W - R) / 2}" y="${H - 6}" text-anchor="middle" font-size="11">strain</text>` +
      `<text x="${L - 6}" y="${T + 10}" text-anchor="end" font-size="11">${fmt(yMax)}</text>` +
      `<text x="${L - 6}" y="${H - B}" text-anchor="end" font-size="11">0</text>` +
      `<text x="${L - 6}" y="${(T + H - B) / 2}" text-anchor="end" font-size="11">N/m</text>`;
    const plot = document.createElement('div');
    plot.innerHTML = `<svg class="fabric-curves" viewBox="0 0 ${W} ${H}" width="${W}" height="${H}" xmlns="${SVG_NS}">${body}</svg>`;
    host.appendChild(plot);
  }
  const table = document.createElement('div');
  host.appendChild(table);
  table.id = 'fabric-working-points';
  const measured = f.model === 'measured';
  drawTable('fabric-working-points', points, 'No working points.',
    '<thead><tr><th class="name">region</th><th>area (cm²)</th><th>course strain</th>' +
    (measured ? '<th>course tension (N/m)</th>' : '') + '<th>wale strain</th>' +
    (measured ? '<th>wale tension (N/m)</th>' : '') + '</tr></thead>',
    (tr, p) => {
      cell(tr, p.region, 'name');
      cell(tr, fmt(p.area_m2 * 1e4));
      cell(tr, percent(p.course.strain));
      if (measured) cell(tr, fmt(p.course.tension_n_per_m));
      cell(tr, percent(p.wale.strain));
      if (measured) cell(tr, fmt(p.wale.tension_n_per_m));
    });
}

/// The ease table: per measurement level the body and pattern circumferences (cm), the
/// ease (%), the fitted garment's circumference and stretch, and each piece's width.
function drawMeasurements() {
  const cm = (m) => (m === null || m === undefined ? '–' : (100 * m).toFixed(1));
  drawTable('measurements', data.measurements,
    'No measurement levels: the garment reaches none (or the scene turns them off with "measurements": []).',
    '<thead><tr><th class="name">level</th><th>placed at</th><th>body (cm)</th><th>pattern (cm)</th>' +
    '<th>ease (%)</th><th>fitted (cm)</th><th>fitted stretch</th><th class="name">pattern width per piece (cm)</th></tr></thead>',
    (tr, m) => {
      cell(tr, m.name, 'name');
      cell(tr, m.anchor);
      if (m.status !== 'measured') {
        const td = document.createElement('td');
        td.colSpan = 6;
        td.className = 'name skipped';
        td.textContent = 'skipped: ' + m.reason;
        tr.appendChild(td);
        return;
      }
      cell(tr, cm(m.body_circumference_m));
      cell(tr, cm(m.pattern_circumference_m));
      cell(tr, m.ease_percent.toFixed(1), 'ease');
      cell(tr, cm(m.garment_circumference_m));
      cell(tr, m.fitted_stretch.toFixed(3));
      cell(tr, m.pieces.map((p) => `${p.piece} ${cm(p.pattern_width_m)}`).join(', '), 'name');
    });
}

/// The silhouettes of the shape target, the initial and the optimized garment in a
/// front and a side view: each layer's triangles filled opaque on its own canvas, then
/// laid over the others translucent (so overlapping triangles do not darken).
function drawSilhouettes() {
  const s = data.silhouettes;
  if (!s || !s.target) return;
  document.getElementById('shape-section').hidden = false;
  const host = document.getElementById('silhouettes');
  const layers = [{ name: 'target', color: '#2e9e4f', mesh: s.target }];
  if (s.initial) layers.push({ name: 'initial', color: '#e08a1e', mesh: s.initial });
  layers.push({ name: 'optimized', color: '#2f5fd0', mesh: data.garment });
  for (const layer of layers) {
    layer.positions = typedArray(layer.mesh.positions);
    layer.indices = typedArray(layer.mesh.indices);
  }
  const size = 360, margin = 12;
  for (const view of [{ name: 'front', axis: 0, sign: 1 }, { name: 'side', axis: 2, sign: 1 }]) {
    let lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
    for (const layer of layers)
      for (let i = 0; i < layer.positions.length; i += 3) {
        const h = view.sign * layer.positions[i + view.axis], v = layer.positions[i + 1];
        lo = [Math.min(lo[0], h), Math.min(lo[1], v)];
        hi = [Math.max(hi[0], h), Math.max(hi[1], v)];
      }
    const scale = (size - 2 * margin) / Math.max(hi[0] - lo[0], hi[1] - lo[1], 1e-9);
    const toPixel = (h, v) => [margin + (h - lo[0]) * scale, size - margin - (v - lo[1]) * scale];
    const figure = document.createElement('figure');
    figure.className = 'silhouette';
    const canvas = document.createElement('canvas');
    canvas.width = size;
    canvas.height = size;
    canvas.dataset.view = view.name;
    const ctx = canvas.getContext('2d');
    ctx.fillStyle = '#ffffff';
    ctx.fillRect(0, 0, size, size);
    for (const layer of layers) {
      const off = document.createElement('canvas');
      off.width = size;
      off.height = size;
      const o = off.getContext('2d');
      o.fillStyle = layer.color;
      o.strokeStyle = layer.color;
      o.lineWidth = 0.6;  // closes the hairline gaps between neighbouring triangles
      const p = layer.positions, t = layer.indices;
      for (let f = 0; f < t.length; f += 3) {
        o.beginPath();
        for (let k = 0; k < 3; ++k) {
          const q = 3 * t[f + k];
          const [x, y] = toPixel(view.sign * p[q + view.axis], p[q + 1]);
          if (k === 0) o.moveTo(x, y); else o.lineTo(x, y);
        }
        o.closePath();
        o.fill();
        o.stroke();
      }
      ctx.globalAlpha = 0.45;
      ctx.drawImage(off, 0, 0);
    }
    ctx.globalAlpha = 1;
    ctx.fillStyle = '#000000';
    ctx.fillRect(margin, size - margin / 2 - 2, 0.1 * scale, 2);  // 10 cm bar
    const caption = document.createElement('figcaption');
    caption.textContent = `${view.name} view: ` + layers.map((l) => l.name).join(', ');
    figure.append(canvas, caption);
    host.appendChild(figure);
  }
}

/// One row per seam; the fit columns read '–' for a pattern without a fit (fmt).
function drawSeams() {
  drawTable('seams', data.seams, 'No seams in this garment.',
    '<thead><tr><th class="name" rowspan="2">seam</th><th rowspan="2">pieces</th>' +
    '<th colspan="3">pattern length (mm)</th><th rowspan="2">on the body (mm)</th><th colspan="2">sewing stretch</th>' +
    '<th colspan="2">traction (N/m)</th><th rowspan="2">angle to up (°)</th></tr>' +
    '<tr><th>side a</th><th>side b</th><th>mismatch</th><th>side a</th><th>side b</th><th>mean</th><th>max</th></tr></thead>',
    (tr, s) => {
      cell(tr, s.name, 'name');
      cell(tr, `${s.piece_a} – ${s.piece_b}`);
      cell(tr, fmt(s.length_a_mm));
      cell(tr, fmt(s.length_b_mm));
      cell(tr, fmt(s.mismatch_mm), s.mismatch_mm > 1 ? 'liftoff' : '');
      for (const key of ['sewn_length_mm', 'stretch_a', 'stretch_b', 'traction_mean_n_per_m',
        'traction_max_n_per_m', 'angle_to_up_deg']) cell(tr, fmt(s[key]));
    });
}

function drawHistogram() {
  const host = document.getElementById('histogram');
  const h = data.pressure_histogram;
  if (!h || !Array.isArray(h.edges_mmhg) || h.area_m2.length === 0) {
    host.textContent = 'No pressure in this fit.';
    return;
  }
  if (h.share_above_warning > 0) {
    const warning = document.createElement('p');
    warning.className = 'pressure-warning';
    warning.textContent = `Warning: ${percent(h.share_above_warning)} of the garment presses harder than ` +
      `${fmt(h.warning_mmhg)} mmHg (up to ${fmt(h.max_mmhg)} mmHg), above the compression classes for ` +
      'garments worn all day (RAL-GZ 387 class III ends at 46 mmHg): a risk for skin and circulation. ' +
      'Check the fabric, the pattern and the pressure targets.';
    host.appendChild(warning);
  }
  const edges = h.edges_mmhg, areas = h.area_m2;
  const total = areas.reduce((a, b) => a + b, 0) || 1;
  const shares = areas.map((a) => a / total);
  const W = 640, H = 220, L = 52, R = 12, T = 18, B = 40;
  const x0 = Math.min(edges[0], 0), x1 = Math.max(edges[edges.length - 1], 0);
  const yMax = Math.max(...shares) || 1;
  const sx = (x) => L + ((x - x0) / (x1 - x0 || 1)) * (W - L - R);
  const sy = (y) => H - B - (y / yMax) * (H - T - B);
  let body = `<rect x="${L}" y="${T}" width="${W - L - R}" height="${H - T - B}" fill="#f7f8fa" stroke="#d5dae0"/>`;
  for (const c of PRESSURE_CLASSES) {
    const lo = Math.max(c.lo, x0), hi = Math.min(c.hi, x1);
    if (hi <= lo) continue;
    body += `<rect class="class-band" x="${sx(lo)}" y="${T}" width="${sx(hi) - sx(lo)}" height="${H - T - B}" fill="#2a6fdb" fill-opacity="0.08"/>` +
      `<text x="${(sx(lo) + sx(hi)) / 2}" y="${T - 4}" text-anchor="middle" font-size="10" fill="#5b6570">${c.label}</text>`;
  }
  for (let k = 0; k < shares.length; ++k) {
    const liftoff = edges[k + 1] <= 0;
    body += `<rect class="bar${liftoff ? ' liftoff' : ''}" x="${sx(edges[k]) + 0.5}" y="${sy(shares[k])}" width="${Math.max(sx(edges[k + 1]) - sx(edges[k]) - 1, 1)}" height="${H - B - sy(shares[k])}" fill="${liftoff ? cssColor([217, 26, 217]) : '#5b6570'}"><title>${fmt(edges[k])}–${fmt(edges[k + 1])} mmHg: ${percent(shares[k])}</title></rect>`;
  }
  const regions = Array.isArray(data.pressure_regions) ? data.pressure_regions : [];
  regions.forEach((r, i) => {
    const lo = Math.max(r.target_mmhg.min, x0), hi = Math.min(r.target_mmhg.max, x1);
    if (hi < lo) return;
    const y = T + 6 + 8 * i;
    body += `<line class="target" x1="${sx(lo)}" x2="${Math.max(sx(hi), sx(lo) + 2)}" y1="${y}" y2="${y}" stroke="#1d7a3a" stroke-width="4"><title>${r.name} target</title></line>` +
      `<text x="${Math.max(sx(hi), sx(lo) + 2) + 4}" y="${y + 3}" font-size="9" fill="#1d7a3a">${r.name}</text>`;
  });
  const ticks = [x0, 0, x1].filter((v, i, a) => a.indexOf(v) === i);
  for (const v of ticks) body += `<text x="${sx(v)}" y="${H - B + 14}" text-anchor="middle" font-size="11">${fmt(v)}</text>`;
  body += `<text x="${L - 6}" y="${T + 10}" text-anchor="end" font-size="11">${percent(yMax)}</text>` +
    `<text x="${L - 6}" y="${H - B}" text-anchor="end" font-size="11">0 %</text>` +
    `<text x="${(L + W - R) / 2}" y="${H - 4}" text-anchor="middle" font-size="12">pressure (mmHg)</text>` +
    `<text x="12" y="${(T + H - B) / 2}" font-size="12" transform="rotate(-90 12 ${(T + H - B) / 2})" text-anchor="middle">share of area</text>`;
  const svg = document.createElementNS(SVG_NS, 'svg');
  svg.setAttribute('viewBox', `0 0 ${W} ${H}`);
  svg.setAttribute('width', W);
  svg.setAttribute('height', H);
  svg.innerHTML = body;
  host.appendChild(svg);
}

/// Ticks of a log axis from lo to hi (both powers of ten): every decade (every second
/// or more when there are many, at most about eight), with 2 and 5 over few decades.
function logTicks(lo, hi) {
  const ticks = [];
  const k0 = Math.round(Math.log10(lo)), k1 = Math.round(Math.log10(hi));
  const every = Math.max(1, Math.ceil((k1 - k0) / 8));
  const mantissas = k1 - k0 <= 2 ? [1, 2, 5] : [1];
  for (let k = k0; k <= k1; k += every)
    for (const m of mantissas) {
      const v = m * 10 ** k;
      if (v <= hi * (1 + 1e-9)) ticks.push(v);
    }
  return ticks;
}

/// A log-axis tick label: "1e-4", "2e-4", or plain numbers from 0.01 to 1000.
function logTickLabel(v) {
  if (v >= 0.01 && v <= 1000) return Number(v.toPrecision(1)).toString();
  const [m, e] = v.toExponential(0).split('e');
  return `${m}e${Number(e)}`;
}

/// Integer ticks on [x0, x1], about six of them.
function iterationTicks(x0, x1) {
  if (x1 <= x0) return [x0];
  const raw = (x1 - x0) / 6;
  const p = 10 ** Math.floor(Math.log10(Math.max(raw, 1)));
  const step = Math.max(1, [1, 2, 5, 10].map((m) => m * p).find((s) => s >= raw) ?? p * 10);
  const ticks = [];
  for (let v = Math.ceil(x0 / step) * step; v <= x1; v += step) ticks.push(v);
  return ticks;
}

const TERM_COLORS = ['#d97706', '#059669', '#7c3aed', '#db2777', '#0891b2', '#65a30d', '#9f1239', '#475569'];

function drawHistory() {
  const host = document.getElementById('history');
  const entries = Array.isArray(data.history) ? data.history : [];
  const iterationOf = (e, i) => (typeof e.iteration === 'number' ? e.iteration : i);
  const series = [{ name: 'objective (total)', color: '#2a6fdb', width: 2.5,
    points: entries.map((e, i) => [iterationOf(e, i), e.objective]) }];
  const names = [];
  for (const e of entries)
    if (e.terms && typeof e.terms === 'object')
      for (const n of Object.keys(e.terms)) if (!names.includes(n)) names.push(n);
  names.forEach((n, k) => series.push({ name: n, color: TERM_COLORS[k % TERM_COLORS.length], width: 1.5,
    points: entries.map((e, i) => [iterationOf(e, i), e.terms ? e.terms[n] : undefined]) }));
  for (const s of series) s.points = s.points.filter(([, y]) => typeof y === 'number' && Number.isFinite(y));
  if (series[0].points.length === 0) {
    host.textContent = 'No optimization history in this fit.';
    return;
  }
  // A log axis over the positive values; zeros (a term inside its admissible range)
  // sit on the bottom edge.
  const positive = series.flatMap((s) => s.points.map((p) => p[1])).filter((y) => y > 0);
  const log = positive.length > 0;
  let lo = log ? Math.min(...positive) : Math.min(...series[0].points.map((p) => p[1]));
  let hi = log ? Math.max(...positive) : Math.max(...series[0].points.map((p) => p[1]));
  if (log) { lo = 10 ** Math.floor(Math.log10(lo)); hi = 10 ** Math.ceil(Math.log10(hi)); }
  if (!(hi > lo)) { hi = lo + 1; }
  const fy = (y) => (log ? Math.log10(Math.max(y, lo)) : y);
  const xs = series[0].points.map((p) => p[0]);
  const [x0, x1] = [Math.min(...xs), Math.max(...xs)];
  const W = 900, H = 280, L = 60, R = 330, T = 10, B = 36;
  const sx = (x) => L + (x1 === x0 ? 0.5 : (x - x0) / (x1 - x0)) * (W - L - R);
  const sy = (y) => T + (1 - (fy(y) - fy(lo)) / (fy(hi) - fy(lo))) * (H - T - B);
  let body = `<rect x="${L}" y="${T}" width="${W - L - R}" height="${H - T - B}" fill="#f7f8fa" stroke="#d5dae0"/>`;
  const yTicks = log ? logTicks(lo, hi) : [lo, (lo + hi) / 2, hi];
  for (const v of yTicks) {
    body += `<line class="ytick" x1="${L}" x2="${W - R}" y1="${sy(v)}" y2="${sy(v)}" stroke="#e3e7ec"/>` +
      `<text class="ytick-label" x="${L - 6}" y="${sy(v) + 4}" text-anchor="end" font-size="11">${log ? logTickLabel(v) : fmt(v)}</text>`;
  }
  for (const v of iterationTicks(x0, x1)) {
    body += `<text class="xtick-label" x="${sx(v)}" y="${H - B + 14}" text-anchor="middle" font-size="11">${v}</text>`;
  }
  series.forEach((s, k) => {
    if (s.points.length === 0) return;
    body += `<polyline class="history-curve" data-term="${s.name}" fill="none" stroke="${s.color}" stroke-width="${s.width}" points="${s.points.map(([x, y]) => `${sx(x)},${sy(y)}`).join(' ')}"><title>${s.name}</title></polyline>`;
    const last = s.points[s.points.length - 1][1];
    body += `<rect x="${W - R + 10}" y="${T + 4 + 16 * k}" width="14" height="4" fill="${s.color}"/>` +
      `<text x="${W - R + 30}" y="${T + 10 + 16 * k}" font-size="11">${s.name}: ${fmt(s.points[0][1])} → ${fmt(last)}</text>`;
  });
  body += `<text x="${(L + W - R) / 2}" y="${H - 4}" text-anchor="middle" font-size="12">L-BFGS iteration</text>` +
    `<text x="12" y="${(T + H - B) / 2}" font-size="12" transform="rotate(-90 12 ${(T + H - B) / 2})" text-anchor="middle">weighted term w·T${log ? ' (log scale)' : ''}</text>`;
  const svg = document.createElementNS(SVG_NS, 'svg');
  svg.setAttribute('viewBox', `0 0 ${W} ${H}`);
  svg.setAttribute('width', W);
  svg.setAttribute('height', H);
  svg.innerHTML = body;
  host.appendChild(svg);
}

/// The run at a glance (data.summary) under the title.
function drawSummary() {
  const host = document.getElementById('summary');
  const s = data.summary ?? {};
  const items = [];
  const add = (label, value, cls) => { if (value !== undefined && value !== null) items.push([label, value, cls]); };
  add('command', s.command);
  add('scene', s.scene);
  add('status', s.status, s.status === 'converged' ? 'ok' : 'warn');
  add('stop reason', s.stop_reason);
  add('iterations', s.iterations);
  add('Newton iterations', s.newton_iterations);
  if (s.objective_initial !== undefined && s.objective_final !== undefined)
    add('objective', `${fmt(s.objective_initial, 4)} → ${fmt(s.objective_final, 4)} (ratio ${fmt(s.objective_final / s.objective_initial, 3)})`);
  if (typeof s.seconds === 'number') add('time', `${fmt(s.seconds, 3)} s`);
  if (typeof s.force_residual_n === 'number') add('force residual', `${fmt(s.force_residual_n, 3)} N`);
  add('version', s.version ? `tightfit ${s.version}` : undefined);
  add('date', s.date);
  if (items.length === 0) { host.hidden = true; return; }
  for (const [label, value, cls] of items) {
    const span = document.createElement('span');
    span.className = 'item' + (cls ? ' ' + cls : '');
    const b = document.createElement('b');
    b.textContent = label + ': ';
    span.append(b, String(value));
    host.appendChild(span);
  }
}

function drawParameters() {
  const host = document.getElementById('parameters');
  const rows = [];
  const walk = (value, path) => {
    if (value !== null && typeof value === 'object' && !Array.isArray(value)) {
      for (const [k, v] of Object.entries(value)) walk(v, path ? `${path}.${k}` : k);
    } else {
      rows.push([path, JSON.stringify(value)]);
    }
  };
  walk(data.parameters, '');
  if (rows.length === 0) {
    host.textContent = 'No scene parameters given.';
    return;
  }
  const table = document.createElement('table');
  for (const [k, v] of rows) {
    const tr = document.createElement('tr');
    cell(tr, k);
    cell(tr, v);
    table.appendChild(tr);
  }
  host.appendChild(table);
}

// ---- start -----------------------------------------------------------------------

const select = document.getElementById('coloring');
colorings.forEach((c, i) => {
  const option = document.createElement('option');
  option.value = String(i);
  option.textContent = c.unit ? `${c.label} (${c.unit})` : c.label;
  select.appendChild(option);
});
select.addEventListener('change', () => applyColoring(Number(select.value)));
document.getElementById('full-range').addEventListener('change', (e) => {
  fullRange = e.target.checked;
  for (const c of colorings) {
    if (c.categories || c.fixed) continue;
    [c.lo, c.hi] = fullRange ? [c.data_min, c.data_max] : c.robust;
  }
  applyColoring(report.coloring);
});
if (data.missing_colorings.length > 0) {
  const missing = document.getElementById('missing');
  missing.hidden = false;
  missing.textContent = 'Not available in this fit: ' + data.missing_colorings.join(', ');
}

// ---- poses -----------------------------------------------------------------------

function setPose(index) {
  const pose = index >= 0 ? poses[index] : null;
  setGarmentPositions(pose ? pose.garment : garment.positions, pose ? pose.normals : garment.normals);
  setEdgePositions(pose ? pose.garment : garment.positions, pose ? pose.normals : garment.normals);
  if (bodyMesh) {
    bodyMesh.geometry.setAttribute('position', new THREE.BufferAttribute(pose ? pose.body : body.positions, 3));
    bodyMesh.geometry.computeVertexNormals();
  }
  if (slidingColoring) slidingColoring.values = pose ? pose.sliding_excess : neutralSliding;
  const hint = document.getElementById('pose-hint');
  hint.hidden = false;
  hint.textContent = pose
    ? `Pose "${pose.name}": ${percent(pose.sliding_share)} of the free garment vertices would slide (their tangential force exceeds the friction limit, μ × the force pressing on the body); colour by "Sliding" to see where and by how much.`
    : `Neutral pose. The scene has ${poses.length} more; the "Sliding" colouring shows here the worst pose of each face.`;
  report.pose = index;
  applyColoring(report.coloring);
}
report.setPose = setPose;
if (poses.length > 0) {
  const poseSelect = document.getElementById('pose');
  document.getElementById('pose-label').hidden = false;
  ['neutral', ...poses.map((p) => p.name)].forEach((name, i) => {
    const option = document.createElement('option');
    option.value = String(i - 1);
    option.textContent = name;
    poseSelect.appendChild(option);
  });
  poseSelect.addEventListener('change', () => setPose(Number(poseSelect.value)));
}

drawSummary();
drawPattern();
drawStats();
drawSilhouettes();
drawSeams();
drawMeasurements();
drawFabric();
drawRegions();
drawHistogram();
drawHistory();
drawParameters();
resize();
applyColoring(colorings.length > 0 ? 0 : -1);
if (poses.length > 0) setPose(-1);
report.ready = true;

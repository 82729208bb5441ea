// haptic_sim view's page: the live scene's deformed surface, the tool, the force and the physics
// loop's frame figures, drawn from the states the scene sends over its WebSocket (protocol
// softsim-view 1, cpp/apps/haptic_sim.md); the pointer is the device. Everything is served by
// haptic_sim itself (three.js from the build tree): nothing is fetched from elsewhere.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const PROTOCOL = 1;
const $ = (id) => document.getElementById(id);
const canvas = $('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
const BACKGROUND_HEX = 0x20242b;  // also the page's background (index.html)
const BACKGROUND = new THREE.Color(BACKGROUND_HEX);
renderer.setClearColor(BACKGROUND);
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(40, 1, 1e-4, 100);
const controls = new OrbitControls(camera, canvas);
// Left button is the tool; right drag orbits, middle drag and the wheel zoom.
controls.mouseButtons = { LEFT: null, MIDDLE: THREE.MOUSE.DOLLY, RIGHT: THREE.MOUSE.ROTATE };
scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.4);
scene.add(sun);

// ---- the organ: drawn deformed; the pointer's ray meets its reference surface ----
const organMaterial = new THREE.MeshStandardMaterial({ vertexColors: true, side: THREE.DoubleSide, roughness: 0.7 });
let organ = null, reference = null, nodes = 0, refPositions = null, meshVersion = -1;
let box = new THREE.Box3(), diag = 1;
let regionBytes = null, maxU = 0;

function buildMesh(m) {
  nodes = m.nodes;
  refPositions = new Float32Array(m.reference);
  const index = new THREE.BufferAttribute(new Uint32Array(m.triangles), 1);
  const first = organ === null;
  if (organ) { scene.remove(organ); organ.geometry.dispose(); scene.remove(reference); reference.geometry.dispose(); }
  const g = new THREE.BufferGeometry();
  const positions = organ && organ.geometry.attributes.position.count === nodes
    ? organ.geometry.attributes.position.array.slice() : refPositions.slice();
  g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  g.setAttribute('color', new THREE.BufferAttribute(new Float32Array(3 * nodes).fill(0.7), 3));
  g.setIndex(index);
  g.computeVertexNormals();
  organ = new THREE.Mesh(g, organMaterial);
  scene.add(organ);
  const rg = new THREE.BufferGeometry();
  rg.setAttribute('position', new THREE.BufferAttribute(refPositions, 3));
  rg.setIndex(index);
  rg.computeBoundingSphere();
  reference = new THREE.Mesh(rg, new THREE.MeshBasicMaterial({ visible: false, side: THREE.DoubleSide }));
  scene.add(reference);
  meshVersion = m.version;
  if (first) {
    rg.computeBoundingBox();
    box = rg.boundingBox.clone();
    diag = box.getSize(new THREE.Vector3()).length();
    depth = 0.04 * diag;
    resetView();
  }
}

function resetView() {
  const c = box.getCenter(new THREE.Vector3());
  controls.target.copy(c);
  camera.position.copy(c).add(new THREE.Vector3(0.35, -1.1, 0.9).multiplyScalar(diag));
  camera.up.set(0, 0, 1);
  camera.near = diag * 1e-3;
  camera.far = diag * 20;
  camera.updateProjectionMatrix();
  controls.update();
  sun.position.copy(camera.position);
}

// Displacement magnitude on a blue-to-red scale (the largest seen so far is red); or region.
const REGION_COLOURS = [[0.55, 0.6, 0.68], [0.95, 0.45, 0.3], [0.98, 0.85, 0.3]];
function colour(positions) {
  const c = organ.geometry.attributes.color.array;
  const field = $('field').value;
  let m = 0;
  for (let i = 0; i < nodes; ++i) {
    const dx = positions[3 * i] - refPositions[3 * i], dy = positions[3 * i + 1] - refPositions[3 * i + 1],
      dz = positions[3 * i + 2] - refPositions[3 * i + 2];
    m = Math.max(m, Math.hypot(dx, dy, dz));
  }
  maxU = Math.max(maxU, m, 1e-4 * diag);
  for (let i = 0; i < nodes; ++i) {
    if (field === 'region' && regionBytes) {
      const rc = REGION_COLOURS[regionBytes[i]] || REGION_COLOURS[0];
      c[3 * i] = rc[0]; c[3 * i + 1] = rc[1]; c[3 * i + 2] = rc[2];
      continue;
    }
    const dx = positions[3 * i] - refPositions[3 * i], dy = positions[3 * i + 1] - refPositions[3 * i + 1],
      dz = positions[3 * i + 2] - refPositions[3 * i + 2];
    const s = Math.min(1, Math.hypot(dx, dy, dz) / maxU);
    c[3 * i] = 0.35 + 0.6 * s; c[3 * i + 1] = 0.55 - 0.25 * s; c[3 * i + 2] = 0.8 - 0.6 * s;
  }
  organ.geometry.attributes.color.needsUpdate = true;
}

// ---- the tool, its force, the trace ----
const tipMarker = new THREE.Mesh(new THREE.SphereGeometry(1, 16, 12), new THREE.MeshStandardMaterial({ color: 0x40c0ff }));
scene.add(tipMarker);
const bladeMarker = new THREE.Mesh(new THREE.CylinderGeometry(1, 1, 1, 8), new THREE.MeshStandardMaterial({ color: 0xe0e0e0 }));
bladeMarker.visible = false;
scene.add(bladeMarker);
const arrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, 0xffd040);
scene.add(arrow);
let maxForce = 0.5;
const trace = [];  // [t, |f|, fz]
const TRACE_SECONDS = 5;

function drawTrace() {
  const tc = $('trace'), ctx = tc.getContext('2d');
  ctx.clearRect(0, 0, tc.width, tc.height);
  ctx.fillStyle = '#ccc';
  ctx.fillText(`force on the tool (N), last ${TRACE_SECONDS} s: |f| yellow, f_z blue`, 8, 14);
  if (trace.length < 2) return;
  const tEnd = trace[trace.length - 1][0], scale = Math.max(maxForce, 1e-3);
  const x = (t) => 8 + (tc.width - 16) * (1 - (tEnd - t) / TRACE_SECONDS);
  const y = (f) => tc.height / 2 + 10 - (tc.height / 2 - 16) * f / scale;
  ctx.strokeStyle = '#555';
  ctx.beginPath(); ctx.moveTo(8, y(0)); ctx.lineTo(tc.width - 8, y(0)); ctx.stroke();
  for (const [k, colourStyle] of [[1, '#ffd040'], [2, '#40c0ff']]) {
    ctx.strokeStyle = colourStyle;
    ctx.beginPath();
    trace.forEach((p, i) => (i ? ctx.lineTo(x(p[0]), y(p[k])) : ctx.moveTo(x(p[0]), y(p[k]))));
    ctx.stroke();
  }
  ctx.fillText(`±${scale.toPrecision(3)} N`, tc.width - 70, 14);
}

// ---- the pointer as the device ----
const raycaster = new THREE.Raycaster();
const ndc = new THREE.Vector2();
let hit = null, normal = new THREE.Vector3(0, 0, 1), pressing = false, blade = false, depth = 0;
let pointerInside = false;

function pick(event) {
  const r = canvas.getBoundingClientRect();
  ndc.set(((event.clientX - r.left) / r.width) * 2 - 1, -((event.clientY - r.top) / r.height) * 2 + 1);
  if (!reference) return;
  raycaster.setFromCamera(ndc, camera);
  const h = raycaster.intersectObject(reference, false)[0];
  pointerInside = !!h;
  if (!h) return;
  hit = h.point.clone();
  normal = h.face.normal.clone();  // the reference surface's outward normal (mesh in world frame)
}
canvas.addEventListener('pointermove', pick);
canvas.addEventListener('pointerdown', (e) => {
  if (e.button !== 0) return;
  pick(e);
  pressing = true;
  canvas.setPointerCapture(e.pointerId);
});
canvas.addEventListener('pointerup', (e) => { if (e.button === 0) pressing = false; });
canvas.addEventListener('contextmenu', (e) => e.preventDefault());
window.addEventListener('wheel', (e) => {
  if (!e.shiftKey) return;  // plain wheel: zoom
  e.preventDefault();
  e.stopPropagation();
  const d = e.deltaY || e.deltaX;
  depth = Math.max(0, depth * (d > 0 ? 1.15 : 1 / 1.15));
}, { capture: true, passive: false });
window.addEventListener('keydown', (e) => {
  if (e.key === 'b' || e.key === 'B') setBlade(!blade);
  else if (e.key === 'r' || e.key === 'R') resetView();
  else if (e.key === ']') depth *= 1.15;
  else if (e.key === '[') depth /= 1.15;
});
function setBlade(on) { blade = on; $('tool').textContent = blade ? 'blade' : 'probe'; }
$('blade').addEventListener('click', () => setBlade(!blade));
$('reset').addEventListener('click', resetView);

// The tip this display frame: on the reference surface under the pointer, pressed `depth` into
// it while the left button is down, else lifted off it.
function currentTip() {
  if (!hit) return null;
  const lift = pressing && pointerInside ? -depth : 0.01 * diag;
  return hit.clone().addScaledVector(normal, lift);
}

// ---- the connection ----
let ws = null, pendingState = null, statesSeen = 0, lastState = null, hello = null;
const errors = [];
function setStatus(text, bad) { $('status').textContent = text; $('status').className = bad ? 'error' : ''; }
function connect() {
  ws = new WebSocket(`ws://${location.host}/`);
  ws.binaryType = 'arraybuffer';
  ws.onopen = () => { ws.send(JSON.stringify({ type: 'hello', protocol: PROTOCOL, states: 'pull' })); ws.send('{"type": "next"}'); setStatus('connected'); };
  ws.onclose = (e) => { setStatus(`disconnected (${e.code}${e.reason ? ': ' + e.reason : ''})`, true); ws = null; };
  ws.onmessage = (e) => {
    if (typeof e.data !== 'string') {
      if (pendingState) applyPositions(pendingState, e.data);
      pendingState = null;
      ws.send('{"type": "next"}');  // the newest state once this one is drawn
      return;
    }
    const m = JSON.parse(e.data);
    if (m.type === 'hello') {
      hello = m;
      if (m.protocol !== PROTOCOL) setStatus(`the scene speaks protocol ${m.protocol}, this page ${PROTOCOL}`, true);
      else setStatus(`connected · ${m.frame_rate} Hz · contact ${m.contact}${m.regions ? ' · regions' : ''}`);
    } else if (m.type === 'mesh') buildMesh(m);
    else if (m.type === 'state') pendingState = m;
    else if (m.type === 'error') { errors.push(m.message); setStatus(`scene: ${m.message}`, true); }
  };
}

let drawsCount = 0, statesCount = 0, rateClock = performance.now();
function applyPositions(s, buffer) {
  if (!organ || s.nodes !== nodes) return;
  const positions = new Float32Array(buffer, 0, 3 * nodes);
  regionBytes = buffer.byteLength > 12 * nodes ? new Uint8Array(buffer, 12 * nodes, nodes) : null;
  organ.geometry.attributes.position.array.set(positions);
  organ.geometry.attributes.position.needsUpdate = true;
  organ.geometry.computeVertexNormals();
  organ.geometry.computeBoundingSphere();
  colour(positions);
  lastState = s;
  ++statesSeen; ++statesCount;
  const f = new THREE.Vector3(...s.force), tip = new THREE.Vector3(...s.tip), fm = f.length();
  maxForce = Math.max(maxForce, fm);
  tipMarker.position.copy(tip);
  tipMarker.scale.setScalar(0.012 * diag);
  bladeMarker.visible = s.blade;
  arrow.position.copy(tip);
  arrow.visible = fm > 1e-9;
  if (fm > 1e-9) {
    arrow.setDirection(f.clone().normalize());
    const len = 0.25 * diag * fm / maxForce;
    arrow.setLength(len, 0.25 * len, 0.12 * len);
  }
  trace.push([s.t, fm, s.force[2]]);
  while (trace.length && trace[0][0] < s.t - TRACE_SECONDS) trace.shift();
  $('force').textContent = fm.toFixed(4);
  $('contact').textContent = s.contact ? 'yes' : 'no';
  $('frames').textContent = s.frame;
  $('compute').textContent = `${(1e3 * s.compute_mean).toFixed(3)} / ${(1e3 * s.compute_max).toFixed(3)}`;
  $('misses').textContent = s.deadline_misses;
  $('lag').textContent = (1e3 * s.start_lag_max).toFixed(2);
  $('cuts').textContent = `${s.cuts} / ${s.events}`;
  drawTrace();
}

// ---- the pointer's tip as samples at 60 Hz, whatever the drawing rate ----
const SAMPLE_RATE = 60;
function sendSample() {
  const tip = currentTip();
  if (!tip || !ws || ws.readyState !== WebSocket.OPEN) return;
  const sample = { type: 'sample', t: performance.now() / 1000, p: [tip.x, tip.y, tip.z], blade: blade && pressing };
  if (sample.blade) {
    // The edge along the surface normal, from above the surface to twice the press depth.
    const e = normal.clone().multiplyScalar(2.4 * Math.max(depth, 0.01 * diag));
    sample.edge = [e.x, e.y, e.z];
    bladeMarker.position.copy(tip);
    bladeMarker.scale.set(0.004 * diag, e.length(), 0.004 * diag);
    bladeMarker.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), normal);
  }
  ws.send(JSON.stringify(sample));
}
setInterval(sendSample, 1000 / SAMPLE_RATE);

// ---- the display loop ----
function animate() {
  requestAnimationFrame(animate);
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) || canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
  $('depth').textContent = (1e3 * depth).toFixed(2);
  sun.position.copy(camera.position);
  renderer.render(scene, camera);
  ++drawsCount;
  const t = performance.now();
  if (t - rateClock > 1000) {
    $('rates').textContent = `${(statesCount * 1000 / (t - rateClock)).toFixed(0)} · ${(drawsCount * 1000 / (t - rateClock)).toFixed(0)}`;
    statesCount = drawsCount = 0;
    rateClock = t;
  }
}

// ---- what a test (or a curious user) can ask the page ----
const gl = renderer.getContext();
function pixels() {
  renderer.render(scene, camera);
  const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight, p = new Uint8Array(4 * w * h);
  gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, p);
  return p;
}
const captures = {};
window.softsimView = {
  get ready() { return !!(organ && lastState); },
  get state() { return lastState; },
  get states() { return statesSeen; },
  get errors() { return errors.slice(); },
  get meshVersion() { return meshVersion; },
  get triangles() { return organ ? organ.geometry.index.count / 3 : 0; },
  get depth() { return depth; },
  set depth(d) { depth = d; },
  setBlade,
  // CSS pixel of a world point, and the reference box (for pointing at the organ).
  project(p) {
    const v = new THREE.Vector3(...p).project(camera), r = canvas.getBoundingClientRect();
    return { x: r.left + (v.x + 1) / 2 * r.width, y: r.top + (1 - v.y) / 2 * r.height };
  },
  box() { return { min: box.min.toArray(), max: box.max.toArray() }; },
  // Pixels that are not the background, and pixels that differ between two captures.
  organPixels() {
    const p = pixels(), bg = [BACKGROUND_HEX >> 16, (BACKGROUND_HEX >> 8) & 255, BACKGROUND_HEX & 255];  // as drawn (sRGB)
    let n = 0;
    for (let i = 0; i < p.length; i += 4)
      if (Math.abs(p[i] - bg[0]) + Math.abs(p[i + 1] - bg[1]) + Math.abs(p[i + 2] - bg[2]) > 30) ++n;
    return n / (p.length / 4);
  },
  capture(name) { captures[name] = pixels(); },
  changed(a, b) {
    const p = captures[a], q = captures[b];
    let n = 0;
    for (let i = 0; i < p.length; i += 4)
      if (Math.abs(p[i] - q[i]) + Math.abs(p[i + 1] - q[i + 1]) + Math.abs(p[i + 2] - q[i + 2]) > 30) ++n;
    return n / (p.length / 4);
  },
};

connect();
animate();

// The slide-viewer page: one WebSocket (/ws) brings the scene as JSON deltas, three.js draws it.
//
// Each message: {epoch, version, reset, time, views: {<robot>: view}, team: {<listener>: team},
// status?, classes?}. reset: true means a full snapshot (forget everything first). A view is one
// robot's bus in that robot's frame; each key is present only when it changed:
//   objects: {set: [[id, class, shape, ...params]], del: [ids]}; shape 0 cuboid: centre xyz,
//            quaternion wxyz, dims lwh; 1 cylinder: root xyz, axis xyz, radius, length;
//            2 ellipsoid: centroid xyz, radius, height (metres)
//   trajectories: {<robot>: [x, y, z, ...]}   keypose: {seq, p: [x, y, z], yaw}
//   instances: {c: [class per instance], n: [points per instance], p: [x, y, z, ...]}
//   optimizer: {keyposes, landmarks, peers, ms, full, rejected, dropped, t}
//   sensor: {state, sent, total, source, detections, reason}
//   loops: [{a, b, ka, kb, method, x, y, z, yaw, score, inliers_a, inliers_b}]
// team (per listener: a robot id, or -1 for the viewer's host): {linked: [robots], bytes_per_s}.
// status: {mode: live|replay|follow, received, dropped, replay?: {start, end, position, paused,
// live, speed}}. The page sends {cmd: pause|play|live|speed|seek, value} for replays.
// window.slideScene summarises what is drawn (for tests and the curious).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);
const canvas = $('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x111418);
const camera = new THREE.PerspectiveCamera(50, 1, 0.1, 5000);
camera.up.set(0, 0, 1);  // robots' frames are z-up
camera.position.set(-40, -40, 45);
const controls = new OrbitControls(camera, canvas);
scene.add(new THREE.HemisphereLight(0xffffff, 0x404050, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.2);
sun.position.set(30, -20, 60);
scene.add(sun);
const grid = new THREE.GridHelper(400, 40, 0x3a4450, 0x242b33);
grid.rotation.x = Math.PI / 2;
scene.add(grid);

const geo = {
  box: new THREE.BoxGeometry(1, 1, 1),
  cyl: new THREE.CylinderGeometry(1, 1, 1, 16).rotateX(Math.PI / 2).translate(0, 0, 0.5),  // base at 0, along z
  sphere: new THREE.SphereGeometry(1, 18, 12),
  cone: new THREE.ConeGeometry(0.7, 2.0, 12).rotateZ(-Math.PI / 2),  // points along +x
};
const PEER_COLOURS = [0xf0a030, 0x40c0f0, 0xe05080, 0x90e040, 0xb080ff, 0xf0e040];
const state = { classes: {}, hidden: new Set(), views: new Map(), selected: null, camMode: 'orbit', epoch: 0,
  version: 0, messages: 0, bytes: 0, team: {}, status: null, rate: [] };
const materials = new Map();

function classColour(cls) {
  const c = state.classes[cls];
  if (c) return new THREE.Color(c.color[0] / 255, c.color[1] / 255, c.color[2] / 255);
  return new THREE.Color().setHSL(((cls * 0.618) % 1 + 1) % 1, 0.6, 0.55);
}
function className(cls) { return state.classes[cls] ? state.classes[cls].name : `class ${cls}`; }
function material(cls) {
  if (!materials.has(cls)) materials.set(cls, new THREE.MeshLambertMaterial({ color: classColour(cls), transparent: true, opacity: 0.9 }));
  return materials.get(cls);
}

function newView(id) {
  const v = { id, group: new THREE.Group(), objects: new Map(), trajectories: new Map(), keypose: null, instances: null,
    rings: new THREE.Group(), loops: [], optimizer: null, sensor: null, instanceCount: 0 };
  v.group.add(v.rings);
  v.group.visible = false;
  scene.add(v.group);
  state.views.set(id, v);
  if (state.selected === null) select(id);
  return v;
}
function dispose(obj) { obj.traverse((o) => { if (o.geometry && !Object.values(geo).includes(o.geometry)) o.geometry.dispose(); }); }
function clearAll() {
  for (const v of state.views.values()) { scene.remove(v.group); dispose(v.group); }
  state.views.clear();
  state.team = {};
}

function setObject(v, row) {
  const [id, cls, shape] = row;
  const p = row.slice(3);
  let m = v.objects.get(id);
  const g = shape === 0 ? geo.box : shape === 1 ? geo.cyl : geo.sphere;
  if (!m || m.geometry !== g) {
    if (m) v.group.remove(m);
    m = new THREE.Mesh(g, material(cls));
    v.objects.set(id, m);
    v.group.add(m);
  }
  m.material = material(cls);
  m.userData.cls = cls;
  m.quaternion.identity();
  if (shape === 0) {
    m.position.set(p[0], p[1], p[2]);
    m.quaternion.set(p[4], p[5], p[6], p[3]);
    m.scale.set(p[7], p[8], p[9]);
  } else if (shape === 1) {
    m.position.set(p[0], p[1], p[2]);
    const axis = new THREE.Vector3(p[3], p[4], p[5]);
    if (axis.lengthSq() > 1e-9) m.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), axis.normalize());
    m.scale.set(p[6], p[6], p[7]);
  } else {
    m.position.set(p[0], p[1], p[2]);
    m.scale.set(p[3], p[3], Math.max(p[4] / 2, 0.05));
  }
  m.visible = !state.hidden.has(cls);
}

function setTrajectory(v, robot, flat) {
  let line = v.trajectories.get(robot);
  if (!line) {
    const colour = robot === v.id ? 0xffffff : PEER_COLOURS[robot % PEER_COLOURS.length];
    line = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: colour }));
    v.trajectories.set(robot, line);
    v.group.add(line);
  }
  line.geometry.setAttribute('position', new THREE.Float32BufferAttribute(flat, 3));
  line.geometry.computeBoundingSphere();
}

function setKeypose(v, k) {
  if (!v.keypose) {
    v.keypose = new THREE.Mesh(geo.cone, new THREE.MeshLambertMaterial({ color: 0xffffff, emissive: 0x303030 }));
    v.group.add(v.keypose);
  }
  v.keypose.position.set(k.p[0], k.p[1], k.p[2] + 1.0);
  v.keypose.rotation.set(0, 0, k.yaw);
  v.keypose.userData.seq = k.seq;
}

function setInstances(v, inst) {
  if (v.instances) { v.group.remove(v.instances); v.instances.geometry.dispose(); }
  const colours = [];
  inst.n.forEach((n, i) => { const c = classColour(inst.c[i]); for (let k = 0; k < n; ++k) colours.push(c.r, c.g, c.b); });
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(inst.p, 3));
  g.setAttribute('color', new THREE.Float32BufferAttribute(colours, 3));
  v.instances = new THREE.Points(g, new THREE.PointsMaterial({ size: 0.3, vertexColors: true }));
  v.instanceCount = inst.p.length / 3;
  v.group.add(v.instances);
}

const ringMaterial = new THREE.MeshBasicMaterial({ color: 0xff40ff, side: THREE.DoubleSide });
const ringGeometry = new THREE.RingGeometry(0.85, 1.0, 32);  // flat on the ground (the x-y plane)
function drawRings(v) {
  v.rings.clear();
  for (const lc of v.loops.slice(-3)) {
    const ids = lc.a === v.id ? lc.inliers_a : lc.b === v.id ? lc.inliers_b : [];
    for (const id of ids) {
      const m = v.objects.get(id);
      if (!m) continue;
      const ring = new THREE.Mesh(ringGeometry, ringMaterial);
      const box = new THREE.Box3().setFromObject(m);
      const size = box.getSize(new THREE.Vector3());
      box.getCenter(ring.position);
      ring.position.z = box.min.z + 0.05;
      const r = Math.max(Math.hypot(size.x, size.y) / 2 + 0.4, 0.8);
      ring.scale.set(r, r, 1);
      v.rings.add(ring);
    }
  }
}

function apply(msg) {
  if (msg.reset || msg.epoch !== state.epoch) clearAll();
  if (msg.classes) { state.classes = msg.classes; materials.clear(); buildLegend(); }
  state.epoch = msg.epoch;
  state.version = msg.version;
  for (const [key, d] of Object.entries(msg.views || {})) {
    const id = Number(key);
    const v = state.views.get(id) || newView(id);
    if (d.objects) {
      for (const row of d.objects.set) setObject(v, row);
      for (const id of d.objects.del) { const m = v.objects.get(id); if (m) { v.group.remove(m); v.objects.delete(id); } }
    }
    for (const [r, flat] of Object.entries(d.trajectories || {})) setTrajectory(v, Number(r), flat);
    if (d.keypose) setKeypose(v, d.keypose);
    if (d.instances) setInstances(v, d.instances);
    if (d.optimizer) v.optimizer = d.optimizer;
    if (d.sensor) v.sensor = d.sensor;
    if (d.loops) v.loops = d.loops;
    if (d.loops || d.objects) drawRings(v);
  }
  Object.assign(state.team, msg.team || {});
  if (msg.status) state.status = msg.status;
  buildRobots();
  showPanels();
  if (!state.fitted) state.fitted = fit();
  summarise();
}

// Frames the selected view's map and trajectories (once when it first has any, and on 'fit').
function fit() {
  const v = state.views.get(state.selected);
  if (!v) return false;
  const box = new THREE.Box3();
  for (const m of v.objects.values()) box.expandByObject(m);
  for (const line of v.trajectories.values()) box.expandByObject(line);
  if (box.isEmpty()) return false;
  const centre = box.getCenter(new THREE.Vector3());
  const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 10);
  const dir = camera.position.clone().sub(controls.target).normalize();
  controls.target.copy(centre);
  camera.position.copy(centre).addScaledVector(dir, radius * 1.8);
  return true;
}

function select(id) {
  state.fitted = state.selected === id && state.fitted;
  state.selected = id;
  for (const v of state.views.values()) v.group.visible = v.id === id;
  buildRobots();
  showPanels();
}
function buildRobots() {
  const ids = [...state.views.keys()].sort((a, b) => a - b);
  const box = $('robots');
  if (box.dataset.ids === ids.join() + '/' + state.selected) return;
  box.dataset.ids = ids.join() + '/' + state.selected;
  box.replaceChildren(...ids.map((id) => {
    const b = document.createElement('button');
    b.textContent = `robot ${id}`;
    b.className = id === state.selected ? 'on' : '';
    b.onclick = () => select(id);
    return b;
  }));
}
function buildLegend() {
  $('legend').replaceChildren(...Object.keys(state.classes).map(Number).map((cls) => {
    const l = document.createElement('label');
    const box = document.createElement('input');
    box.type = 'checkbox';
    box.checked = !state.hidden.has(cls);
    box.onchange = () => {
      if (box.checked) state.hidden.delete(cls); else state.hidden.add(cls);
      for (const v of state.views.values()) for (const m of v.objects.values()) m.visible = !state.hidden.has(m.userData.cls);
    };
    const sw = document.createElement('span');
    sw.className = 'swatch';
    sw.style.background = '#' + classColour(cls).getHexString();
    l.append(box, sw, `${className(cls)} (${state.classes[cls].shape})`);
    return l;
  }));
}

function rateText(bytesPerS) {
  return bytesPerS < 1024 ? `${Math.round(bytesPerS)} B/s` : `${(bytesPerS / 1024).toFixed(1)} KB/s`;
}

function showPanels() {
  const v = state.views.get(state.selected);
  const o = v && v.optimizer;
  $('optimizer').textContent = o ? `${o.keyposes} key poses, ${o.landmarks} landmarks, ${o.peers} peers merged; ` +
    `update ${o.ms} ms${o.full ? ' (full solve)' : ''}${o.rejected || o.dropped ? `; refused ${o.rejected}, dropped ${o.dropped}` : ''}` : '–';
  const s = v && v.sensor;
  $('sensor').textContent = s ? `${s.state}: ${s.sent}${s.total ? ' / ' + s.total : ''} frames (detections: ${s.detections || '?'})` +
    (s.reason ? ` – ${s.reason}` : '') : '–';
  $('sensor-bar').style.width = s && s.total ? `${Math.min(100, 100 * s.sent / s.total)}%` : '0';
  const team = state.team[state.selected] || state.team[-1];
  $('team').textContent = team ? `linked: ${team.linked.length ? team.linked.map((r) => 'robot ' + r).join(', ') : 'none'}; ` +
    `${rateText(team.bytes_per_s)} on its team bus` : '–';
  $('loops').replaceChildren(...(v ? v.loops.slice().reverse() : []).map((lc) => {
    const d = document.createElement('div');
    d.textContent = `${lc.a === lc.b ? 'intra' : 'inter'} r${lc.a}←r${lc.b} ${lc.method}: ${lc.inliers_a.length} inliers, ` +
      `x ${lc.x} y ${lc.y} yaw ${(lc.yaw * 180 / Math.PI).toFixed(1)}°`;
    return d;
  }));
  if (v && !v.loops.length) $('loops').textContent = 'none yet';
  const st = state.status;
  const rate = state.rate.length > 1 ? (state.rate.at(-1)[1] - state.rate[0][1]) / Math.max(1, state.rate.at(-1)[0] - state.rate[0][0]) : 0;
  $('traffic').textContent = st ? `${st.mode}; bus messages ${st.received}, dropped ${st.dropped}; to this page ${rateText(rate)}` : '';
  const r = st && st.replay;
  $('replay').hidden = !r;
  if (r) {
    $('play').textContent = r.paused ? 'play' : 'pause';
    $('live').className = r.live ? 'on' : '';
    if (!slider.dragging) $('slider').value = r.end > r.start ? Math.round(1000 * (r.position - r.start) / (r.end - r.start)) : 1000;
    $('clock').textContent = `${(r.position - r.start).toFixed(1)} / ${(r.end - r.start).toFixed(1)} s`;
  }
}

function summarise() {
  const views = {};
  for (const v of state.views.values()) {
    const classes = {};
    for (const m of v.objects.values()) classes[m.userData.cls] = (classes[m.userData.cls] || 0) + 1;
    const trajectories = {};
    for (const [r, line] of v.trajectories) trajectories[r] = line.geometry.getAttribute('position').count;
    views[v.id] = { objects: v.objects.size, classes, trajectories, instances: v.instanceCount, loops: v.loops.length,
      keypose: v.keypose ? v.keypose.position.toArray() : null, rings: v.rings.children.length };
  }
  window.slideScene = { epoch: state.epoch, version: state.version, messages: state.messages, bytes: state.bytes,
    selected: state.selected, views, status: state.status, team: state.team };
}
// Pixel position of a point of the selected view's frame (for tests that sample the picture).
window.slideScreenOf = (x, y, z) => {
  const p = new THREE.Vector3(x, y, z).project(camera);
  return [(p.x + 1) / 2 * canvas.clientWidth, (1 - p.y) / 2 * canvas.clientHeight];
};

// Camera: orbit (free), top (from above, north up), follow (keeps its offset to the robot).
$('fit').onclick = () => fit();
document.querySelectorAll('#camera button[data-mode]').forEach((b) => b.onclick = () => {
  state.camMode = b.dataset.mode;
  document.querySelectorAll('#camera button[data-mode]').forEach((o) => o.className = o === b ? 'on' : '');
  controls.enableRotate = state.camMode !== 'top';
  if (state.camMode === 'top') {
    const d = camera.position.distanceTo(controls.target);
    camera.position.set(controls.target.x, controls.target.y - 0.01, controls.target.z + d);
  }
});
function robotPosition(v) {
  if (v.keypose) return v.keypose.position.clone();
  const line = v.trajectories.get(v.id);
  const pos = line && line.geometry.getAttribute('position');
  return pos && pos.count ? new THREE.Vector3().fromBufferAttribute(pos, pos.count - 1) : null;
}
function updateScale() {
  const dist = camera.position.distanceTo(controls.target);
  const perPx = 2 * dist * Math.tan(THREE.MathUtils.degToRad(camera.fov / 2)) / Math.max(1, canvas.clientHeight);
  let len = 1;
  for (const m of [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000]) if (m / perPx <= 140) len = m;
  $('scale-bar').style.width = `${len / perPx}px`;
  $('scale-label').textContent = `${len} m`;
}
function frame() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== Math.floor(w * devicePixelRatio) || canvas.height !== Math.floor(h * devicePixelRatio)) {
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(1, h);
    camera.updateProjectionMatrix();
  }
  const v = state.views.get(state.selected);
  if (state.camMode === 'follow' && v) {
    const p = robotPosition(v);
    if (p) { camera.position.add(p.clone().sub(controls.target)); controls.target.copy(p); }
  }
  controls.update();
  updateScale();
  renderer.render(scene, camera);
  requestAnimationFrame(frame);
}
requestAnimationFrame(frame);

// Replay controls.
const slider = $('slider');
let socket = null;
const send = (cmd, value) => socket && socket.readyState === 1 && socket.send(JSON.stringify({ cmd, value }));
$('play').onclick = () => send(state.status && state.status.replay && state.status.replay.paused ? 'play' : 'pause');
$('live').onclick = () => send('live');
$('speed').onchange = () => send('speed', Number($('speed').value));
slider.oninput = () => { slider.dragging = true; };
slider.onchange = () => {
  const r = state.status && state.status.replay;
  if (r) send('seek', r.start + (r.end - r.start) * slider.value / 1000);
  slider.dragging = false;
};

function connect() {
  socket = new WebSocket(`${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws`);
  socket.onopen = () => { $('conn').textContent = 'connected'; $('conn').className = 'ok'; };
  socket.onmessage = (e) => {
    state.messages += 1;
    state.bytes += e.data.length;
    const now = performance.now() / 1000;
    state.rate.push([now, state.bytes]);
    while (state.rate.length > 2 && now - state.rate[0][0] > 10) state.rate.shift();
    apply(JSON.parse(e.data));
  };
  socket.onclose = () => {
    $('conn').textContent = 'disconnected, retrying';
    $('conn').className = 'bad';
    state.epoch = 0;
    setTimeout(connect, 1000);
  };
}
connect();
summarise();

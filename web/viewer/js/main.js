// The viewer page: replay of a recorded trial (?result=REL, served by vb_view) or live
// teleoperation (?teleop=1). docs/viewer.md describes both; window.vbViewer is the test hook
// (state the headless-browser tests read, and seek()).
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/OrbitControls.js';
import { TrialError, loadTrial } from './trial_data.js';
import {
  CLASS_COLOURS, VehicleModel, buildObstacles, buildRoute, buildTerrain, buildTrail,
} from './scene.js';
import { PLOT_SERIES, Plot } from './plots.js';
import { startTeleop } from './teleop.js';

const hook = {
  ready: false, error: null, mode: null, loadMs: null, samples: 0, duration: 0, time: 0,
  frames: 0, playing: false, plotPoints: {}, terrainTriangles: 0, obstacles: 0,
  timings: {},   // ms since navigation start at each loading stage
};
window.vbViewer = hook;

const $ = (id) => document.getElementById(id);

export function showError(message) {
  hook.error = String(message);
  const box = $('error');
  box.textContent = `Cannot show this trial:\n${message}`;
  box.hidden = false;
  console.error(message);
}

// ---- the 3-D view -------------------------------------------------------------------------
class View {
  constructor(canvas) {
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x9fb8cf);
    this.camera = new THREE.PerspectiveCamera(50, 1, 0.5, 5000);
    this.camera.up.set(0, 0, 1);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.enableDamping = true;
    this.scene.add(new THREE.HemisphereLight(0xf4f8ff, 0x4a4036, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.8);
    sun.position.set(-0.5, -0.3, 1.0);
    this.scene.add(sun);
    this.follow = true;
    this.lastTarget = null;
    const resize = () => {
      const w = canvas.clientWidth, h = canvas.clientHeight;
      if (w === 0 || h === 0) return;
      this.renderer.setSize(w, h, false);
      this.camera.aspect = w / h;
      this.camera.updateProjectionMatrix();
    };
    new ResizeObserver(resize).observe(canvas);
    resize();
  }
  overview(task) {
    const s = Math.max(task.size_m[0], task.size_m[1]);
    this.controls.target.set(0, 0, 0);
    this.camera.position.set(0, -0.95 * s, 0.85 * s);
    this.lastTarget = null;
    this.controls.update();
  }
  chase(x, y, z, yawDeg, scale) {
    const yaw = yawDeg * Math.PI / 180;
    const back = 22 * scale, up = 14 * scale;
    this.controls.target.set(x, y, z);
    this.camera.position.set(x - back * Math.cos(yaw), y - back * Math.sin(yaw), z + up);
    this.lastTarget = new THREE.Vector3(x, y, z);
    this.controls.update();
  }
  // Keeps the orbit's offset while the vehicle moves (follow mode).
  track(x, y, z) {
    if (!this.follow) return;
    const p = new THREE.Vector3(x, y, z);
    if (this.lastTarget !== null) {
      const d = p.clone().sub(this.lastTarget);
      this.camera.position.add(d);
      this.controls.target.add(d);
    }
    this.lastTarget = p;
  }
  render() {
    this.controls.update();
    this.renderer.render(this.scene, this.camera);
    hook.frames += 1;
  }
}

function fillInfo(rows) {
  const table = $('info');
  table.replaceChildren();
  for (const [k, v] of rows) {
    const tr = document.createElement('tr');
    const a = document.createElement('td');
    const b = document.createElement('td');
    a.textContent = k;
    b.textContent = v;
    tr.append(a, b);
    table.append(tr);
  }
}

function fillLegend(task) {
  const present = new Set(task.semantics.classes);
  const legend = $('legend');
  legend.replaceChildren();
  for (const id of [...present].sort((a, b) => a - b)) {
    const name = task.semantics.class_names[id];
    const item = document.createElement('div');
    const sw = document.createElement('span');
    sw.className = 'swatch';
    sw.style.background = `#${(CLASS_COLOURS[name] ?? 0xff00ff).toString(16).padStart(6, '0')}`;
    item.append(sw, name);
    legend.append(item);
  }
  const extra = document.createElement('div');
  extra.innerHTML = '<span class="swatch" style="background:#6d6a66"></span>rock ' +
    '<span class="swatch" style="background:#2f7d32"></span>tree ' +
    '<span class="swatch" style="background:#2f6dff"></span>path ' +
    '<span class="swatch" style="background:#ff8c1a"></span>driven';
  legend.append(extra);
}

// The static world: terrain, obstacles, route. Returns what playback and teleop need.
export function buildWorld(view, bundle) {
  const task = bundle.task;
  const pair = task.pairs[bundle.pair];
  const terrain = buildTerrain(task);
  view.scene.add(terrain.mesh);
  view.scene.add(buildObstacles(task));
  // A trial's own goal circle (its rules' radius) where it has one, else the task's (vb's rules).
  const goalRadius = bundle.trial?.goal_radius_m ?? task.goal_radius_m;
  view.scene.add(buildRoute(task, pair, terrain.heightField, goalRadius));
  const vehicle = new VehicleModel(bundle.vehicle);
  view.scene.add(vehicle.group);
  hook.terrainTriangles = terrain.triangles;
  hook.obstacles = task.obstacles.length;
  fillLegend(task);
  return { task, pair, terrain, vehicle };
}

// ---- replay -------------------------------------------------------------------------------
function startReplay(view, bundle, t0) {
  const mark = (name) => { hook.timings[name] = Math.round(performance.now()); };
  const { result, traj } = loadTrial(bundle);   // checks first: a bad trial draws nothing
  mark('trial_parsed');
  const { task, vehicle } = buildWorld(view, bundle);
  mark('world_built');
  const c = traj.columns;
  const n = traj.n;
  const t = c.t_s;
  // Rolled distance per sample (for the wheel spin): planar path length.
  const dist = new Float64Array(n);
  for (let i = 1; i < n; ++i) {
    dist[i] = dist[i - 1] + Math.hypot(c.x_m[i] - c.x_m[i - 1], c.y_m[i] - c.y_m[i - 1]);
  }
  const trail = buildTrail(c.x_m, c.y_m, c.z_m, 0.1 * task.scale);
  view.scene.add(trail);

  const plotsDiv = $('plots');
  const plots = PLOT_SERIES.map((s) => {
    const p = new Plot(plotsDiv, s.label, s.unit, s.colour, (time) => seek(time));
    p.setData(t, c[s.key], n, t[n - 1]);
    return p;
  });

  fillInfo([
    ['task', `${result.task} (${task.file})`],
    ['pair', String(result.pair)],
    ['vehicle / system', `${result.vehicle} / ${result.system}`],
    ['seed', String(result.seed)],
    ['status', result.status + (result.tipped ? ' (tipped)' : '')],
    ['traversal time', result.traversal_time_s === null ? '-' : `${result.traversal_time_s.toFixed(2)} s`],
    ['simulated', `${result.sim_time_s.toFixed(2)} s, ${n} samples`],
    ['goal distance', `${result.final_goal_distance_m.toFixed(2)} m`],
    ['path length', `${result.path_length_m.toFixed(1)} m`],
    ['obstacle contacts', String(result.obstacle_contacts)],
    ['max |roll|, |pitch|', `${result.abs_roll_deg.max.toFixed(1)}°, ${result.abs_pitch_deg.max.toFixed(1)}°`],
  ]);
  $('title').textContent = `${result.task} pair ${result.pair}: ${result.status}`;

  const duration = t[n - 1];
  const slider = $('slider');
  slider.min = String(t[0]);
  slider.max = String(duration);
  hook.samples = n;
  hook.duration = duration;
  let time = t[0];
  let playing = false;
  let speed = 1;

  // Pose at time `time`: linear between samples (yaw across the ±180° seam).
  const index = (time) => {
    let lo = 0, hi = n - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (t[mid] <= time) lo = mid; else hi = mid - 1;
    }
    return lo;
  };
  const pose = (time) => {
    const i = index(time);
    const j = Math.min(i + 1, n - 1);
    const a = j > i ? Math.min(1, Math.max(0, (time - t[i]) / (t[j] - t[i]))) : 0;
    const lerp = (arr) => arr[i] + a * (arr[j] - arr[i]);
    let dyaw = c.yaw_deg[j] - c.yaw_deg[i];
    if (dyaw > 180) dyaw -= 360;
    if (dyaw < -180) dyaw += 360;
    return { i, x: lerp(c.x_m), y: lerp(c.y_m), z: lerp(c.z_m), roll: lerp(c.roll_deg),
             pitch: lerp(c.pitch_deg), yaw: c.yaw_deg[i] + a * dyaw, steering: lerp(c.steering),
             distance: lerp(dist) };
  };

  const apply = () => {
    const p = pose(time);
    vehicle.setPose(p.x, p.y, p.z, p.roll, p.pitch, p.yaw, p.steering, p.distance);
    trail.geometry.setDrawRange(0, p.i + 1);
    view.track(p.x, p.y, p.z);
    slider.value = String(time);
    $('clock').textContent = `${time.toFixed(2)} / ${duration.toFixed(2)} s`;
    for (const plot of plots) plot.render(time);
    hook.time = time;
    hook.sampleIndex = p.i;
  };
  function seek(newTime) {
    time = Math.min(duration, Math.max(t[0], Number(newTime)));
    apply();
  }
  const setPlaying = (on) => {
    playing = on && time < duration;
    hook.playing = playing;
    $('play').textContent = playing ? '❚❚' : '▶';
  };
  slider.addEventListener('input', () => { setPlaying(false); seek(slider.value); });
  $('play').addEventListener('click', () => {
    if (time >= duration) seek(t[0]);
    setPlaying(!playing);
  });
  $('speed').addEventListener('change', () => { speed = Number($('speed').value); });
  window.addEventListener('keydown', (ev) => {
    if (ev.code === 'Space') { ev.preventDefault(); $('play').click(); }
    if (ev.code === 'ArrowRight') seek(time + 1);
    if (ev.code === 'ArrowLeft') seek(time - 1);
  });
  $('follow').addEventListener('change', () => {
    view.follow = $('follow').checked;
    view.lastTarget = null;
    if (view.follow) { const p = pose(time); view.chase(p.x, p.y, p.z, p.yaw, task.scale); }
  });
  $('overview').addEventListener('click', () => {
    $('follow').checked = false;
    view.follow = false;
    view.overview(task);
  });

  const p0 = pose(t[0]);
  view.chase(p0.x, p0.y, p0.z, p0.yaw, task.scale);
  seek(t0 === null ? t[0] : t0);

  mark('replay_ready');
  hook.plotPoints = Object.fromEntries(PLOT_SERIES.map((s, k) => [s.key, plots[k].pointCount]));
  hook.seek = (s) => { setPlaying(false); seek(s); view.render(); return hook.vehiclePose(); };
  hook.play = (on = true) => setPlaying(on);
  hook.vehiclePose = () => {
    const g = vehicle.group;
    return { x: g.position.x, y: g.position.y, z: g.position.z,
             roll_deg: THREE.MathUtils.radToDeg(g.rotation.x),
             pitch_deg: THREE.MathUtils.radToDeg(g.rotation.y),
             yaw_deg: THREE.MathUtils.radToDeg(g.rotation.z), sample: hook.sampleIndex };
  };
  hook.setSpeed = (s) => { speed = s; };

  let last = performance.now();
  view.renderer.setAnimationLoop(() => {
    const now = performance.now();
    const dt = (now - last) / 1000;
    last = now;
    if (playing) {
      time = Math.min(duration, time + dt * speed);
      if (time >= duration) setPlaying(false);
      apply();
    }
    view.render();
  });
}

// ---- start --------------------------------------------------------------------------------
async function fetchJson(url) {
  let response;
  try {
    response = await fetch(url);
  } catch (e) {
    throw new TrialError(`cannot reach the vb_view server (${url}): ${e.message}`);
  }
  const text = await response.text();
  let body;
  try {
    body = JSON.parse(text);
  } catch (e) {
    throw new TrialError(`${url}: answer is not JSON (HTTP ${response.status})`);
  }
  if (!response.ok || body.error) {
    throw new TrialError(body.error ?? `${url}: HTTP ${response.status}`);
  }
  return body;
}

async function main() {
  const started = performance.now();
  hook.timings.script_started = Math.round(started);
  const params = new URLSearchParams(window.location.search);
  let view = null;
  try {
    try {
      view = new View($('scene'));
    } catch (e) {
      throw new TrialError(`this browser cannot draw 3-D (WebGL): ${e.message}`);
    }
    hook.timings.renderer_created = Math.round(performance.now());
    if (params.has('teleop')) {
      hook.mode = 'teleop';
      const bundle = await fetchJson('/api/scene');
      const world = buildWorld(view, bundle);
      startTeleop(view, world, bundle, hook, { fillInfo, showError });
    } else if (params.has('result')) {
      hook.mode = 'replay';
      hook.timings.trial_requested = Math.round(performance.now());
      const bundle = await fetchJson(`/api/trial?result=${encodeURIComponent(params.get('result'))}`);
      hook.timings.bundle_received = Math.round(performance.now());
      const t0 = params.has('t') ? Number(params.get('t')) : null;
      startReplay(view, bundle, t0);
    } else {
      throw new TrialError('no trial given: open a trial with `vb_view RESULT.json`, a results ' +
                           'directory with `vb_view serve DIR`, or drive with `vb_view teleop TASK`');
    }
    hook.loadMs = performance.now() - started;
    view.render();
    hook.readyMs = performance.now();   // since navigation start: HTML, scripts, data, scene
    // The part that grows with the trial: from asking for it to its first frame.
    if (hook.timings.trial_requested !== undefined) {
      hook.trialLoadMs = hook.readyMs - hook.timings.trial_requested;
    }
    hook.ready = true;
  } catch (e) {
    showError(e instanceof TrialError ? e.message : `internal error: ${e.stack ?? e}`);
    if (view !== null) view.render();
    hook.ready = true;
  }
}

main();

// Teleoperation in the page: keyboard (and a gamepad through the Gamepad API where one is
// connected) -> command messages over the WebSocket to vb_view, which steps the episode at real
// time and answers with the vehicle's state (docs/viewer.md "Teleoperation").
import { LiveTrail } from './scene.js';
import { PLOT_SERIES, Plot } from './plots.js';

// Pedal and steering-wheel rates: a key press moves the command towards its target at these
// rates (per second), as a person's foot and hands would, instead of jumping.
const THROTTLE_RATE = 2.0;
const BRAKE_RATE = 4.0;
const STEER_RATE = 1.5;
const SEND_PERIOD_MS = 50;
const LIVE_CAPACITY = 60 * 30 + 600;   // 60 s of state messages at 30 Hz, with margin

function approach(value, target, rate, dt) {
  const step = rate * dt;
  if (Math.abs(target - value) <= step) return target;
  return value + Math.sign(target - value) * step;
}

export function startTeleop(view, world, bundle, hook, ui) {
  const { task, vehicle, pair } = world;
  document.getElementById('teleop-panel').hidden = false;
  document.getElementById('slider').disabled = true;
  document.getElementById('play').disabled = true;
  document.getElementById('title').textContent = `${task.name} pair ${bundle.pair}: drive`;
  ui.fillInfo([
    ['task', task.file],
    ['pair', `${bundle.pair}: (${pair.start_m}) → (${pair.goal_m})`],
    ['vehicle', bundle.vehicle.name],
  ]);
  const statusDiv = document.getElementById('teleop-status');
  const commandDiv = document.getElementById('teleop-command');
  const recordedDiv = document.getElementById('teleop-recorded');

  const teleop = { connected: false, states: 0, commandsSent: 0, lastCommand: null,
                   lastState: null, recorded: null, errors: [] };
  hook.teleop = teleop;

  const trail = new LiveTrail(LIVE_CAPACITY, 0.1 * task.scale);
  view.scene.add(trail.line);
  const live = { t: new Float64Array(LIVE_CAPACITY), n: 0 };
  for (const s of PLOT_SERIES) live[s.key] = new Float64Array(LIVE_CAPACITY);
  const plotsDiv = document.getElementById('plots');
  const plots = PLOT_SERIES.map((s) => new Plot(plotsDiv, s.label, s.unit, s.colour, null));
  let lastPlot = 0;
  let distance = 0;
  let lastXY = null;

  const p0 = pair.start_m;
  const yaw0 = Math.atan2(pair.goal_m[1] - p0[1], pair.goal_m[0] - p0[0]) * 180 / Math.PI;
  const z0 = world.terrain.heightField.height(p0[0], p0[1]) + bundle.vehicle.wheel_radius_m;
  vehicle.setPose(p0[0], p0[1], z0, 0, 0, yaw0, 0, 0);
  view.chase(p0[0], p0[1], z0, yaw0, task.scale);

  // Keyboard state.
  const held = new Set();
  const keys = {
    up: ['KeyW', 'ArrowUp'], down: ['KeyS', 'ArrowDown'],
    left: ['KeyA', 'ArrowLeft'], right: ['KeyD', 'ArrowRight'],
  };
  const isHeld = (name) => keys[name].some((k) => held.has(k));
  window.addEventListener('keydown', (ev) => {
    if (Object.values(keys).flat().includes(ev.code)) ev.preventDefault();
    held.add(ev.code);
  });
  window.addEventListener('keyup', (ev) => held.delete(ev.code));
  window.addEventListener('blur', () => held.clear());

  const command = { throttle: 0, steering: 0, braking: 0 };
  let sent = '';
  let lastTick = performance.now();

  const url = `ws://${window.location.host}/ws`;
  const ws = new WebSocket(url);
  const send = (text) => { if (ws.readyState === WebSocket.OPEN) ws.send(text); };
  ws.addEventListener('open', () => {
    teleop.connected = true;
    statusDiv.textContent = 'connected: press "start drive"';
  });
  ws.addEventListener('close', () => {
    teleop.connected = false;
    statusDiv.textContent = 'disconnected from vb_view (restart it and reload the page)';
  });
  ws.addEventListener('error', () => ui.showError(`WebSocket ${url} failed: is vb_view teleop running?`));
  ws.addEventListener('message', (ev) => {
    const m = JSON.parse(ev.data);
    if (m.type === 'state') onState(m);
    else if (m.type === 'recorded') {
      teleop.recorded = m.result;
      recordedDiv.innerHTML = '';
      const a = document.createElement('a');
      a.href = `index.html?result=${encodeURIComponent(m.result)}`;
      a.textContent = `recorded ${m.result} (${m.status}): replay`;
      a.target = '_blank';
      recordedDiv.append(a);
    } else if (m.type === 'error') {
      teleop.errors.push(m.message);
      statusDiv.textContent = `server: ${m.message}`;
      console.error(m.message);
    }
  });

  function onState(m) {
    teleop.states += 1;
    teleop.lastState = m;
    if (m.drive === 0 || m.t_s === undefined) return;
    statusDiv.textContent = `drive ${m.drive}: ${m.status}, t = ${m.t_s.toFixed(2)} s, ` +
      `${m.forward_speed_mps.toFixed(1)} m/s, gear ${m.gear}, goal ${m.goal_distance_m.toFixed(1)} m`;
    if (lastXY !== null) distance += Math.hypot(m.x_m - lastXY[0], m.y_m - lastXY[1]);
    lastXY = [m.x_m, m.y_m];
    vehicle.setPose(m.x_m, m.y_m, m.z_m, m.roll_deg, m.pitch_deg, m.yaw_deg, m.steering, distance);
    view.track(m.x_m, m.y_m, m.z_m);
    if (!m.driving) return;
    trail.push(m.x_m, m.y_m, m.z_m);
    if (live.n < LIVE_CAPACITY) {
      live.t[live.n] = m.t_s;
      for (const s of PLOT_SERIES) live[s.key][live.n] = m[s.key];
      live.n += 1;
    }
    document.getElementById('clock').textContent = `${m.t_s.toFixed(2)} s`;
  }

  document.getElementById('drive-start').addEventListener('click', () => {
    trail.clear();
    live.n = 0;
    distance = 0;
    lastXY = null;
    teleop.recorded = null;
    recordedDiv.textContent = '';
    send('start');
    sent = '';
  });
  document.getElementById('drive-stop').addEventListener('click', () => send('stop'));

  // Reads the inputs, moves the command towards them and sends it when it changed.
  setInterval(() => {
    const now = performance.now();
    const dt = Math.min(0.2, (now - lastTick) / 1000);
    lastTick = now;
    let throttleTarget = isHeld('up') ? 1 : 0;
    let brakeTarget = isHeld('down') ? 1 : 0;
    let steerTarget = (isHeld('left') ? 1 : 0) - (isHeld('right') ? 1 : 0);
    let direct = false;
    for (const pad of (navigator.getGamepads ? navigator.getGamepads() : [])) {
      if (!pad) continue;
      const stick = pad.axes.length > 0 ? -pad.axes[0] : 0;   // left stick, + = left
      const rt = pad.buttons[7] ? pad.buttons[7].value : 0;
      const lt = pad.buttons[6] ? pad.buttons[6].value : 0;
      if (Math.abs(stick) > 0.08 || rt > 0.05 || lt > 0.05) {
        throttleTarget = rt;
        brakeTarget = lt;
        steerTarget = Math.abs(stick) > 0.08 ? stick : 0;
        direct = true;   // analogue inputs are positions already: no ramp
      }
    }
    if (direct) {
      command.throttle = throttleTarget;
      command.braking = brakeTarget;
      command.steering = steerTarget;
    } else {
      command.throttle = approach(command.throttle, throttleTarget, THROTTLE_RATE, dt);
      command.braking = approach(command.braking, brakeTarget, BRAKE_RATE, dt);
      command.steering = approach(command.steering, steerTarget, STEER_RATE, dt);
    }
    const text = `command ${command.throttle.toFixed(3)} ${command.steering.toFixed(3)} ` +
                 `${command.braking.toFixed(3)}`;
    commandDiv.textContent = `throttle ${command.throttle.toFixed(2)}  steering ` +
      `${command.steering.toFixed(2)}  brake ${command.braking.toFixed(2)}`;
    if (text !== sent && ws.readyState === WebSocket.OPEN) {
      send(text);
      sent = text;
      teleop.commandsSent += 1;
      teleop.lastCommand = { ...command };
    }
  }, SEND_PERIOD_MS);

  view.renderer.setAnimationLoop(() => {
    const now = performance.now();
    if (now - lastPlot > 200 && live.n > 0) {
      lastPlot = now;
      for (const p of plots) {
        const s = PLOT_SERIES[plots.indexOf(p)];
        p.setData(live.t, live[s.key], live.n, Math.max(live.t[live.n - 1], 1));
        p.render(live.t[live.n - 1]);
      }
    }
    view.render();
  });
}

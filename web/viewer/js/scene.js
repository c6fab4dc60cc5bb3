// The 3-D scene in world coordinates (x east, y north, z up; metres), as the physics sees it:
// the terrain surface triangulated along each cell's SW-NE diagonal (the triangles the wheels
// touch), coloured by the semantic patch under each cell; rocks and trees as their collision
// boxes; the pair's global path, start and goal circle draped on the ground; the driven trail;
// and a schematic vehicle (body box + wheels) posed from the recorded pose.
import * as THREE from 'three';

export const CLASS_COLOURS = {
  clay: 0xb8733f, concrete: 0xa6a8ab, dirt: 0x8a6a48, grass: 0x6f8f3a, gravel: 0x9c9a88,
  rock: 0x7b7266, wood: 0x9c5a32, mud: 0x5b4330, sand: 0xdcc488, snow: 0xf1f4f8,
};

// Height of the triangulated surface at (x, y): the same triangle split as terrain::Terrain.
export class HeightField {
  constructor(task) {
    const h = task.heights;
    this.rows = h.rows;
    this.cols = h.cols;
    this.v = h.values_m;
    this.sx = task.size_m[0];
    this.sy = task.size_m[1];
    this.dx = this.sx / (this.cols - 1);
    this.dy = this.sy / (this.rows - 1);
  }
  at(r, c) { return this.v[r * this.cols + c]; }
  height(x, y) {
    let u = (x + this.sx / 2) / this.dx;            // column coordinate
    let w = (this.sy / 2 - y) / this.dy;            // row coordinate (0 at the north edge)
    u = Math.min(Math.max(u, 0), this.cols - 1);
    w = Math.min(Math.max(w, 0), this.rows - 1);
    const c = Math.min(Math.floor(u), this.cols - 2);
    const r = Math.min(Math.floor(w), this.rows - 2);
    const fx = u - c;              // 0 at west, 1 at east
    const fy = 1 - (w - r);        // 0 at south (row r+1), 1 at north (row r)
    const sw = this.at(r + 1, c), se = this.at(r + 1, c + 1);
    const ne = this.at(r, c + 1), nw = this.at(r, c);
    if (fx >= fy) return sw + fx * (se - sw) + fy * (ne - se);   // triangle SW-SE-NE
    return sw + fy * (nw - sw) + fx * (ne - nw);                  // triangle SW-NE-NW
  }
}

export function buildTerrain(task) {
  const hf = new HeightField(task);
  const sem = task.semantics;
  const cells = (hf.rows - 1) * (hf.cols - 1);
  const pos = new Float32Array(cells * 18);
  const col = new Float32Array(cells * 18);
  const colour = new THREE.Color();
  const classColour = sem.class_names.map((name) => new THREE.Color(CLASS_COLOURS[name] ?? 0xff00ff));
  let k = 0;
  const x = (c) => -hf.sx / 2 + c * hf.dx;
  const y = (r) => hf.sy / 2 - r * hf.dy;
  for (let r = 0; r < hf.rows - 1; ++r) {
    for (let c = 0; c < hf.cols - 1; ++c) {
      // Patch under the cell centre (patches tile the world evenly, row 0 north).
      const cx = x(c) + hf.dx / 2, cy = y(r) - hf.dy / 2;
      const pc = Math.min(sem.cols - 1, Math.floor((cx + hf.sx / 2) / hf.sx * sem.cols));
      const pr = Math.min(sem.rows - 1, Math.floor((hf.sy / 2 - cy) / hf.sy * sem.rows));
      colour.copy(classColour[sem.classes[pr * sem.cols + pc]]);
      const tri = [
        [r + 1, c], [r + 1, c + 1], [r, c + 1],      // SW, SE, NE
        [r + 1, c], [r, c + 1], [r, c],              // SW, NE, NW
      ];
      for (const [vr, vc] of tri) {
        pos[k] = x(vc); pos[k + 1] = y(vr); pos[k + 2] = hf.at(vr, vc);
        col[k] = colour.r; col[k + 1] = colour.g; col[k + 2] = colour.b;
        k += 3;
      }
    }
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(col, 3));
  geometry.computeVertexNormals();
  const material = new THREE.MeshLambertMaterial({ vertexColors: true });
  const mesh = new THREE.Mesh(geometry, material);
  mesh.name = 'terrain';
  return { mesh, heightField: hf, triangles: cells * 2 };
}

// One obstacle's convex hull (vertices_m and counter-clockwise face polygons from the scene),
// fan-triangulated; an obstacle without them (an older scene) is its bounding box.
function obstacleGeometry(o) {
  if (!o.vertices_m || !o.faces) {
    const g = new THREE.BoxGeometry(1, 1, 1);
    const size = [0, 1, 2].map((a) => o.max_m[a] - o.min_m[a]);
    const centre = [0, 1, 2].map((a) => (o.max_m[a] + o.min_m[a]) / 2);
    g.scale(size[0], size[1], size[2]);
    g.translate(centre[0], centre[1], centre[2]);
    return g.toNonIndexed();
  }
  const pos = [];
  for (const face of o.faces) {
    for (let k = 1; k + 1 < face.length; ++k) {
      for (const id of [face[0], face[k], face[k + 1]]) pos.push(...o.vertices_m[id]);
    }
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(pos, 3));
  g.computeVertexNormals();   // flat shading: the triangles share no vertices
  return g;
}

export function buildObstacles(task) {
  const group = new THREE.Group();
  group.name = 'obstacles';
  for (const kind of ['rock', 'tree']) {
    const list = task.obstacles.filter((o) => o.kind === kind);
    if (list.length === 0) continue;
    const material = new THREE.MeshLambertMaterial({ color: kind === 'rock' ? 0x6d6a66 : 0x6b4f2e });
    const kindGroup = new THREE.Group();
    kindGroup.name = kind;
    for (const o of list) kindGroup.add(new THREE.Mesh(obstacleGeometry(o), material));
    group.add(kindGroup);
  }
  return group;
}

// A polyline on the ground, `lift` metres above it, with points at most `step` apart.
function drapedLine(points, hf, lift, step, material) {
  const out = [];
  for (let i = 0; i < points.length; ++i) {
    const [x1, y1] = points[i];
    if (i > 0) {
      const [x0, y0] = points[i - 1];
      const n = Math.max(1, Math.ceil(Math.hypot(x1 - x0, y1 - y0) / step));
      for (let j = 1; j < n; ++j) {
        const x = x0 + (x1 - x0) * j / n, y = y0 + (y1 - y0) * j / n;
        out.push(x, y, hf.height(x, y) + lift);
      }
    }
    out.push(x1, y1, hf.height(x1, y1) + lift);
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(out, 3));
  return new THREE.Line(g, material);
}

export function buildRoute(task, pair, hf, goalRadius = task.goal_radius_m) {
  const group = new THREE.Group();
  group.name = 'route';
  const step = Math.max(hf.dx, hf.dy) / 2;
  const lift = 0.25 * task.scale;
  group.add(drapedLine(pair.path_m, hf, lift, step,
                       new THREE.LineBasicMaterial({ color: 0x2f6dff })));
  const ring = [];
  const radius = goalRadius;
  for (let i = 0; i <= 96; ++i) {
    const a = (i / 96) * 2 * Math.PI;
    ring.push([pair.goal_m[0] + radius * Math.cos(a), pair.goal_m[1] + radius * Math.sin(a)]);
  }
  group.add(drapedLine(ring, hf, lift, step, new THREE.LineBasicMaterial({ color: 0xff3030 })));
  const pole = (xy, colour) => {
    const height = 6 * task.scale;
    const m = new THREE.Mesh(new THREE.CylinderGeometry(0.25 * task.scale, 0.25 * task.scale, height, 8),
                             new THREE.MeshBasicMaterial({ color: colour }));
    m.rotation.x = Math.PI / 2;     // cylinder axis along z
    m.position.set(xy[0], xy[1], hf.height(xy[0], xy[1]) + height / 2);
    return m;
  };
  group.add(pole(pair.goal_m, 0xff3030));
  group.add(pole(pair.start_m, 0x30d050));
  return group;
}

// The driven trail: the whole trajectory, drawn up to the current sample (setDrawRange).
export function buildTrail(xs, ys, zs, lift) {
  const n = xs.length;
  const pos = new Float32Array(n * 3);
  for (let i = 0; i < n; ++i) {
    pos[3 * i] = xs[i]; pos[3 * i + 1] = ys[i]; pos[3 * i + 2] = zs[i] + lift;
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  g.setDrawRange(0, 0);
  const line = new THREE.Line(g, new THREE.LineBasicMaterial({ color: 0xff8c1a }));
  line.name = 'trail';
  line.frustumCulled = false;
  return line;
}

// A trail that grows (teleoperation): preallocated, buffers cannot grow.
export class LiveTrail {
  constructor(capacity, lift) {
    this.capacity = capacity;
    this.n = 0;
    this.lift = lift;
    this.pos = new Float32Array(capacity * 3);
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(this.pos, 3));
    g.setDrawRange(0, 0);
    this.line = new THREE.Line(g, new THREE.LineBasicMaterial({ color: 0xff8c1a }));
    this.line.frustumCulled = false;
  }
  clear() { this.n = 0; this.line.geometry.setDrawRange(0, 0); }
  push(x, y, z) {
    if (this.n >= this.capacity) return;
    this.pos.set([x, y, z + this.lift], 3 * this.n);
    this.n += 1;
    const g = this.line.geometry;
    g.attributes.position.needsUpdate = true;
    g.setDrawRange(0, this.n);
  }
}

// The vehicle: body box (the chassis envelope's bounding box), a cab box above it, and the
// wheels at their design positions; front wheels turn with the steering input.
export class VehicleModel {
  constructor(v) {
    this.v = v;
    this.group = new THREE.Group();
    this.group.name = 'vehicle';
    this.group.rotation.order = 'ZYX';   // yaw, then pitch, then roll (intrinsic), as vb's Rpy
    const lo = v.body_min_m, hi = v.body_max_m;
    const body = new THREE.Mesh(
      new THREE.BoxGeometry(hi[0] - lo[0], hi[1] - lo[1], Math.max(0.2, hi[2] - lo[2])),
      new THREE.MeshLambertMaterial({ color: 0xc8b27a }));
    body.position.set((hi[0] + lo[0]) / 2, (hi[1] + lo[1]) / 2, (hi[2] + lo[2]) / 2);
    this.group.add(body);
    const length = hi[0] - lo[0];
    const width = hi[1] - lo[1];
    const cabHeight = 1.6 * v.wheel_radius_m;
    const cab = new THREE.Mesh(new THREE.BoxGeometry(0.6 * length, width, cabHeight),
                               new THREE.MeshLambertMaterial({ color: 0x9c8a5c }));
    cab.position.set(lo[0] + 0.45 * length, 0, hi[2] + cabHeight / 2);
    this.group.add(cab);
    // Marks the front, so that heading is visible from far away.
    const nose = new THREE.Mesh(new THREE.BoxGeometry(0.3, 0.8 * width, 0.3),
                                new THREE.MeshBasicMaterial({ color: 0xff3030 }));
    nose.position.set(hi[0], 0, hi[2] + 0.15);
    this.group.add(nose);
    this.wheels = [];
    const r = v.wheel_radius_m, w = v.wheel_width_m;
    const tyre = new THREE.CylinderGeometry(r, r, w, 20);
    const tyreMaterial = new THREE.MeshLambertMaterial({ color: 0x202020 });
    const hubMaterial = new THREE.MeshLambertMaterial({ color: 0xd0d0d0 });
    for (const axle of v.axles) {
      for (const side of [1, -1]) {
        const knuckle = new THREE.Group();    // turns about z (steering)
        knuckle.position.set(axle.x_m, side * axle.half_track_m, axle.z_m);
        const spin = new THREE.Group();       // turns about y (rolling)
        const t = new THREE.Mesh(tyre, tyreMaterial);  // cylinder axis is y already
        const hub = new THREE.Mesh(new THREE.BoxGeometry(r * 1.2, w * 1.05, r * 0.25), hubMaterial);
        spin.add(t, hub);
        knuckle.add(spin);
        this.group.add(knuckle);
        this.wheels.push({ knuckle, spin, steered: axle.steered });
      }
    }
  }
  // Pose from the trajectory: position of the reference point, roll/pitch/yaw in degrees,
  // steering input [-1, 1], rolled distance (for the wheel spin).
  setPose(x, y, z, rollDeg, pitchDeg, yawDeg, steering, distance) {
    const d = Math.PI / 180;
    this.group.position.set(x, y, z);
    this.group.rotation.set(rollDeg * d, pitchDeg * d, yawDeg * d, 'ZYX');
    const steer = steering * this.v.max_steer_rad;
    const spin = distance / this.v.wheel_radius_m;
    for (const wheel of this.wheels) {
      wheel.knuckle.rotation.z = wheel.steered ? steer : 0;
      wheel.spin.rotation.y = spin;
    }
  }
}

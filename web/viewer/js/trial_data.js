// Parsing and checking a trial's files in the page (docs/viewer.md "Bad input"): the result
// record (JSON) and the trajectory (CSV, docs/reports.md columns), both as the server passes
// them through. Every problem is a TrialError whose message names the file, and the line where
// there is one; the page shows it instead of a half-drawn scene.

export class TrialError extends Error {}

// Columns the viewer needs, in vb_run's order (tools/io/result_io.h WriteTrajectoryCsv).
export const REQUIRED_COLUMNS = [
  't_s', 'x_m', 'y_m', 'z_m', 'vx_mps', 'vy_mps', 'vz_mps', 'speed_mps', 'roll_deg',
  'pitch_deg', 'yaw_deg', 'throttle', 'steering', 'braking', 'gear',
];

export function parseResultJson(text, file) {
  let r;
  try {
    r = JSON.parse(text);
  } catch (e) {
    throw new TrialError(`${file}: not valid JSON (${e.message})`);
  }
  if (r === null || typeof r !== 'object' || Array.isArray(r)) {
    throw new TrialError(`${file}: the record is not a JSON object`);
  }
  for (const key of ['task', 'pair', 'status', 'sim_time_s', 'trajectory_samples']) {
    if (!(key in r)) throw new TrialError(`${file}: key '${key}' is missing`);
  }
  return r;
}

// Columns as Float64Arrays keyed by name; n rows. Strict: every row has every field, every field
// is a finite number, time increases.
export function parseTrajectoryCsv(text, file) {
  const lines = text.split('\n');
  if (lines.length > 0 && lines[lines.length - 1] === '') lines.pop();
  else if (lines.length > 0) {
    throw new TrialError(`${file}:${lines.length}: last line is incomplete (no line end): ` +
                         'the file is truncated');
  }
  if (lines.length === 0) throw new TrialError(`${file}: empty file (no header)`);
  const header = lines[0].split(',');
  for (let i = 0; i < REQUIRED_COLUMNS.length; ++i) {
    if (header[i] !== REQUIRED_COLUMNS[i]) {
      throw new TrialError(`${file}:1: column ${i + 1} is '${header[i] ?? ''}', ` +
                           `expected '${REQUIRED_COLUMNS[i]}'`);
    }
  }
  const n = lines.length - 1;
  const width = header.length;
  const cols = header.map(() => new Float64Array(n));
  for (let row = 0; row < n; ++row) {
    const fields = lines[row + 1].split(',');
    if (fields.length !== width) {
      throw new TrialError(`${file}:${row + 2}: ${fields.length} fields, the header has ${width}` +
                           (row === n - 1 ? ' (the file is truncated)' : ''));
    }
    for (let c = 0; c < width; ++c) {
      const v = Number(fields[c]);
      if (fields[c] === '' || !Number.isFinite(v)) {
        throw new TrialError(`${file}:${row + 2}: column '${header[c]}': '${fields[c]}' is not ` +
                             'a finite number');
      }
      cols[c][row] = v;
    }
    if (row > 0 && !(cols[0][row] > cols[0][row - 1])) {
      throw new TrialError(`${file}:${row + 2}: t_s ${cols[0][row]} does not increase`);
    }
  }
  const byName = {};
  header.forEach((name, c) => { byName[name] = cols[c]; });
  return { n, columns: byName, header };
}

// The whole trial as the page uses it, checked against the scene it is drawn in.
export function loadTrial(bundle) {
  const t = bundle.trial;
  const result = parseResultJson(t.result_json, t.result_file);
  if (t.trajectory_csv === null) {
    throw new TrialError(`${t.trajectory_file}: trajectory missing (${t.trajectory_error})`);
  }
  const traj = parseTrajectoryCsv(t.trajectory_csv, t.trajectory_file);
  if (traj.n !== result.trajectory_samples) {
    throw new TrialError(`${t.trajectory_file}: ${traj.n} samples, but ${t.result_file} ` +
                         `records ${result.trajectory_samples}: the trajectory is truncated or ` +
                         'belongs to another run');
  }
  if (traj.n < 2) throw new TrialError(`${t.trajectory_file}: fewer than 2 samples to replay`);
  const task = bundle.task;
  if (result.task !== task.name) {
    throw new TrialError(`${t.result_file}: trial of task '${result.task}', but the task ` +
                         `loaded is '${task.name}' (${task.file})`);
  }
  const pair = task.pairs[result.pair];
  if (pair === undefined) {
    throw new TrialError(`${t.result_file}: pair ${result.pair} is not in task ${task.file}`);
  }
  // The vehicle is dropped at the pair's start: a trajectory that begins elsewhere was driven in
  // another world or from another pair.
  const x0 = traj.columns.x_m[0], y0 = traj.columns.y_m[0];
  const d = Math.hypot(x0 - pair.start_m[0], y0 - pair.start_m[1]);
  const tolerance = 3.0 * task.scale;
  if (d > tolerance) {
    throw new TrialError(`${t.trajectory_file}:2: the trajectory starts at (${x0.toFixed(2)}, ` +
                         `${y0.toFixed(2)}), ${d.toFixed(1)} m from pair ${result.pair}'s start ` +
                         `(${pair.start_m[0]}, ${pair.start_m[1]}) in ${task.file}: the task ` +
                         'does not match the trial');
  }
  return { result, traj, pair };
}

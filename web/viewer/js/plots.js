// Time-series plots with a cursor in sync with playback: the series is drawn once into an
// offscreen canvas (every sample: pointCount is what the tests check), the cursor each frame.
// Clicking or dragging on a plot seeks.

export class Plot {
  constructor(parent, label, unit, colour, onSeek) {
    this.label = label;
    this.unit = unit;
    this.colour = colour;
    this.div = document.createElement('div');
    this.div.className = 'plot';
    this.caption = document.createElement('div');
    this.caption.className = 'label';
    this.canvas = document.createElement('canvas');
    this.div.append(this.caption, this.canvas);
    parent.append(this.div);
    this.t = new Float64Array(0);
    this.y = new Float64Array(0);
    this.n = 0;
    this.pointCount = 0;
    this.cursor = 0;
    this.tMax = 1;
    this.background = null;
    const seek = (ev) => {
      if (!onSeek || (ev.type !== 'click' && !(ev.buttons & 1))) return;
      const rect = this.canvas.getBoundingClientRect();
      onSeek(((ev.clientX - rect.left) / rect.width) * this.tMax);
    };
    this.canvas.addEventListener('click', seek);
    this.canvas.addEventListener('pointermove', seek);
  }

  // Whole series (replay). t and y are shared, not copied.
  setData(t, y, n = t.length, tMax = t[n - 1]) {
    this.t = t;
    this.y = y;
    this.n = n;
    this.tMax = Math.max(tMax, 1e-9);
    this.background = null;
  }

  render(cursorT) {
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(50, Math.round(this.canvas.clientWidth * dpr));
    const h = Math.max(30, Math.round(this.canvas.clientHeight * dpr));
    if (this.canvas.width !== w || this.canvas.height !== h) {
      this.canvas.width = w;
      this.canvas.height = h;
      this.background = null;
    }
    if (this.background === null) this.background = this.drawSeries(w, h);
    const ctx = this.canvas.getContext('2d');
    ctx.clearRect(0, 0, w, h);
    ctx.drawImage(this.background, 0, 0);
    const x = (cursorT / this.tMax) * w;
    ctx.strokeStyle = '#ffffff';
    ctx.lineWidth = 1;
    ctx.beginPath();
    ctx.moveTo(x, 0);
    ctx.lineTo(x, h);
    ctx.stroke();
    const v = this.valueAt(cursorT);
    this.caption.textContent = `${this.label}: ${Number.isFinite(v) ? v.toFixed(2) : '-'} ${this.unit}` +
      `  [${this.lo.toFixed(2)}, ${this.hi.toFixed(2)}]`;
  }

  valueAt(t) {
    if (this.n === 0) return NaN;
    let lo = 0, hi = this.n - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (this.t[mid] <= t) lo = mid; else hi = mid - 1;
    }
    return this.y[lo];
  }

  drawSeries(w, h) {
    const off = document.createElement('canvas');
    off.width = w;
    off.height = h;
    const ctx = off.getContext('2d');
    let lo = Infinity, hi = -Infinity;
    for (let i = 0; i < this.n; ++i) {
      lo = Math.min(lo, this.y[i]);
      hi = Math.max(hi, this.y[i]);
    }
    if (!(hi > lo)) { lo = (Number.isFinite(lo) ? lo : 0) - 1; hi = lo + 2; }
    const pad = 0.08 * (hi - lo);
    this.lo = lo; this.hi = hi;
    lo -= pad; hi += pad;
    const px = (t) => (t / this.tMax) * w;
    const py = (v) => h - ((v - lo) / (hi - lo)) * h;
    if (lo < 0 && hi > 0) {
      ctx.strokeStyle = '#3a4048';
      ctx.beginPath();
      ctx.moveTo(0, py(0));
      ctx.lineTo(w, py(0));
      ctx.stroke();
    }
    ctx.strokeStyle = this.colour;
    ctx.lineWidth = Math.max(1, (window.devicePixelRatio || 1));
    ctx.beginPath();
    let count = 0;
    for (let i = 0; i < this.n; ++i) {
      if (i === 0) ctx.moveTo(px(this.t[i]), py(this.y[i]));
      else ctx.lineTo(px(this.t[i]), py(this.y[i]));
      ++count;
    }
    ctx.stroke();
    this.pointCount = count;
    return off;
  }
}

// The five plots of a trial: speed, roll, pitch, throttle, steering.
export const PLOT_SERIES = [
  { key: 'speed_mps', label: 'speed', unit: 'm/s', colour: '#7cc4ff' },
  { key: 'roll_deg', label: 'roll', unit: '°', colour: '#ffb454' },
  { key: 'pitch_deg', label: 'pitch', unit: '°', colour: '#c792ea' },
  { key: 'throttle', label: 'throttle', unit: '', colour: '#8bd17c' },
  { key: 'steering', label: 'steering (+ left)', unit: '', colour: '#ff7a90' },
];

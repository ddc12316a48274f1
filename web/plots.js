// Small 2-D plots on canvases for the dynamics panel: axes with ticks, labels and units, lines,
// envelopes (bands between a low and a high curve), horizontal and vertical reference lines and
// labelled markers. Linear or log-10 axes. No library: the page loads nothing from the network.

const FONT = '11px system-ui, -apple-system, "Segoe UI", Roboto, sans-serif';
const INK = '#1d2330';
const MUTED = '#667085';
const GRID = '#eef0f3';

/** Sizes `canvas` to its CSS width × `aspect` at the device pixel ratio; returns its 2-D context
 * scaled to CSS pixels, with the CSS width and height. */
export function prepare(canvas, aspect = 0.62) {
  const dpr = Math.max(1, window.devicePixelRatio || 1);
  const w = Math.max(200, Math.round(canvas.getBoundingClientRect().width) || 360);
  const h = Math.round(w * aspect);
  canvas.width = Math.round(w * dpr);
  canvas.height = Math.round(h * dpr);
  canvas.style.height = `${h}px`;
  const ctx = canvas.getContext('2d');
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.fillStyle = '#fff';
  ctx.fillRect(0, 0, w, h);
  return { ctx, width: w, height: h };
}

/** A tick label: few digits, no trailing zeros. */
export function tickText(v) {
  if (v === 0) return '0';
  const a = Math.abs(v);
  if (a >= 1e5 || a < 1e-3) return v.toExponential(0).replace('e+', 'e');
  return String(Number(v.toPrecision(4)));
}

/** About `n` round ticks covering [lo, hi]. */
function linearTicks(lo, hi, n = 5) {
  const raw = (hi - lo) / n;
  const mag = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 2.5, 5, 10].map((m) => m * mag).find((s) => s >= raw) || 10 * mag;
  const ticks = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) ticks.push(Math.abs(v) < step * 1e-9 ? 0 : v);
  return ticks;
}

/** Decades in [lo, hi] (lo > 0). */
function logTicks(lo, hi) {
  const ticks = [];
  for (let e = Math.ceil(Math.log10(lo) - 1e-9); e <= Math.floor(Math.log10(hi) + 1e-9); e++) ticks.push(10 ** e);
  return ticks;
}

/** An axis's range from `values` (finite ones; > 0 on a log axis), padded a little. */
function range(values, log, floorRatio, headroom = 1) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const v of values) {
    if (!Number.isFinite(v) || (log && v <= 0)) continue;
    lo = Math.min(lo, v);
    hi = Math.max(hi, v);
  }
  if (!(lo <= hi)) return log ? [1e-3, 1] : [0, 1];
  if (log) {
    if (floorRatio) lo = Math.max(lo, hi / floorRatio);
    if (hi / lo < 10) [lo, hi] = [lo / 2, hi * 2];
    hi *= headroom;
    return [10 ** Math.floor(Math.log10(lo)), 10 ** Math.ceil(Math.log10(hi))];
  }
  if (hi === lo) return [lo - (Math.abs(lo) || 1) * 0.5, hi + (Math.abs(hi) || 1) * 0.5];
  const pad = (hi - lo) * 0.05;
  return [lo - pad, hi + pad];
}

/**
 * Draws one plot in the rectangle `box` ({x, y, w, h}, CSS pixels) of `ctx`.
 * `spec.x`, `spec.y`: {label, unit, log?, min?, max?, floorRatio?, headroom?} (a log axis
 * spans at most `floorRatio` below its highest value, and reaches at least `headroom` times
 * above it, room for labels). `spec.series`: a list of
 * {type: 'line', x, y, colour, label, dash?}, {type: 'band', x, lo, hi, colour, label},
 * {type: 'hline', y, colour, label}, {type: 'vline', x, colour, label} and
 * {type: 'markers', x, y, labels, colour}. A legend of the labelled series goes top right.
 */
export function drawPlot(ctx, box, spec) {
  const left = box.x + 52;
  const right = box.x + box.w - 10;
  const top = box.y + 8;
  const bottom = box.y + box.h - 34;
  const xs = [];
  const ys = [];
  for (const s of spec.series) {
    if (s.type === 'line' || s.type === 'markers') {
      xs.push(...s.x);
      ys.push(...s.y);
    } else if (s.type === 'band') {
      xs.push(...s.x);
      ys.push(...s.lo, ...s.hi);
    } else if (s.type === 'hline') {
      ys.push(s.y);
    } else if (s.type === 'vline') {
      xs.push(s.x);
    }
  }
  let [x0, x1] = range(xs, spec.x.log);
  let [y0, y1] = range(ys, spec.y.log, spec.y.floorRatio, spec.y.headroom);
  if (spec.x.min !== undefined) x0 = spec.x.min;
  if (spec.x.max !== undefined) x1 = spec.x.max;
  if (spec.y.min !== undefined) y0 = spec.y.min;
  if (spec.y.max !== undefined) y1 = spec.y.max;
  const map = (v, a, b, p, q, log) => {
    const t = log ? (Math.log10(v) - Math.log10(a)) / (Math.log10(b) - Math.log10(a)) : (v - a) / (b - a);
    return p + t * (q - p);
  };
  const px = (v) => map(v, x0, x1, left, right, spec.x.log);
  const py = (v) => map(spec.y.log ? Math.max(v, y0) : v, y0, y1, bottom, top, spec.y.log);

  ctx.save();
  ctx.font = FONT;
  // Grid, ticks and their labels.
  ctx.strokeStyle = GRID;
  ctx.fillStyle = MUTED;
  ctx.lineWidth = 1;
  ctx.textAlign = 'center';
  ctx.textBaseline = 'top';
  for (const v of spec.x.log ? logTicks(x0, x1) : linearTicks(x0, x1)) {
    const x = Math.round(px(v)) + 0.5;
    ctx.beginPath();
    ctx.moveTo(x, top);
    ctx.lineTo(x, bottom);
    ctx.stroke();
    ctx.fillText(tickText(v), x, bottom + 3);
  }
  ctx.textAlign = 'right';
  ctx.textBaseline = 'middle';
  for (const v of spec.y.log ? logTicks(y0, y1) : linearTicks(y0, y1, 4)) {
    const y = Math.round(py(v)) + 0.5;
    ctx.beginPath();
    ctx.moveTo(left, y);
    ctx.lineTo(right, y);
    ctx.stroke();
    ctx.fillText(tickText(v), left - 4, y);
  }
  // Axis titles with units.
  ctx.fillStyle = INK;
  ctx.textAlign = 'center';
  ctx.textBaseline = 'bottom';
  ctx.fillText(`${spec.x.label} (${spec.x.unit})`, (left + right) / 2, box.y + box.h - 2);
  ctx.save();
  ctx.translate(box.x + 11, (top + bottom) / 2);
  ctx.rotate(-Math.PI / 2);
  ctx.textBaseline = 'middle';
  ctx.fillText(`${spec.y.label} (${spec.y.unit})`, 0, 0);
  ctx.restore();

  // The series, clipped to the plot area.
  ctx.save();
  ctx.beginPath();
  ctx.rect(left, top, right - left, bottom - top);
  ctx.clip();
  for (const s of spec.series) {
    ctx.strokeStyle = s.colour;
    ctx.fillStyle = s.colour;
    ctx.lineWidth = s.width || 1.5;
    ctx.setLineDash(s.dash || []);
    if (s.type === 'line') {
      ctx.beginPath();
      let pen = false;
      s.x.forEach((x, i) => {
        const y = s.y[i];
        if (!Number.isFinite(x) || !Number.isFinite(y) || (spec.y.log && y <= 0)) {
          pen = false;
          return;
        }
        if (pen) ctx.lineTo(px(x), py(y));
        else ctx.moveTo(px(x), py(y));
        pen = true;
      });
      ctx.stroke();
    } else if (s.type === 'band') {
      // One bar from the lowest to the highest value per run, as wide as the step to the next
      // run: an envelope however fast the channel swings inside a run.
      s.x.forEach((x, i) => {
        const u = px(x);
        const next = i + 1 < s.x.length ? px(s.x[i + 1]) : u;
        const [a, b] = [py(s.hi[i]), py(s.lo[i])];
        if (!Number.isFinite(a) || !Number.isFinite(b)) return;
        const w = Math.max(1, Math.abs(next - u));
        const h = Math.max(1.5, b - a);
        ctx.fillRect(Math.min(u, next), (a + b) / 2 - h / 2, w, h);
      });
    } else if (s.type === 'hline') {
      const y = Math.round(py(s.y)) + 0.5;
      ctx.beginPath();
      ctx.moveTo(left, y);
      ctx.lineTo(right, y);
      ctx.stroke();
    } else if (s.type === 'vline') {
      const x = Math.round(px(s.x)) + 0.5;
      ctx.beginPath();
      ctx.moveTo(x, top);
      ctx.lineTo(x, bottom);
      ctx.stroke();
    }
  }
  ctx.setLineDash([]);
  // Markers last, each labelled (once per text) where its label covers no other marker or
  // label.
  ctx.textAlign = 'left';
  ctx.textBaseline = 'bottom';
  for (const s of spec.series.filter((m) => m.type === 'markers')) {
    // Boxes [left, top, right, bottom] of the markers, then of the labels placed.
    const placed = s.x.map((x, i) => [px(x) - 3, py(s.y[i]) - 3, px(x) + 3, py(s.y[i]) + 3]);
    const hits = (box, j) => box[0] < placed[j][2] + 1 && placed[j][0] < box[2] + 1 && box[1] < placed[j][3] && placed[j][1] < box[3];
    const texts = new Set();
    ctx.fillStyle = s.colour;
    s.x.forEach((x, i) => {
      const [u, v] = [px(x), py(s.y[i])];
      ctx.beginPath();
      ctx.arc(u, v, 3, 0, 2 * Math.PI);
      ctx.fill();
      const text = s.labels[i];
      if (texts.has(text)) return;
      const w = ctx.measureText(text).width;
      // Above the marker, else right of it, left of it, below it.
      const spots = [[u - w / 2, v - 6], [u + 5, v - 2], [u - 5 - w, v - 2], [u + 5, v + 14]]
        .map(([sx, sy]) => [Math.max(left + 2, Math.min(sx, right - w - 2)), Math.max(top + 12, Math.min(sy, bottom - 2))]);
      const free = spots.map(([tx, ty]) => [tx, ty - 11, tx + w, ty]).find((box) => !placed.some((_, j) => j !== i && hits(box, j)));
      if (!free) return;
      placed.push(free);
      texts.add(text);
      ctx.fillText(text, free[0], free[3]);
    });
  }
  ctx.restore();

  // Frame and legend.
  ctx.strokeStyle = '#c5ccd6';
  ctx.strokeRect(left + 0.5, top + 0.5, right - left - 1, bottom - top - 1);
  const legend = spec.series.filter((s) => s.label && s.type !== 'markers');
  ctx.textAlign = 'right';
  ctx.textBaseline = 'middle';
  legend.forEach((s, i) => {
    const y = top + 9 + 13 * i;
    const w = ctx.measureText(s.label).width;
    ctx.fillStyle = 'rgba(255, 255, 255, 0.8)';
    ctx.fillRect(right - w - 30, y - 6, w + 28, 13);
    ctx.strokeStyle = s.colour;
    ctx.fillStyle = s.colour;
    ctx.lineWidth = s.type === 'band' ? 6 : 2;
    ctx.setLineDash(s.dash || []);
    ctx.beginPath();
    ctx.moveTo(right - w - 26, y);
    ctx.lineTo(right - w - 10, y);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.fillStyle = INK;
    ctx.fillText(s.label, right - 4, y);
  });
  ctx.restore();
}

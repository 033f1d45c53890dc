// draw.js: one frame of a decoded recording on a 2D canvas, in the view's transform
// (screen x = ox + s * x, screen y = oy - s * y, in CSS pixels of the canvas).
"use strict";

RV.TRAILS = 64;          // bodies that get a trail (the chosen one always does)
RV.ARROW_S = 0.25;       // a velocity arrow is 0.25 s of motion
RV.BG = "#f7f7f4";

RV.css = function (rgba, alpha, dark) {
  const r = (rgba >>> 24) & 255, g = (rgba >>> 16) & 255, b = (rgba >>> 8) & 255;
  const a = alpha !== undefined ? alpha : (rgba & 255) / 255, f = dark ? 0.55 : 1;
  return "rgba(" + Math.round(r * f) + "," + Math.round(g * f) + "," + Math.round(b * f) + "," + a + ")";
};

// The view that fits the world box into w x h pixels with a margin.
RV.fit = function (world, w, h) {
  const wx = Math.max(world[2] - world[0], 1e-3), wy = Math.max(world[3] - world[1], 1e-3);
  const s = Math.min(w / (wx * 1.08), h / (wy * 1.08));
  return { s: s, ox: w / 2 - s * (world[0] + world[2]) / 2, oy: h / 2 + s * (world[1] + world[3]) / 2 };
};

function niceStep(span) {
  const raw = span / 10, p = Math.pow(10, Math.floor(Math.log10(raw))), m = raw / p;
  return p * (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10);
}

function label(g, step) {
  return Math.abs(g) < step * 1e-6 ? "0" : +g.toPrecision(6) + "";
}

// Grid lines (CSS pixel position, colour) a nice step apart, and their labels.
function gridLines(v, w, h) {
  const x0 = -v.ox / v.s, x1 = (w - v.ox) / v.s, y1 = v.oy / v.s, y0 = (v.oy - h) / v.s;
  const step = niceStep(Math.max(x1 - x0, y1 - y0)), g = { x: [], y: [], labels: [] };
  for (let gx = Math.ceil(x0 / step) * step; gx <= x1; gx += step) {
    const px = Math.round(v.ox + gx * v.s) + 0.5;
    g.x.push([px, Math.abs(gx) < step / 2 ? 0xc4c4bcff : 0xe6e6e0ff]);
    if (px < w - 40) g.labels.push([label(gx, step), px + 3, h - 4]);
  }
  for (let gy = Math.ceil(y0 / step) * step; gy <= y1; gy += step) {
    const py = Math.round(v.oy - gy * v.s) + 0.5;
    g.y.push([py, Math.abs(gy) < step / 2 ? 0xc4c4bcff : 0xe6e6e0ff]);
    g.labels.push([label(gy, step), 3, py - 3]);
  }
  g.labels.push(["m", w - 12, h - 4]);
  return g;
}

function drawGrid(ctx, g, w, h) {
  ctx.lineWidth = 1;
  for (const l of g.x) {
    ctx.strokeStyle = RV.css(l[1]);
    ctx.beginPath(); ctx.moveTo(l[0], 0); ctx.lineTo(l[0], h); ctx.stroke();
  }
  for (const l of g.y) {
    ctx.strokeStyle = RV.css(l[1]);
    ctx.beginPath(); ctx.moveTo(0, l[0]); ctx.lineTo(w, l[0]); ctx.stroke();
  }
}

function gridLabels(ctx, g) {
  ctx.font = "11px sans-serif";
  ctx.fillStyle = "#8a8a84";
  for (const l of g.labels) ctx.fillText(l[0], l[1], l[2]);
}

// The tracks that get trails: the chosen one, then named moving bodies, then the others in
// creation order, RV.TRAILS in all.
RV.trailTracks = function (rec, chosen) {
  const out = [], moving = rec.tracks.filter(function (t) { return t.type !== 0 && t.first >= 0; });
  if (chosen) out.push(chosen);
  for (const pass of [true, false])
    for (const t of moving)
      if (out.length < RV.TRAILS && (t.name !== null) === pass && out.indexOf(t) < 0) out.push(t);
  return out;
};

function drawTrails(ctx, rec, k, v, tracks) {
  ctx.lineWidth = 1.5;
  for (const t of tracks) {
    if (k < t.first) continue;
    const end = Math.min(k, t.last) - t.first, stride = Math.max(1, Math.ceil(end / 600));
    const col = t.col.at(Math.min(k, t.last));
    ctx.strokeStyle = col >= 0 ? RV.css(RV.meta.colors[col][0], 0.45) : "rgba(60,60,60,0.45)";
    ctx.beginPath();
    let pen = false;
    for (let i = 0; ; i = Math.min(i + stride, end)) {   // every stride-th, and the last
      const x = t.x[i];
      if (x !== x) {
        pen = false;
      } else {
        const px = v.ox + x * v.s, py = v.oy - t.y[i] * v.s;
        if (pen) ctx.lineTo(px, py); else ctx.moveTo(px, py);
        pen = true;
      }
      if (i >= end) break;
    }
    ctx.stroke();
  }
}

// Bodies of frame k as one path per colour; returns the number drawn.
function drawBodies(ctx, rec, k, v, w, h) {
  const colors = RV.meta.colors, buckets = [];
  for (let c = 0; c < colors.length; c++) buckets.push([]);
  const points = [];
  for (const t of rec.tracks) {
    if (k < t.first || k > t.last) continue;
    const i = k - t.first, x = t.x[i];
    if (x !== x) continue;
    const px = v.ox + x * v.s, py = v.oy - t.y[i] * v.s;
    const col = t.col.at(k);
    if (t.shape === 0) { points.push(px, py, col); continue; }
    const sz = t.size.at(k), hx = sz[0] * v.s, hy = sz[1] * v.s;
    if (px + hx < 0 || px - hx > w || py + hy < 0 || py - hy > h) continue;
    buckets[col].push(t.shape, px, py, hx, hy);
  }
  let drawn = points.length / 3;
  for (let c = 0; c < buckets.length; c++) {
    const b = buckets[c];
    if (!b.length) continue;
    ctx.beginPath();
    let small = 0;
    for (let j = 0; j < b.length; j += 5) {
      const px = b[j + 1], py = b[j + 2], hx = Math.max(b[j + 3], 0.6), hy = Math.max(b[j + 4], 0.6);
      if (b[j] === 1) {
        ctx.moveTo(px + hx, py);
        ctx.arc(px, py, hx, 0, 2 * Math.PI);
      } else {
        ctx.rect(px - hx, py - hy, 2 * hx, 2 * hy);
      }
      if (Math.min(hx, hy) < 3) small++;
    }
    ctx.fillStyle = RV.css(colors[c][0]);
    ctx.fill();
    if (small < b.length / 10) {   /* outlines only where bodies are big enough to show them */
      ctx.lineWidth = 1;
      ctx.strokeStyle = RV.css(colors[c][0], 0.9, true);
      ctx.stroke();
    }
    drawn += b.length / 5;
  }
  for (let j = 0; j < points.length; j += 3) {   /* bodies without a shape: a ring and a dot */
    const css = points[j + 2] >= 0 ? RV.css(colors[points[j + 2]][0], 1, true) : "#333";
    ctx.beginPath();
    ctx.arc(points[j], points[j + 1], 4, 0, 2 * Math.PI);
    ctx.lineWidth = 1.5;
    ctx.strokeStyle = css;
    ctx.stroke();
    ctx.fillStyle = css;
    ctx.fillRect(points[j] - 1, points[j + 1] - 1, 2, 2);
  }
  return drawn;
}

function drawBounds(ctx, rec, k, v) {
  ctx.lineWidth = 1;
  let style = null;
  ctx.beginPath();
  for (const t of rec.tracks) {
    if (k < t.first || k > t.last) continue;
    const b = t.box.at(k);
    if (!b) continue;
    if (style === null) style = t.col.at(k);
    ctx.rect(v.ox + b[0] * v.s, v.oy - b[3] * v.s, (b[2] - b[0]) * v.s, (b[3] - b[1]) * v.s);
  }
  const seen = RV.meta.colors.findIndex(function (c) { return c[1] & 32; });
  ctx.strokeStyle = seen >= 0 ? RV.css(RV.meta.colors[seen][0], 0.6) : "rgba(40,150,40,0.6)";
  ctx.stroke();
}

// A free list (contacts, springs): points as small squares, the rest as one stroked path
// per colour.
function drawList(ctx, list, v, qc) {
  const colors = RV.meta.colors, paths = new Map();
  for (let o = 0; o < list.length; o += RV.PRIM) {
    const kind = list[o], col = list[o + 1];
    const x0 = v.ox + list[o + 2] * qc * v.s, y0 = v.oy - list[o + 3] * qc * v.s;
    if (kind === 0) {
      ctx.fillStyle = RV.css(colors[col][0]);
      ctx.fillRect(x0 - 2, y0 - 2, 4, 4);
      continue;
    }
    if (!paths.has(col)) paths.set(col, new Path2D());
    const p = paths.get(col);
    if (kind === 1) {
      p.moveTo(x0, y0);
      p.lineTo(v.ox + list[o + 4] * qc * v.s, v.oy - list[o + 5] * qc * v.s);
    } else if (kind === 3) {
      const x1 = v.ox + list[o + 4] * qc * v.s, y1 = v.oy - list[o + 5] * qc * v.s;
      p.rect(x0, y1, x1 - x0, y0 - y1);
    } else {
      const r = Math.max(list[o + 4] * qc * v.s, 1);
      p.moveTo(x0 + r, y0);
      p.arc(x0, y0, r, 0, 2 * Math.PI);
    }
  }
  ctx.lineWidth = 1.5;
  paths.forEach(function (p, col) {
    ctx.strokeStyle = RV.css(colors[col][0]);
    ctx.stroke(p);
  });
}

RV.VELOCITY = 0x28a03cff;   // RG_COLOR_VELOCITY, the arrows' colour in the SVG pictures too

function drawVelocities(ctx, rec, k, v) {
  ctx.strokeStyle = ctx.fillStyle = RV.css(RV.VELOCITY);
  ctx.lineWidth = 1.2;
  for (const t of rec.tracks) {
    if (t.type === 0 || k < t.first || k > t.last) continue;
    const i = k - t.first, x = t.x[i];
    if (x !== x) continue;
    const vx = t.vx[i], vy = t.vy[i], sp = Math.hypot(vx, vy);
    let len = sp * RV.ARROW_S * v.s;
    if (len < 4) continue;
    if (len > 150) len = 150;
    const ux = vx / sp, uy = -vy / sp, px = v.ox + x * v.s, py = v.oy - t.y[i] * v.s;
    const ex = px + ux * len, ey = py + uy * len;
    ctx.beginPath();
    ctx.moveTo(px, py);
    ctx.lineTo(ex, ey);
    ctx.stroke();
    ctx.beginPath();
    ctx.moveTo(ex, ey);
    ctx.lineTo(ex - 7 * ux + 3 * uy, ey - 7 * uy - 3 * ux);
    ctx.lineTo(ex - 7 * ux - 3 * uy, ey - 7 * uy + 3 * ux);
    ctx.fill();
  }
}

// Names beside their bodies, skipping any that would overlap a name already placed.
function drawNames(ctx, rec, k, v, w, h) {
  const placed = [];
  ctx.font = "12px sans-serif";
  ctx.fillStyle = "#111";
  for (const t of rec.tracks) {
    if (t.name === null || k < t.first || k > t.last || placed.length >= 80) continue;
    const i = k - t.first, x = t.x[i];
    if (x !== x) continue;
    const sz = t.size.at(k), tw = ctx.measureText(t.name).width, py = v.oy - (t.y[i] + sz[1]) * v.s - 3;
    let px = v.ox + (x + sz[0]) * v.s + 3;
    if (px + tw > w) px = v.ox + (x - sz[0]) * v.s - 3 - tw;   // left of the body at the right edge
    if (px > w || py < 0 || px + tw < 0 || py - 12 > h) continue;
    if (placed.some(function (r) { return px < r[2] && px + tw > r[0] && py - 11 < r[3] && py > r[1]; })) continue;
    placed.push([px, py - 11, px + tw, py]);
    ctx.fillText(t.name, px, py);
  }
}

// Bodies alive at frame k (an upper bound of those in view).
function aliveAt(rec, k) {
  let n = 0;
  for (const t of rec.tracks) if (k >= t.first && k <= t.last) n++;
  return n;
}

// Draws frame k: what the toggles in `show` ask for, rasterised when crowded (raster.js).
RV.drawFrame = function (ctx, rec, k, v, w, h, dpr, show, chosen) {
  const g = gridLines(v, w, h), lists = RV.listsAt(rec, k);
  const fast = aliveAt(rec, k) >= RV.RASTER_MIN;
  if (fast) {
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    RV.rasterFrame(ctx, rec, k, v, w, h, dpr, show, lists, RV.meta.qc, g);
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  } else {
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.fillStyle = RV.BG;
    ctx.fillRect(0, 0, w, h);
    drawGrid(ctx, g, w, h);
  }
  gridLabels(ctx, g);
  if (show.trails) drawTrails(ctx, rec, k, v, RV.trailTracks(rec, chosen));
  if (!fast) {
    drawBodies(ctx, rec, k, v, w, h);
    if (show.bounds) drawBounds(ctx, rec, k, v);
    drawList(ctx, lists[1], v, RV.meta.qc);   // springs, always
    if (show.contacts) drawList(ctx, lists[0], v, RV.meta.qc);
  }
  if (show.velocities) drawVelocities(ctx, rec, k, v);
  if (chosen && k >= chosen.first && k <= chosen.last && chosen.x[k - chosen.first] === chosen.x[k - chosen.first]) {
    const i = k - chosen.first, sz = chosen.size.at(k);
    const px = v.ox + chosen.x[i] * v.s, py = v.oy - chosen.y[i] * v.s;
    const hx = Math.max(sz[0] * v.s, 4) + 3, hy = Math.max(sz[1] * v.s, 4) + 3;
    ctx.setLineDash([4, 3]);
    ctx.strokeStyle = "#000";
    ctx.lineWidth = 1;
    ctx.strokeRect(px - hx, py - hy, 2 * hx, 2 * hy);
    ctx.setLineDash([]);
  }
  if (show.names) drawNames(ctx, rec, k, v, w, h);
  return fast;
};

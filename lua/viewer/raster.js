// raster.js: the fast path for crowded frames.  The background, grid lines, bodies, fat
// boxes and contacts are written straight into an ImageData (no anti-aliasing: a filled
// span per pixel row, a darker rim), which software canvases draw far faster than
// thousands of anti-aliased paths; draw.js puts the rest (trails, arrows, names) on top.
"use strict";

RV.RASTER_MIN = 600;     // bodies in view from which frames are rasterised

// 0xRRGGBBAA to the little-endian ImageData word 0xAABBGGRR, and the darker rim's.
function word(rgba, dark) {
  const f = dark ? 0.55 : 1;
  const r = Math.round(((rgba >>> 24) & 255) * f), g = Math.round(((rgba >>> 16) & 255) * f);
  const b = Math.round(((rgba >>> 8) & 255) * f);
  return ((rgba & 255) << 24 | b << 16 | g << 8 | r) >>> 0;
}

function Raster(w, h) {
  this.w = w;
  this.h = h;
  this.img = new ImageData(w, h);
  this.buf = new Uint32Array(this.img.data.buffer);
}

// One pixel of colour c (a word); alpha below 255 blends over what is there.
Raster.prototype.put = function (o, c) {
  const a = c >>> 24;
  if (a === 255) { this.buf[o] = c; return; }
  const d = this.buf[o], t = a / 255, u = 1 - t;
  const r = (c & 255) * t + (d & 255) * u, g = ((c >>> 8) & 255) * t + ((d >>> 8) & 255) * u;
  const b = ((c >>> 16) & 255) * t + ((d >>> 16) & 255) * u;
  this.buf[o] = (0xff000000 | (b & 255) << 16 | (g & 255) << 8 | (r & 255)) >>> 0;
};

Raster.prototype.span = function (y, x0, x1, c) {
  if (y < 0 || y >= this.h) return;
  x0 = Math.max(0, x0);
  x1 = Math.min(this.w, x1);
  const o = y * this.w;
  if (c >>> 24 === 255) { if (x1 > x0) this.buf.fill(c, o + x0, o + x1); return; }
  for (let x = x0; x < x1; x++) this.put(o + x, c);
};

Raster.prototype.pixel = function (x, y, c) {
  if (x >= 0 && y >= 0 && x < this.w && y < this.h) this.put(y * this.w + x, c);
};

// A filled circle (centre and radius in pixels), with a rim when it is big enough.
Raster.prototype.circle = function (cx, cy, r, c, rim) {
  const y0 = Math.ceil(cy - r - 0.5), y1 = Math.floor(cy + r - 0.5), ring = r >= 3;
  for (let y = y0; y <= y1; y++) {
    const dy = y + 0.5 - cy, half = Math.sqrt(Math.max(0, r * r - dy * dy));
    const x0 = Math.round(cx - half), x1 = Math.round(cx + half);
    if (ring && (y === y0 || y === y1)) { this.span(y, x0, x1, rim); continue; }
    this.span(y, x0, x1, c);
    if (ring && x1 > x0) { this.pixel(x0, y, rim); this.pixel(x1 - 1, y, rim); }
  }
};

Raster.prototype.box = function (x0, y0, x1, y1, c, rim) {
  x0 = Math.round(x0); x1 = Math.max(Math.round(x1), x0 + 1);
  y0 = Math.round(y0); y1 = Math.max(Math.round(y1), y0 + 1);
  const ring = x1 - x0 >= 6 && y1 - y0 >= 6;
  for (let y = y0; y < y1; y++) {
    if (ring && (y === y0 || y === y1 - 1)) { this.span(y, x0, x1, rim); continue; }
    this.span(y, x0, x1, c);
    if (ring) { this.pixel(x0, y, rim); this.pixel(x1 - 1, y, rim); }
  }
};

Raster.prototype.outline = function (x0, y0, x1, y1, c) {
  x0 = Math.round(x0); x1 = Math.round(x1); y0 = Math.round(y0); y1 = Math.round(y1);
  this.span(y0, x0, x1 + 1, c);
  this.span(y1, x0, x1 + 1, c);
  for (let y = y0 + 1; y < y1; y++) { this.pixel(x0, y, c); this.pixel(x1, y, c); }
};

Raster.prototype.line = function (x0, y0, x1, y1, c) {
  const n = Math.min(Math.ceil(Math.max(Math.abs(x1 - x0), Math.abs(y1 - y0))), 4096);
  for (let i = 0; i <= n; i++) {
    const t = n ? i / n : 0;
    this.pixel(Math.floor(x0 + (x1 - x0) * t), Math.floor(y0 + (y1 - y0) * t), c);
  }
};

let raster = null;

// Rasterises frame k into ctx's canvas (size in device pixels, dpr per CSS pixel).
RV.rasterFrame = function (ctx, rec, k, v, w, h, dpr, show, lists, qc, gridSteps) {
  const W = Math.round(w * dpr), Hh = Math.round(h * dpr), s = v.s * dpr, ox = v.ox * dpr, oy = v.oy * dpr;
  if (!raster || raster.w !== W || raster.h !== Hh) raster = new Raster(W, Hh);
  const R = raster, colors = RV.meta.colors;
  R.buf.fill(word(0xf7f7f4ff));
  for (const g of gridSteps.x) R.line(Math.floor(g[0] * dpr), 0, Math.floor(g[0] * dpr), Hh - 1, word(g[1]));
  for (const g of gridSteps.y) R.span(Math.floor(g[0] * dpr), 0, W, word(g[1]));
  const fill = colors.map(function (c) { return word(c[0]); });
  const rim = colors.map(function (c) { return word(c[0], true); });
  const shapeless = word(0x333333ff);
  for (const t of rec.tracks) {
    if (k < t.first || k > t.last) continue;
    const i = k - t.first, x = t.x[i];
    if (x !== x) continue;
    const px = ox + x * s, py = oy - t.y[i] * s, col = t.col.at(k);
    if (t.shape === 0) {
      const c = col >= 0 ? rim[col] : shapeless;
      R.circle(px, py, 4 * dpr, c, c);
      continue;
    }
    const sz = t.size.at(k), hx = sz[0] * s, hy = sz[1] * s;
    if (px + hx < 0 || px - hx > W || py + hy < 0 || py - hy > Hh) continue;
    if (t.shape === 1) R.circle(px, py, Math.max(hx, 0.6), fill[col], rim[col]);
    else R.box(px - hx, py - hy, px + hx, py + hy, fill[col], rim[col]);
  }
  if (show.bounds) {
    const b = colors.findIndex(function (c) { return c[1] & 32; });
    const c = b >= 0 ? word(colors[b][0]) : word(0x30a030ff);
    for (const t of rec.tracks) {
      if (k < t.first || k > t.last) continue;
      const bb = t.box.at(k);
      if (bb) R.outline(ox + bb[0] * s, oy - bb[3] * s, ox + bb[2] * s, oy - bb[1] * s, c);
    }
  }
  for (let l = 1; l >= 0; l--) {   // springs always, contacts when asked
    if (l === 0 && !show.contacts) continue;
    const list = lists[l];
    for (let o = 0; o < list.length; o += RV.PRIM) {
      const kind = list[o], c = fill[list[o + 1]];
      const x0 = ox + list[o + 2] * qc * s, y0 = oy - list[o + 3] * qc * s;
      if (kind === 0) R.box(x0 - 1.5 * dpr, y0 - 1.5 * dpr, x0 + 1.5 * dpr, y0 + 1.5 * dpr, c, c);
      else if (kind === 1) R.line(x0, y0, ox + list[o + 4] * qc * s, oy - list[o + 5] * qc * s, c);
      else if (kind === 3) R.outline(x0, oy - list[o + 5] * qc * s, ox + list[o + 4] * qc * s, y0, c);
      else R.circle(x0, y0, Math.max(list[o + 4] * qc * s, 1), c, c);
    }
  }
  ctx.putImageData(R.img, 0, 0);
};

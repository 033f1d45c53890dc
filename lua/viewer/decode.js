// decode.js: the recording of lua/lhtml.c back into tracks and frames.  The stream's format
// is documented in lua/lframes.h; this reads exactly what lframes.c writes.
"use strict";
const RV = {};

// Base64 text (whitespace ignored) to bytes.
RV.base64 = function (text) {
  const bin = atob(text.replace(/\s+/g, ""));
  const out = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) out[i] = bin.charCodeAt(i);
  return out;
};

// zlib (RFC 1950) bytes to bytes, with the browser's own DecompressionStream.
RV.inflate = async function (bytes) {
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate"));
  return new Uint8Array(await new Response(stream).arrayBuffer());
};

// A varint reader (values are below 2^53, so plain numbers hold them exactly).
RV.Reader = function (bytes) {
  this.b = bytes;
  this.p = 0;
};
RV.Reader.prototype.uv = function () {
  const b = this.b;
  let c = b[this.p++];
  if (c < 128) return c;
  let v = c & 127, m = 128;
  do {
    c = b[this.p++];
    if (c === undefined) throw new Error("the recording ends in the middle of a number");
    v += (c & 127) * m;
    m *= 128;
  } while (c >= 128);
  return v;
};
RV.Reader.prototype.sv = function () {
  const u = this.uv();
  return u % 2 ? -(u + 1) / 2 : u / 2;
};

const PRIM_COORDS = [2, 4, 3, 4];   // point, segment, circle, box
const PRIM = 6;                     // a primitive in a list: kind, colour, 4 coordinates

// One frame's free list from the reader, given the last frame's list as written.
RV.readList = function (r, prev) {
  const code = r.uv();
  if (code === 0) return prev;
  const n = code - 1, out = new Float64Array(n * PRIM);
  let last = -1;
  const fresh = [0, 0, 0, 0];
  for (let j = 0; j < n; j++) {
    const o = j * PRIM, g = r.uv();
    if (g > 0) {
      const ref = last + g, p = ref * PRIM;
      if (ref >= prev.length / PRIM) throw new Error("a reference past the last frame's list");
      last = ref;
      const kind = prev[p];
      out[o] = kind;
      out[o + 1] = prev[p + 1];
      for (let k = 0; k < PRIM_COORDS[kind]; k++) {
        let d = r.sv();
        if (k >= 2 && kind !== 2) d += out[o + 2 + k - 2] - prev[p + 2 + k - 2];
        out[o + 2 + k] = prev[p + 2 + k] + d;
      }
    } else {
      const kind = r.uv();
      if (kind > 3) throw new Error("an unknown primitive kind " + kind);
      out[o] = kind;
      out[o + 1] = r.uv();
      for (let k = 0; k < PRIM_COORDS[kind]; k++) {
        fresh[k] += r.sv();
        out[o + 2 + k] = fresh[k];
      }
    }
  }
  return out;
};

// Values that change seldom (size, colour, fat box): the frames where they change.
function Changes() {
  this.f = [];
  this.v = [];
}
Changes.prototype.add = function (frame, value) {
  this.f.push(frame);
  this.v.push(value);
};
Changes.prototype.at = function (frame) {   // the value in force at frame, or undefined
  const f = this.f;
  let lo = 0, hi = f.length - 1;
  if (hi < 0 || frame < f[0]) return undefined;
  if (frame >= f[hi]) return this.v[hi];
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (f[mid] <= frame) lo = mid; else hi = mid - 1;
  }
  return this.v[lo];
};

const LISTS = 2, SNAP = 32;

// The whole recording: meta (the JSON) and the inflated stream.  Positions in metres.
RV.decode = function (meta, bytes) {
  const N = meta.frames, q = meta.q, r = new RV.Reader(bytes);
  const T = meta.tracks.map(function (a, id) {
    const len = a[4] >= 0 ? a[5] - a[4] + 1 : 0;
    const t = {
      id: id, name: a[0], type: a[1], shape: a[2], sensor: a[3], first: a[4], last: a[5],
      serial: a[6], x: new Float32Array(len), y: new Float32Array(len),
      vx: new Float32Array(len), vy: new Float32Array(len),
      size: new Changes(), col: new Changes(), box: new Changes(),
    };
    t.x.fill(NaN);
    return t;
  });
  const nt = T.length, H1 = [], H2 = [];
  for (let c = 0; c < 12; c++) H1.push(new Float64Array(nt));
  for (let c = 0; c < 4; c++) H2.push(new Float64Array(nt));
  const hn = new Uint8Array(nt);
  const times = new Float64Array(N), listOff = new Float64Array(N), snaps = [];
  let alive = [], t1 = 0, t2 = 0;
  let lists = [new Float64Array(0), new Float64Array(0)];
  const cur = new Float64Array(12);
  const vals = [];
  for (let c = 0; c < 12; c++) vals.push(new Float64Array(nt));
  for (let k = 0; k < N; k++) {
    const d = r.sv(), tq = k === 0 ? d : k === 1 ? t1 + d : 2 * t1 - t2 + d;
    t2 = t1;
    t1 = tq;
    times[k] = tq * 1e-6;
    // births and deaths
    const nb = r.uv(), born = [];
    for (let i = 0, last = -1; i < nb; i++) born.push(last += r.uv());
    const nd = r.uv(), dead = new Set();
    for (let i = 0, last = -1; i < nd; i++) dead.add(last += r.uv());
    if (nb || nd) {
      for (const id of born) {
        if (id >= nt) throw new Error("a body outside the track table");
        hn[id] = 0;
      }
      alive = alive.filter(function (id) { return !dead.has(id); }).concat(born);
      alive.sort(function (a, b) { return a - b; });
    }
    const n = alive.length;
    for (let c = 0; c < 4; c++) {
      const h1 = H1[c], h2 = H2[c], v = vals[c];
      for (let j = 0; j < n; j++) {
        const id = alive[j], m = hn[id];
        v[j] = (m === 0 ? 0 : m === 1 ? h1[id] : 2 * h1[id] - h2[id]) + r.sv();
      }
    }
    for (let c = 4; c < 7; c++) {
      const h1 = H1[c], v = vals[c];
      for (let j = 0; j < n; j++) v[j] = (hn[alive[j]] === 0 ? 0 : h1[alive[j]]) + r.sv();
    }
    const hasBox = vals[7];
    for (let j = 0; j < n; j++) hasBox[j] = r.uv();
    for (let j = 0; j < n; j++) {
      const id = alive[j], tr = T[id], i = k - tr.first;
      if (hasBox[j]) {
        for (let c = 8; c < 12; c++) {
          cur[c] = (hn[id] === 0 ? 0 : H1[c][id]) + r.sv();
          H1[c][id] = cur[c];
        }
      } else if (hn[id] === 0) {
        for (let c = 8; c < 12; c++) H1[c][id] = 0;
      }
      if (i < 0 || k > tr.last) throw new Error("a body drawn outside its frames");
      tr.x[i] = vals[0][j] * q;
      tr.y[i] = vals[1][j] * q;
      tr.vx[i] = vals[2][j] * q;
      tr.vy[i] = vals[3][j] * q;
      const sz = tr.size.v.length ? tr.size.v[tr.size.v.length - 1] : null;
      if (hn[id] === 0 || !sz || sz[0] !== vals[4][j] * q || sz[1] !== vals[5][j] * q)
        tr.size.add(k, [vals[4][j] * q, vals[5][j] * q]);
      const col = vals[6][j] - 1;
      if (hn[id] === 0 || tr.col.v[tr.col.v.length - 1] !== col) tr.col.add(k, col);
      const bl = tr.box.v.length ? tr.box.v[tr.box.v.length - 1] : undefined;
      if (hasBox[j]) {
        const b = [H1[8][id] * q, H1[9][id] * q, H1[10][id] * q, H1[11][id] * q];
        if (!bl || b[0] !== bl[0] || b[1] !== bl[1] || b[2] !== bl[2] || b[3] !== bl[3]) tr.box.add(k, b);
      } else if (bl !== null) {
        tr.box.add(k, null);
      }
      for (let c = 0; c < 4; c++) {
        H2[c][id] = H1[c][id];
        H1[c][id] = vals[c][j];
      }
      for (let c = 4; c < 8; c++) H1[c][id] = vals[c][j];
      if (hn[id] < 2) hn[id]++;
    }
    // the free lists: kept as snapshots every SNAP frames and re-read on demand
    if (k % SNAP === 0) snaps.push(lists);
    listOff[k] = r.p;
    const next = [];
    for (let l = 0; l < LISTS; l++) next.push(RV.readList(r, lists[l]));
    lists = next;
  }
  if (r.p !== bytes.length) throw new Error("the recording has " + (bytes.length - r.p) + " bytes past its last frame");
  return { frames: N, times: times, tracks: T, bytes: bytes, listOff: listOff, snaps: snaps,
           cache: { k: -1, lists: null } };
};

// The free lists (contacts, springs) of frame k: from the nearest snapshot, or one frame on
// from the last asked for.
RV.listsAt = function (rec, k) {
  const c = rec.cache;
  if (c.k === k) return c.lists;
  let j, lists;
  if (c.k >= 0 && c.k < k && k - c.k <= SNAP) {
    j = c.k + 1;
    lists = c.lists;
  } else {
    j = Math.floor(k / SNAP) * SNAP;
    lists = rec.snaps[j / SNAP];
  }
  const r = new RV.Reader(rec.bytes);
  for (; j <= k; j++) {
    r.p = rec.listOff[j];
    const next = [];
    for (let l = 0; l < LISTS; l++) next.push(RV.readList(r, lists[l]));
    lists = next;
  }
  c.k = k;
  c.lists = lists;
  return lists;
};
RV.PRIM = PRIM;

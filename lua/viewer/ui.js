// ui.js: the player around draw.js: playback, scrubbing, zoom and pan, toggles, hover,
// the log in step with the picture, the plot of one body, the URL's #frame=K.
"use strict";

(async function () {
  const $ = function (id) { return document.getElementById(id); };
  const view = $("view"), ctx = view.getContext("2d"), status = $("status");
  let meta, rec;
  try {
    meta = RV.meta = JSON.parse($("rigid-meta").textContent);
    document.title = meta.title;
    $("title").textContent = meta.title;
    $("subtitle").textContent = meta.subtitle + (meta.stopped ? "; recording stopped early: " + meta.stopped : "") +
      (meta.log_dropped ? "; " + meta.log_dropped + " printed lines past the log's cap not kept" : "");
    if (meta.frames === 0) throw new Error("no frames were recorded");
    rec = RV.decode(meta, await RV.inflate(RV.base64($("rigid-frames").textContent)));
  } catch (e) {
    status.textContent = meta && meta.frames === 0 ? "nothing to replay: the script stepped no world"
                                                   : "cannot read the recording: " + e.message;
    if (meta) $("log").textContent = meta.log.map(function (l) { return l[1]; }).join("\n");
    document.body.dataset.error = e.message;
    return;
  }
  status.hidden = true;
  const N = rec.frames, times = rec.times, T = rec.tracks;
  const W = 960, world = meta.world;
  const H = Math.round(Math.min(600, Math.max(320, W * (world[3] - world[1]) / Math.max(world[2] - world[0], 1e-3))));
  const dpr = window.devicePixelRatio || 1;
  function size(c, w, h) {
    c.width = Math.round(w * dpr);
    c.height = Math.round(h * dpr);
    c.style.width = w + "px";
    c.style.height = h + "px";
  }
  size(view, W, H);
  $("left").style.width = (W + 2) + "px";
  $("log").style.height = (H + 230) + "px";
  const st = { k: 0, playing: false, speed: 1, simT: 0, last: null, v: RV.fit(world, W, H), chosen: null,
               show: { contacts: true, velocities: false, bounds: false, trails: true, names: true } };
  const stats = { ts: [], draw: [] };

  // ---------------------------------------------------------------- drawing
  let pending = false;
  function render() {
    const t0 = performance.now();
    RV.drawFrame(ctx, rec, st.k, st.v, W, H, dpr, st.show, st.chosen);
    drawPlot();
    updateLog();
    $("scrub").value = st.k;
    $("time").textContent = "t = " + times[st.k].toFixed(3) + " s   frame " + st.k + " / " + (N - 1);
    document.body.dataset.frame = st.k;
    stats.draw.push(performance.now() - t0);
    if (stats.draw.length > 600) stats.draw.shift();
  }
  function redraw() {
    if (pending || st.playing) return;
    pending = true;
    requestAnimationFrame(function () { pending = false; render(); });
  }
  function seek(k) {
    st.k = Math.max(0, Math.min(N - 1, Math.round(k)));
    st.simT = times[st.k];
    redraw();
  }

  // ---------------------------------------------------------------- playback
  function tick(ts) {
    if (!st.playing) return;
    if (st.last !== null) {
      st.simT += (ts - st.last) / 1000 * st.speed;
      while (st.k + 1 < N && times[st.k + 1] <= st.simT + 1e-9) st.k++;
    }
    st.last = ts;
    stats.ts.push(ts);
    if (stats.ts.length > 600) stats.ts.shift();
    render();
    if (st.k >= N - 1) pause(); else requestAnimationFrame(tick);
  }
  function play() {
    if (st.playing) return;
    if (st.k >= N - 1) st.k = 0;
    st.playing = true;
    st.simT = times[st.k];
    st.last = null;
    stats.ts.length = 0;
    $("play").innerHTML = "&#10074;&#10074;";
    requestAnimationFrame(tick);
  }
  function pause() {
    st.playing = false;
    $("play").innerHTML = "&#9654;";
    const f = stats.ts.length > 1 ? (stats.ts.length - 1) / ((stats.ts[stats.ts.length - 1] - stats.ts[0]) / 1000) : 0;
    if (f > 0) $("fps").textContent = f.toFixed(0) + " frames per second while playing";
    history.replaceState(null, "", "#frame=" + st.k);
    redraw();
  }
  function step(d) {
    if (st.playing) pause();
    seek(st.k + d);
  }

  // ---------------------------------------------------------------- log
  const log = $("log"), lines = meta.log, lineFrames = lines.map(function (l) { return l[0]; });
  const lineEls = lines.map(function (l) {
    const d = document.createElement("div"), t = document.createElement("span");
    t.className = "t";
    t.textContent = times[Math.min(l[0], N - 1)].toFixed(2) + " s";
    d.appendChild(t);
    d.appendChild(document.createTextNode(l[1]));
    d.className = "future";
    d.onclick = function () { step(l[0] - st.k); };
    log.appendChild(d);
    return d;
  });
  if (!lines.length) log.textContent = "(the script printed nothing)";
  let shown = 0;   // lines at or before the current frame
  function updateLog() {
    let lo = 0, hi = lineFrames.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (lineFrames[mid] <= st.k) lo = mid + 1; else hi = mid;
    }
    if (lo === shown) return;
    // the lines between the old and the new boundary, and the last line shown, change
    for (let i = Math.max(0, Math.min(lo, shown) - 1); i < Math.max(lo, shown); i++)
      lineEls[i].className = i < lo - 1 ? "" : i === lo - 1 ? "now" : "future";
    shown = lo;
    if (lo > 0) log.scrollTop = lineEls[lo - 1].offsetTop - log.offsetTop - log.clientHeight / 2;
  }

  // ---------------------------------------------------------------- plot of one body
  const plot = $("plot"), pctx = plot.getContext("2d"), PH = 150;
  size(plot, W, PH);
  let plotCache = null;
  const PL = 46, PR = 46, PT = 8, PB = 18;
  function plotScales(t) {
    let y0 = Infinity, y1 = -Infinity, v1 = 0;
    for (let i = 0; i <= t.last - t.first; i++) {
      if (t.x[i] !== t.x[i]) continue;
      y0 = Math.min(y0, t.y[i]);
      y1 = Math.max(y1, t.y[i]);
      v1 = Math.max(v1, Math.hypot(t.vx[i], t.vy[i]));
    }
    if (!(y0 <= y1)) y0 = y1 = 0;
    if (y1 - y0 < 1e-6) { y0 -= 0.5; y1 += 0.5; }
    return { y0: y0, y1: y1, v1: v1 > 0 ? v1 : 1, t1: Math.max(times[N - 1], 1e-9) };
  }
  function px(sc, t) { return PL + (W - PL - PR) * t / sc.t1; }
  function drawPlotCache() {
    const c = document.createElement("canvas"), g = c.getContext("2d"), t = st.chosen;
    size(c, W, PH);
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.fillStyle = "#fff";
    g.fillRect(0, 0, W, PH);
    g.font = "11px sans-serif";
    g.fillStyle = "#777";
    if (!t) {
      g.fillText("no body chosen", PL, PH / 2);
      return { c: c };
    }
    const sc = plotScales(t), ih = PH - PT - PB;
    g.strokeStyle = "#ddd";
    g.strokeRect(PL, PT, W - PL - PR, ih);
    const series = [[t.y, sc.y0, sc.y1, "#1f63b4"], [null, 0, sc.v1, "#d0600e"]];
    for (const s of series) {
      g.strokeStyle = s[3];
      g.lineWidth = 1.5;
      g.beginPath();
      let pen = false;
      for (let i = 0; i <= t.last - t.first; i++) {
        if (t.x[i] !== t.x[i]) { pen = false; continue; }
        const val = s[0] ? s[0][i] : Math.hypot(t.vx[i], t.vy[i]);
        const x = px(sc, times[t.first + i]), y = PT + ih * (1 - (val - s[1]) / (s[2] - s[1]));
        if (pen) g.lineTo(x, y); else g.moveTo(x, y);
        pen = true;
      }
      g.stroke();
    }
    g.fillStyle = "#1f63b4";
    g.fillText(sc.y1.toPrecision(3), 4, PT + 9);
    g.fillText(sc.y0.toPrecision(3), 4, PT + ih);
    g.fillStyle = "#d0600e";
    g.fillText(sc.v1.toPrecision(3), W - PR + 4, PT + 9);
    g.fillText("0", W - PR + 4, PT + ih);
    g.fillStyle = "#777";
    for (let s = 0; s <= 5; s++) g.fillText((sc.t1 * s / 5).toFixed(2) + " s", px(sc, sc.t1 * s / 5) - 14, PH - 4);
    return { c: c, sc: sc };
  }
  function drawPlot() {
    if (!plotCache) plotCache = drawPlotCache();
    pctx.setTransform(1, 0, 0, 1, 0, 0);
    pctx.drawImage(plotCache.c, 0, 0);
    if (!plotCache.sc) return;
    pctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    const x = px(plotCache.sc, times[st.k]);
    pctx.strokeStyle = "#d62728";
    pctx.lineWidth = 1;
    pctx.beginPath();
    pctx.moveTo(x, PT);
    pctx.lineTo(x, PH - PB);
    pctx.stroke();
  }
  plot.addEventListener("click", function (e) {
    if (!plotCache || !plotCache.sc) return;
    const t = (e.offsetX - PL) / (W - PL - PR) * plotCache.sc.t1;
    let k = 0;
    while (k + 1 < N && times[k + 1] <= t) k++;
    step(k - st.k);
  });

  // ---------------------------------------------------------------- choosing a body
  const select = $("body");
  function label(t) { return (t.name !== null ? t.name : "body") + " #" + t.serial; }
  function choose(t) {
    st.chosen = t;
    plotCache = null;
    if (t && !Array.prototype.some.call(select.options, function (o) { return +o.value === t.id; })) {
      const o = document.createElement("option");
      o.value = t.id;
      o.textContent = label(t);
      select.appendChild(o);
    }
    select.value = t ? t.id : "";
    redraw();
  }
  T.filter(function (t) { return t.name !== null && t.first >= 0; }).slice(0, 500).forEach(function (t) {
    const o = document.createElement("option");
    o.value = t.id;
    o.textContent = label(t);
    select.appendChild(o);
  });
  select.onchange = function () { choose(T[+select.value] || null); };
  const moving = T.filter(function (t) { return t.type !== 0 && t.first >= 0; });
  choose(moving.find(function (t) { return t.name !== null; }) || moving[0] || null);

  // ---------------------------------------------------------------- hover, zoom, pan
  function bodyAt(mx, my) {
    const v = st.v, x = (mx - v.ox) / v.s, y = (v.oy - my) / v.s, tol = 3 / v.s;
    let best = null, area = Infinity;
    for (const t of T) {
      if (st.k < t.first || st.k > t.last) continue;
      const i = st.k - t.first;
      if (t.x[i] !== t.x[i]) continue;
      const sz = t.size.at(st.k), dx = x - t.x[i], dy = y - t.y[i];
      const hit = t.shape === 0 ? Math.hypot(dx, dy) <= 6 / v.s
        : t.shape === 1 ? Math.hypot(dx, dy) <= sz[0] + tol
        : Math.abs(dx) <= sz[0] + tol && Math.abs(dy) <= sz[1] + tol;
      const a = (sz[0] + tol) * (sz[1] + tol);
      if (hit && a < area) { best = t; area = a; }
    }
    return best;
  }
  const STATE = [[1, "static"], [2, "kinematic"], [4, "awake"], [8, "asleep"], [16, "sensor"]];
  function describe(t) {
    const i = st.k - t.first, col = t.col.at(st.k), seen = col >= 0 ? meta.colors[col][1] : 0;
    const what = ["static", "kinematic", "dynamic"][t.type] + (t.sensor ? " sensor" : "") +
      (t.shape === 1 ? " circle r " + t.size.at(st.k)[0].toFixed(3) : t.shape === 2 ? " box" : " point") +
      (t.type === 2 && seen & 8 && !(seen & 4) ? ", asleep" : "");
    const f = function (a) { return (a >= 0 ? " " : "") + a.toFixed(3); };
    return label(t) + "  " + what + "\nx =" + f(t.x[i]) + "  y =" + f(t.y[i]) + " m\nvx =" + f(t.vx[i]) +
      "  vy =" + f(t.vy[i]) + " m/s  |v| = " + Math.hypot(t.vx[i], t.vy[i]).toFixed(3);
  }
  const tip = $("tip");
  let drag = null;
  view.addEventListener("mousemove", function (e) {
    if (drag) {
      st.v.ox += e.offsetX - drag.x;
      st.v.oy += e.offsetY - drag.y;
      drag.moved = drag.moved || Math.abs(e.offsetX - drag.x0) + Math.abs(e.offsetY - drag.y0) > 3;
      drag.x = e.offsetX;
      drag.y = e.offsetY;
      redraw();
      return;
    }
    const t = bodyAt(e.offsetX, e.offsetY);
    tip.hidden = !t;
    if (t) {
      tip.textContent = describe(t);
      tip.style.left = Math.min(e.offsetX + 14, W - 260) + "px";
      tip.style.top = Math.min(e.offsetY + 14, H - 60) + "px";
    }
  });
  view.addEventListener("mouseleave", function () { tip.hidden = true; drag = null; });
  view.addEventListener("mousedown", function (e) {
    drag = { x: e.offsetX, y: e.offsetY, x0: e.offsetX, y0: e.offsetY, moved: false };
  });
  view.addEventListener("mouseup", function (e) {
    if (drag && !drag.moved) {
      const t = bodyAt(e.offsetX, e.offsetY);
      if (t) choose(t);
    }
    drag = null;
  });
  function zoom(f, mx, my) {
    const v = st.v;
    v.ox = mx - (mx - v.ox) * f;
    v.oy = my - (my - v.oy) * f;
    v.s *= f;
    redraw();
  }
  view.addEventListener("wheel", function (e) {
    e.preventDefault();
    zoom(Math.exp(-e.deltaY * 0.0015), e.offsetX, e.offsetY);
  }, { passive: false });

  // ---------------------------------------------------------------- controls
  const scrub = $("scrub");
  scrub.max = N - 1;
  scrub.oninput = function () { if (st.playing) pause(); seek(+scrub.value); };
  $("play").onclick = function () { if (st.playing) pause(); else play(); };
  $("back").onclick = function (e) { step(e.shiftKey ? -10 : -1); };
  $("fwd").onclick = function (e) { step(e.shiftKey ? 10 : 1); };
  $("speed").onchange = function () { st.speed = +$("speed").value; };
  $("fit").onclick = function () { st.v = RV.fit(world, W, H); redraw(); };
  const toggles = { contacts: meta.recorded.contacts, velocities: true, bounds: meta.recorded.bounds,
                    trails: true, names: T.some(function (t) { return t.name !== null; }) };
  Object.keys(toggles).forEach(function (name) {
    const box = $("show-" + name);
    if (!toggles[name]) {
      box.disabled = true;
      box.parentNode.title = "none in this recording";
      box.parentNode.style.color = "#aaa";
    }
    box.onchange = function () { st.show[name] = box.checked; redraw(); };
  });
  document.addEventListener("keydown", function (e) {
    if (e.target.tagName === "SELECT" || e.ctrlKey || e.metaKey || e.altKey) return;
    const keys = { " ": function () { if (st.playing) pause(); else play(); },
                   ArrowLeft: function () { step(e.shiftKey ? -10 : -1); },
                   ArrowRight: function () { step(e.shiftKey ? 10 : 1); },
                   Home: function () { step(-st.k); }, End: function () { step(N - 1 - st.k); },
                   "+": function () { zoom(1.25, W / 2, H / 2); }, "=": function () { zoom(1.25, W / 2, H / 2); },
                   "-": function () { zoom(0.8, W / 2, H / 2); },
                   "0": function () { $("fit").onclick(); } };
    if (keys[e.key]) {
      e.preventDefault();
      keys[e.key]();
    }
  }, true);
  document.querySelectorAll("button").forEach(function (b) {
    b.addEventListener("mouseup", function () { b.blur(); });
  });

  // ---------------------------------------------------------------- legend
  const legend = $("legend");
  function item(html) {
    const s = document.createElement("span");
    s.innerHTML = html;
    legend.appendChild(s);
  }
  function swatch(rgba) { return "<span class=\"sw\" style=\"background:" + RV.css(rgba) + "\"></span>"; }
  meta.colors.forEach(function (c) {
    const what = [];
    STATE.forEach(function (s) { if (c[1] & s[0]) what.push(s[0] === 4 ? "dynamic, awake" : s[0] === 8 ? "dynamic, asleep" : s[1]); });
    if (what.length) item(swatch(c[0]) + what.join(" / "));
    if (c[1] & 32) item(swatch(c[0]) + "fat box (broadphase bounds)");
    if (c[1] & 64) item(swatch(c[0]) + (c[1] & 16 ? "contact with a sensor" : "contact point and normal"));
    if (c[1] & 128) item(swatch(c[0]) + "spring");
  });
  if (T.some(function (t) { return t.shape === 0 && t.first >= 0; })) item("&#9711; body without a shape");
  item("<span style=\"color:" + RV.css(RV.VELOCITY) + "\">&#8594;</span> velocity: " + RV.ARROW_S + " s of motion");
  item("&#9472; trail: the path so far (" + RV.TRAILS + " bodies at most)");
  item("dashed box: the plotted body");
  item("colours: rg_world_draw's");

  // ---------------------------------------------------------------- the URL, and tests
  function fromHash() {
    const h = new URLSearchParams(location.hash.replace(/^#/, ""));
    Object.keys(st.show).forEach(function (name) {
      if (h.has(name) && toggles[name]) {
        st.show[name] = h.get(name) !== "0";
        $("show-" + name).checked = st.show[name];
      }
    });
    if (h.has("speed") && +h.get("speed") > 0) st.speed = +h.get("speed");
    if (h.has("frame")) {
      if (st.playing) pause();
      seek(+h.get("frame") || 0);
    }
    if (h.get("play") === "1") play();
  }
  Object.keys(st.show).forEach(function (name) { st.show[name] = st.show[name] && !!toggles[name]; $("show-" + name).checked = st.show[name]; });
  window.addEventListener("hashchange", fromHash);
  window.rigidViewer = {
    frames: N, frame: function () { return st.k; }, seek: seek, play: play, pause: pause,
    // page coordinates (CSS pixels) of world point (x, y)
    worldToPage: function (x, y) {
      const r = view.getBoundingClientRect();
      return [r.left + window.scrollX + st.v.ox + x * st.v.s, r.top + window.scrollY + st.v.oy - y * st.v.s];
    },
    scale: function () { return st.v.s; },
    // frame rate while playing, from the requestAnimationFrame timestamps
    stats: function () {
      const ts = stats.ts, n = ts.length, iv = [];
      for (let i = 1; i < n; i++) iv.push(ts[i] - ts[i - 1]);
      iv.sort(function (a, b) { return a - b; });
      const d = stats.draw.slice().sort(function (a, b) { return a - b; });
      return { frames: n, fps: n > 1 ? (n - 1) / ((ts[n - 1] - ts[0]) / 1000) : 0,
               interval_p50_ms: iv.length ? iv[iv.length >> 1] : 0,
               interval_max_ms: iv.length ? iv[iv.length - 1] : 0,
               draw_p50_ms: d.length ? d[d.length >> 1] : 0, draw_max_ms: d.length ? d[d.length - 1] : 0,
               playing: st.playing };
    },
  };
  fromHash();
  render();
  document.body.dataset.ready = "1";
})();

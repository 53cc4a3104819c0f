// The replay viewer's page: plain HTML, CSS and script, no library and no network. `@DATA@` is
// replaced by the run's data (html_report.cpp).
#include <string>

namespace slamkit {

std::string HtmlReportTemplate() {
  return R"HTML(<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>slamkit report</title>
<style>
body { font-family: sans-serif; margin: 16px; color: #222; }
.row { display: flex; gap: 20px; flex-wrap: wrap; align-items: flex-start; }
canvas { border: 1px solid #aaa; background: #fff; }
table { border-collapse: collapse; font-size: 12px; margin-top: 8px; }
td { border: 1px solid #ddd; padding: 2px 6px; }
td.key { color: #555; }
#controls { margin-top: 6px; }
#slider { width: 520px; vertical-align: middle; }
.legend span { margin-right: 12px; font-size: 12px; }
</style></head>
<body>
<h2 id="title"></h2>
<div class="row">
  <div>
    <canvas id="view" width="720" height="720"></canvas>
    <div id="controls"><button id="play">play</button>
      <input id="slider" type="range" min="0" max="1000" value="1000">
      <span id="time"></span> <span id="pose-sigma"></span>
      <span id="landmarks-shown"></span></div>
    <div class="legend" id="legend"></div>
  </div>
  <div>
    <canvas id="curves" width="560" height="380"></canvas>
    <table id="metrics"></table>
  </div>
</div>
<script id="data" type="application/json">@DATA@</script>
<script>
"use strict";
const D = JSON.parse(document.getElementById("data").textContent);
const view = document.getElementById("view"), curves = document.getElementById("curves");
const slider = document.getElementById("slider"), timeLabel = document.getElementById("time");
document.getElementById("title").textContent = D.title;
const main = D.paths.length ? D.paths[0] : null;

// The world box: paths, landmarks and the map.
let box = [Infinity, Infinity, -Infinity, -Infinity];
const grow = (x, y) => { box = [Math.min(box[0], x), Math.min(box[1], y), Math.max(box[2], x),
                                Math.max(box[3], y)]; };
for (const p of D.paths) for (let i = 0; i < p.x.length; ++i) grow(p.x[i], p.y[i]);
for (const l of D.landmarks) grow(l.x, l.y);
if (!isFinite(box[0]) && D.map) {
  grow(D.map.origin[0], D.map.origin[1]);
  grow(D.map.origin[0] + D.map.w * D.map.resolution, D.map.origin[1] + D.map.h * D.map.resolution);
}
if (!isFinite(box[0])) box = [0, 0, 1, 1];
const pad = 0.05 * Math.max(box[2] - box[0], box[3] - box[1], 1);
box = [box[0] - pad, box[1] - pad, box[2] + pad, box[3] + pad];
const scale = Math.min(view.width / (box[2] - box[0]), view.height / (box[3] - box[1]));
const px = (x) => (x - box[0]) * scale, py = (y) => view.height - (y - box[1]) * scale;

// The map as an image (map_server's grey levels, top row = largest y).
let mapCanvas = null;
if (D.map) {
  const bytes = Uint8Array.from(atob(D.map.pixels), (c) => c.charCodeAt(0));
  mapCanvas = document.createElement("canvas");
  mapCanvas.width = D.map.w; mapCanvas.height = D.map.h;
  const ctx = mapCanvas.getContext("2d"), img = ctx.createImageData(D.map.w, D.map.h);
  for (let i = 0; i < bytes.length; ++i) {
    img.data[4 * i] = img.data[4 * i + 1] = img.data[4 * i + 2] = bytes[i];
    img.data[4 * i + 3] = 255;
  }
  ctx.putImageData(img, 0, 0);
}

const t0 = main && main.t.length ? main.t[0] : 0, t1 = main && main.t.length ? main.t[main.t.length - 1] : 1;
const timeAt = (fraction) => t0 + fraction * (t1 - t0);
// The last index of `t` at or before time `t` (t sorted as the run wrote it).
const lastAt = (ts, t) => { let k = -1; for (let i = 0; i < ts.length; ++i) if (ts[i] <= t) k = i; return k; };

// The 2σ ellipse of covariance [cxx, cxy, cyy] at (x, y); returns its semi-axes [m].
function ellipse(ctx, x, y, cov) {
  const [a, b, c] = cov, m = (a + c) / 2, d = Math.sqrt(((a - c) / 2) ** 2 + b * b);
  const r1 = 2 * Math.sqrt(Math.max(m + d, 0)), r2 = 2 * Math.sqrt(Math.max(m - d, 0));
  const angle = 0.5 * Math.atan2(2 * b, a - c);
  ctx.beginPath();
  ctx.ellipse(px(x), py(y), Math.max(r1 * scale, 1), Math.max(r2 * scale, 1), -angle, 0, 2 * Math.PI);
  ctx.stroke();
  return [r1, r2];
}

function drawView(t) {
  const ctx = view.getContext("2d");
  ctx.clearRect(0, 0, view.width, view.height);
  if (mapCanvas) {
    const x0 = px(D.map.origin[0]), y1 = py(D.map.origin[1] + D.map.h * D.map.resolution);
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(mapCanvas, x0, y1, D.map.w * D.map.resolution * scale, D.map.h * D.map.resolution * scale);
  }
  // With a map history, the estimated landmarks of its last snapshot at or before t.
  const snapshot = D.history.length ? D.history[lastAt(D.history.map((s) => s.t), t)] : null;
  const shown = D.history.length
      ? (snapshot ? snapshot.l.map(([x, y, a, b, c]) => ({x, y, est: true, c: [a, b, c]})) : [])
      : D.landmarks.filter((l) => l.est);
  for (const l of D.landmarks.filter((l) => !l.est).concat(shown)) {
    ctx.strokeStyle = ctx.fillStyle = l.est ? "#d00" : "#555";
    if (l.est && l.c && l.c.every((v) => v !== null)) ellipse(ctx, l.x, l.y, l.c);
    if (!l.est) ctx.fillRect(px(l.x) - 2, py(l.y) - 2, 4, 4);
    else { ctx.beginPath(); ctx.arc(px(l.x), py(l.y), 1.5, 0, 2 * Math.PI); ctx.fill(); }
  }
  document.getElementById("landmarks-shown").textContent =
      shown.length || D.landmarks.length ? `${shown.length} estimated landmarks` : "";
  for (const p of D.paths) {
    const k = lastAt(p.t, t);
    ctx.strokeStyle = p.color; ctx.lineWidth = 1.5; ctx.beginPath();
    for (let i = 0; i <= k; ++i) (i ? ctx.lineTo : ctx.moveTo).call(ctx, px(p.x[i]), py(p.y[i]));
    ctx.stroke();
  }
  if (main) {
    const k = Math.max(lastAt(main.t, t), 0), x = px(main.x[k]), y = py(main.y[k]), th = main.th[k];
    ctx.fillStyle = "#000"; ctx.beginPath();
    ctx.moveTo(x + 9 * Math.cos(th), y - 9 * Math.sin(th));
    ctx.lineTo(x + 5 * Math.cos(th + 2.5), y - 5 * Math.sin(th + 2.5));
    ctx.lineTo(x + 5 * Math.cos(th - 2.5), y - 5 * Math.sin(th - 2.5));
    ctx.fill();
    timeLabel.textContent = `t = ${(t - t0).toFixed(2)} s (${k + 1}/${main.t.length})`;
    const sigma = document.getElementById("pose-sigma");
    if (main.c && main.c[k] && main.c[k].every((v) => v !== null)) {
      ctx.strokeStyle = "#000"; ctx.lineWidth = 1;
      const [r1, r2] = ellipse(ctx, main.x[k], main.y[k], main.c[k]);
      sigma.textContent = `pose 2σ ellipse ${r1.toPrecision(3)} × ${r2.toPrecision(3)} m`;
    } else {
      sigma.textContent = "";
    }
  }
}

// Each series in its own strip, scaled to its own range, with a cursor at time t.
function drawCurves(t) {
  const ctx = curves.getContext("2d");
  ctx.clearRect(0, 0, curves.width, curves.height);
  const n = D.series.length;
  if (!n) { ctx.fillStyle = "#777"; ctx.fillText("no series over time in this run", 20, 20); return; }
  const h = curves.height / n, left = 50, w = curves.width - left - 10;
  D.series.forEach((s, j) => {
    const vs = s.v.filter((v) => v !== null);
    let lo = Math.min(0, ...vs), hi = Math.max(...vs, ...(s.band || []));
    if (!(hi > lo)) hi = lo + 1;
    const sx = (x) => left + (x - s.t[0]) / Math.max(s.t[s.t.length - 1] - s.t[0], 1e-9) * w;
    const sy = (v) => j * h + h - 6 - (v - lo) / (hi - lo) * (h - 20);
    ctx.fillStyle = "#222"; ctx.fillText(`${s.name} (max ${hi.toPrecision(4)})`, left, j * h + 12);
    if (s.band) {
      ctx.strokeStyle = "#9c9"; ctx.beginPath();
      for (const b of s.band) { ctx.moveTo(left, sy(b)); ctx.lineTo(left + w, sy(b)); }
      ctx.stroke();
    }
    ctx.strokeStyle = "#05a"; ctx.beginPath();
    let pen = false;
    s.t.forEach((x, i) => {
      if (s.v[i] === null) { pen = false; return; }
      (pen ? ctx.lineTo : ctx.moveTo).call(ctx, sx(x), sy(s.v[i])); pen = true;
    });
    ctx.stroke();
    ctx.strokeStyle = "#d00"; ctx.beginPath();
    ctx.moveTo(sx(t), j * h + 14); ctx.lineTo(sx(t), j * h + h - 4); ctx.stroke();
  });
}

// The metrics: every scalar, nested keys joined by dots (per-run lists left out).
function addMetrics(table, value, key) {
  if (key === "per_run") return;
  if (value !== null && typeof value === "object" && !(Array.isArray(value) && value.length <= 4 &&
      value.every((v) => typeof v !== "object"))) {
    if (Array.isArray(value)) return;
    for (const k of Object.keys(value)) addMetrics(table, value[k], key ? `${key}.${k}` : k);
    return;
  }
  const row = table.insertRow(), name = row.insertCell(), cell = row.insertCell();
  name.className = "key"; name.textContent = key;
  cell.id = `m-${key}`; cell.textContent = Array.isArray(value) ? JSON.stringify(value) : String(value);
}
addMetrics(document.getElementById("metrics"), D.metrics || {}, "");
document.getElementById("legend").innerHTML = D.paths.map((p) =>
  `<span style="color:${p.color}">&#9644; ${p.name}</span>`).join("");

function draw() {
  const t = timeAt(slider.value / 1000);
  drawView(t); drawCurves(t);
  document.body.dataset.drawn = slider.value;
}
slider.addEventListener("input", draw);
let timer = null;
document.getElementById("play").addEventListener("click", () => {
  if (timer) { clearInterval(timer); timer = null; return; }
  if (+slider.value >= 1000) slider.value = 0;
  timer = setInterval(() => {
    slider.value = Math.min(1000, +slider.value + 4); draw();
    if (+slider.value >= 1000) { clearInterval(timer); timer = null; }
  }, 40);
});
const start = /[#&]t=([0-9.]+)/.exec(location.hash);
if (start) slider.value = Math.round(1000 * Math.min(1, Math.max(0, parseFloat(start[1]))));
draw();
</script>
</body></html>
)HTML";
}

}  // namespace slamkit

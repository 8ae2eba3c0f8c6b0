// windplan viewer, robot cells (export/plots/viewer.h): the joint panel, embedded after
// viewer_app.js in the pages of robot jobs only. Reads the JSON block "windplan-joints" (per
// machine state on the page: its planned time, the index of its row in joints.csv, the robot's
// time and E1, A1..A6 in degrees as joints.csv holds them; the joints' names and limits) and
// shows, in a folding box over the 3-D view's top left corner, for the moment of the time slider,
// every joint's value with a bar over its travel (the limits at the ends, the mark red within 3%
// of one; E1, which has none, over the program's range) and the joints against time (one strip
// each, over the joint's range in the program, as joints.svg) with a cursor at that moment. It follows the slider by
// watching the axes table, which viewer_app.js redraws at every change of time, and takes the
// state viewer_app.js shows: the last whose planned time is <= slider / 1000 x the wind time.
// Logs "windplan-viewer: joints panel ..." once built and, outside playback,
// "windplan-viewer: joints t=<fraction> row=<joints.csv row> t_robot=<s> E1=<deg> A1=..." at each
// change of time, for the browser test.
(function () {
  'use strict';
  var node = document.getElementById('windplan-joints');
  var axesBox = document.getElementById('axes');
  var slider = document.getElementById('slider');
  if (!node || !axesBox || !slider) return;
  var J = JSON.parse(node.textContent);
  function b64(s) {
    var bin = atob(s), u = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; ++i) u[i] = bin.charCodeAt(i);
    return u.buffer;
  }
  var T = new Float32Array(b64(J.state_t)), ROW = new Uint32Array(b64(J.rows));
  var V = new Float32Array(b64(J.values)), NJ = J.names.length, VS = NJ + 1, N = T.length;
  if (N === 0) return;

  function el(tag, attrs, parent, text) {
    var e = document.createElement(tag);
    for (var k in attrs) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    if (parent) parent.appendChild(e);
    return e;
  }
  // The panel: over the 3-D view's top left corner, folding (the side panel scrolls, and the
  // joints are read while the slider moves).
  var box = el('details', { id: 'joints', open: '', style: 'position:absolute;left:8px;top:8px;' +
               'background:rgba(251,252,253,0.93);border:1px solid #c9d1da;padding:4px 6px;' +
               'font-size:12px;z-index:2' }, document.body);
  el('summary', { style: 'font-weight:bold;cursor:pointer' }, box, 'Joints: ' + J.arm);
  var tbl = el('table', { id: 'joint-values', style: 'border-collapse:collapse' }, box);
  var cells = J.names.map(function (name, j) {
    var tr = el('tr', { 'data-joint': name }, tbl);
    el('td', {}, tr, name);
    var val = el('td', { 'class': 'jv', style: 'text-align:right;font-family:monospace' }, tr);
    var barTd = el('td', { style: 'width:100px' }, tr);
    var bar = el('div', { style: 'position:relative;height:10px;background:#dde3ea;' +
                          'border:1px solid #9aa6b2;margin-top:3px' }, barTd);
    var mark = el('div', { style: 'position:absolute;top:-2px;width:3px;height:14px;' +
                           'background:#1d2733' }, bar);
    el('td', { style: 'font-size:11px;color:#55606c;white-space:nowrap' }, tr,
       J.limited[j] ? '[' + J.min[j] + ', ' + J.max[j] + ']' : 'no limits');
    return { val: val, mark: mark };
  });
  var tr0 = el('tr', {}, tbl);
  el('td', {}, tr0, 't robot');
  var tRobot = el('td', { colspan: 3, style: 'font-family:monospace' }, tr0);

  // Joints against time: one strip per joint, its limits (or range) top to bottom.
  var W = 300, H = 15, G = 2;
  var canvas = el('canvas', { id: 'joint-plot', width: W, height: NJ * (H + G) }, box);
  canvas.style.width = W + 'px';
  var ctx = canvas.getContext('2d');
  var t0 = V[0], t1 = V[VS * (N - 1)] > t0 ? V[VS * (N - 1)] : t0 + 1;
  var L = 78;  // px on the left for the strips' labels
  function xOf(t) { return L + (t - t0) / (t1 - t0) * (W - 1 - L); }
  function frac(j, v) { return (v - J.min[j]) / (J.max[j] - J.min[j] || 1); }
  // The strips: each joint over its own range in the program (as joints.svg), the bars over the
  // limits.
  var lo = [], hi = [];
  for (var j = 0; j < NJ; ++j) {
    lo.push(Infinity);
    hi.push(-Infinity);
    for (var i = 0; i < N; ++i) {
      lo[j] = Math.min(lo[j], V[VS * i + 1 + j]);
      hi[j] = Math.max(hi[j], V[VS * i + 1 + j]);
    }
    if (!(hi[j] - lo[j] > 1e-3)) { lo[j] -= 0.5; hi[j] += 0.5; }
  }
  function strip(j, v) { return (v - lo[j]) / (hi[j] - lo[j]); }
  ctx.fillStyle = '#fbfcfd';
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  for (j = 0; j < NJ; ++j) {
    var y0 = j * (H + G);
    ctx.fillStyle = '#eef1f5';
    ctx.fillRect(L, y0, W - L, H);
    ctx.strokeStyle = '#2b6cb0';
    ctx.beginPath();
    for (var i = 0; i < N; ++i) {
      var x = xOf(V[VS * i]), y = y0 + H - 1 - strip(j, V[VS * i + 1 + j]) * (H - 2);
      if (i === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
    }
    ctx.stroke();
    ctx.fillStyle = '#3c4b5c';
    ctx.font = '10px sans-serif';
    ctx.fillText(J.names[j] + ' ' + lo[j].toFixed(0) + '..' + hi[j].toFixed(0), 2, y0 + 11);
  }
  var background = ctx.getImageData(0, 0, canvas.width, canvas.height);

  function stateAt(f) {  // as viewer_app.js: the last state with t <= f * wind time
    var t = f * T[N - 1], lo = 0, hi = N - 1;
    while (lo < hi) {
      var mid = (lo + hi + 1) >> 1;
      if (T[mid] <= t) lo = mid; else hi = mid - 1;
    }
    return lo;
  }
  var shown = -2;
  function refresh() {
    var f = slider.value / 1000, s = stateAt(f), o = VS * s;
    var playing = (document.getElementById('play') || {}).textContent === 'pause';
    if (s === shown && playing) return;
    shown = s;
    var log = 'windplan-viewer: joints t=' + f.toFixed(3) + ' row=' + ROW[s] +
              ' t_robot=' + V[o].toFixed(3);
    cells.forEach(function (c, j) {
      var v = V[o + 1 + j], p = Math.max(0, Math.min(1, frac(j, v)));
      c.val.textContent = v.toFixed(2) + ' deg';
      c.mark.style.left = 'calc(' + (100 * p).toFixed(2) + '% - 1px)';
      c.mark.style.background = J.limited[j] && (p < 0.03 || p > 0.97) ? '#c0392b' : '#1d2733';
      log += ' ' + J.names[j] + '=' + v.toFixed(3);
    });
    tRobot.textContent = V[o].toFixed(2) + ' s of ' + J.cycle_time.toFixed(1) + ' s cycle';
    ctx.putImageData(background, 0, 0);
    ctx.strokeStyle = '#ff3d00';
    ctx.beginPath();
    ctx.moveTo(xOf(V[o]) + 0.5, 0);
    ctx.lineTo(xOf(V[o]) + 0.5, canvas.height);
    ctx.stroke();
    if (!playing) console.log(log);
  }
  console.log('windplan-viewer: joints panel ' + J.names.join(',') + ' (' + N + ' states)');
  refresh();
  new MutationObserver(refresh).observe(axesBox, { childList: true });
})();

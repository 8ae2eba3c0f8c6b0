// windplan viewer (export/plots/viewer.h): reads the JSON block "windplan-data" and draws the plan with
// three.js r111. No network, no modules: THREE is the global of the embedded build.
// Frame: x along the spindle axis, y and z across it (mm). Rendering is on demand (a change of
// view, time or colour draws one frame), and each frame drawn outside playback is logged as
// "windplan-viewer: frame ..." for the browser test; script errors as "windplan-viewer ERROR: ...".
(function () {
  'use strict';
  window.addEventListener('error', function (e) {
    console.log('windplan-viewer ERROR: ' + e.message + ' (line ' + e.lineno + ')');
  });
  var origError = console.error.bind(console);
  console.error = function () {
    var a = Array.prototype.slice.call(arguments).join(' ');
    console.log('windplan-viewer ERROR: ' + a);
    origError.apply(null, arguments);
  };

  var D = JSON.parse(document.getElementById('windplan-data').textContent);
  function b64(s) {
    var bin = atob(s), u = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; ++i) u[i] = bin.charCodeAt(i);
    return u.buffer;
  }
  function f32(s) { return new Float32Array(b64(s)); }
  function u32(s) { return new Uint32Array(b64(s)); }

  var P = f32(D.positions), N = f32(D.normals), ANG = f32(D.angles), SLIP = f32(D.slippage);
  var S = f32(D.states), SS = D.state_stride, NS = S.length / SS;
  var circuits = D.circuits, NP = ANG.length;
  var mu = D.mu > 0 ? D.mu : 0.2;

  // ---- hash parameters ----
  var params = {};
  location.hash.replace(/^#/, '').split('&').forEach(function (kv) {
    var i = kv.indexOf('=');
    if (i > 0) params[decodeURIComponent(kv.slice(0, i))] = decodeURIComponent(kv.slice(i + 1));
  });

  // ---- panel ----
  var panel = document.getElementById('panel');
  function el(tag, attrs, parent, text) {
    var e = document.createElement(tag);
    for (var k in attrs) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    if (parent) parent.appendChild(e);
    return e;
  }
  el('h1', {}, panel, 'windplan: ' + D.job);
  if (D.note) el('div', { 'class': 'note', id: 'note' }, panel, D.note);
  var tbl = el('table', { id: 'headline' }, panel);
  D.headline.forEach(function (r) {
    var tr = el('tr', {}, tbl);
    el('td', {}, tr, r[0]);
    el('td', {}, tr, r[1]);
  });
  if (D.coverage) {  // the measured coverage: figures, then one row per station (folded)
    el('h2', {}, panel, 'Measured coverage');
    var ct = el('table', { id: 'coverage' }, panel);
    var cdet = el('details', { id: 'coverage-stations' }, panel), nst = 0;
    D.coverage.forEach(function (r) {
      var station = r[0].indexOf('at ') === 0;
      var tr = el('tr', {}, station ? (cdet.querySelector('table') || el('table', {}, cdet)) : ct);
      if (station) ++nst;
      el('td', {}, tr, r[0]);
      el('td', { 'class': /bare 0\.00%/.test(r[1]) || !station ? '' : 'warn' }, tr, r[1]);
    });
    el('summary', {}, cdet, 'per station (' + nst + ')');
    cdet.insertBefore(cdet.lastChild, cdet.firstChild);
  }
  if (D.warnings.length) {
    var det = el('details', { id: 'warnings' }, panel);
    el('summary', {}, det, D.warnings.length + ' warning' + (D.warnings.length > 1 ? 's' : ''));
    D.warnings.forEach(function (w) { el('div', { 'class': 'warn' }, det, w); });
  }

  el('h2', {}, panel, 'Time');
  var slider = el('input', { type: 'range', id: 'slider', min: 0, max: 1000, value: 1000 }, panel);
  var play = el('button', { id: 'play' }, panel, 'play');
  var axesBox = el('div', { id: 'axes' }, panel);

  el('h2', {}, panel, 'Colour');
  var modeSel = el('select', { id: 'mode' }, panel);
  [['circuit', 'by circuit'], ['layer', 'by layer'], ['angle', 'by winding angle'],
   ['slippage', 'by slippage |k_g/k_n| / mu']].forEach(function (m) {
    el('option', { value: m[0] }, modeSel, m[1]);
  });
  var legend = el('div', { id: 'legend' }, panel);

  el('h2', {}, panel, 'Show');
  var showBox = el('div', {}, panel);
  function checkbox(id, text, on, parent) {
    var l = el('label', {}, parent || showBox);
    var c = el('input', { type: 'checkbox', id: id }, l);
    c.checked = on;
    l.appendChild(document.createTextNode(' ' + text));
    return c;
  }
  var cbMandrel = checkbox('show-mandrel', 'mandrel', true);
  var cbCut = checkbox('show-cutlines', 'cut-lines (' + D.cutlines.length + ')', true);
  var cbEye = checkbox('show-eye', 'eye path so far', true);
  var cbEyeAll = checkbox('show-eye-all', 'whole eye path', false);
  var frameSel = el('select', { id: 'frame' }, showBox);
  el('option', { value: 'mandrel' }, frameSel, 'mandrel frame (the eye orbits)');
  el('option', { value: 'machine' }, frameSel, 'machine frame (the mandrel turns by A)');
  var layerIds = [];
  circuits.forEach(function (c) { if (layerIds.indexOf(c.layer) < 0) layerIds.push(c.layer); });
  layerIds.sort(function (a, b) { return a - b; });
  var layerBox = el('div', { id: 'layers' }, panel);

  // ---- colours ----
  function hsl(h, s, l) { return new THREE.Color().setHSL(h, s, l); }
  // The colour of circuit k as in development.svg (export/svg_util.h circuit_colour).
  function circuitColour(k) { return hsl(((k * 137.50776405) % 360) / 360, 0.75, 0.42); }
  var layerPalette = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b',
                      '#e377c2', '#17becf', '#bcbd22', '#7f7f7f'];
  function layerName(l) { return D.layers && D.layers[l] ? D.layers[l] : 'layer ' + l; }
  function layerColour(l) { return new THREE.Color(layerPalette[((l % 10) + 10) % 10]); }
  function ramp(stops, x) {  // stops: [[x, '#rrggbb'], ...] increasing in x
    if (x <= stops[0][0]) return new THREE.Color(stops[0][1]);
    for (var i = 1; i < stops.length; ++i) {
      if (x <= stops[i][0]) {
        var f = (x - stops[i - 1][0]) / (stops[i][0] - stops[i - 1][0]);
        return new THREE.Color(stops[i - 1][1]).lerp(new THREE.Color(stops[i][1]), f);
      }
    }
    return new THREE.Color(stops[stops.length - 1][1]);
  }
  var angleStops = [[0, '#3b4cc0'], [30, '#1fa187'], [55, '#a0da39'], [75, '#fdae32'],
                    [90, '#d7301f']];
  var slipStops = [[0, '#1a9850'], [0.5, '#91cf60'], [1, '#fee08b'], [1.0001, '#fc8d59'],
                   [2, '#d73027']];
  function pointColour(mode, c, i) {
    if (mode === 'layer') return layerColour(circuits[c].layer);
    if (mode === 'angle') return ramp(angleStops, ANG[i]);
    if (mode === 'slippage') return ramp(slipStops, SLIP[i] / mu);
    return circuitColour(c);
  }

  // ---- scene ----
  var view = document.getElementById('view');
  var renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    view.textContent = 'WebGL is not available in this browser: ' + e.message;
    console.log('windplan-viewer ERROR: no WebGL');
    return;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xe9edf2);
  view.appendChild(renderer.domElement);
  var scene = new THREE.Scene();
  var root = new THREE.Group();
  scene.add(root);
  var camera = new THREE.PerspectiveCamera(35, 1, 1, 1e6);
  scene.add(camera);
  scene.add(new THREE.AmbientLight(0xffffff, 0.5));
  var lamp = new THREE.DirectionalLight(0xffffff, 0.6);
  lamp.position.set(0.4, 0.8, 1);
  camera.add(lamp);

  // Mandrel.
  var mg = new THREE.BufferGeometry();
  mg.setAttribute('position', new THREE.BufferAttribute(f32(D.mesh_positions), 3));
  mg.setIndex(new THREE.BufferAttribute(u32(D.mesh_triangles), 1));
  mg.computeVertexNormals();
  mg.computeBoundingSphere();
  var mandrel = new THREE.Mesh(mg, new THREE.MeshLambertMaterial({
    color: 0x9b9b9b, side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1,
    polygonOffsetUnits: 2 }));
  root.add(mandrel);
  var bs = mg.boundingSphere.clone();
  if (!(bs.radius > 0)) bs.radius = 100;
  var size = bs.radius;

  // Bands: per point two vertices at +-w/2 across the fibre in the tangent plane, lifted along the
  // normal; per segment two triangles. One geometry per layer; the time slider sets each geometry's
  // draw range. Bands overlap in a plane strip's sag (w^2/8R: 0.3 mm for the vessel) rather than
  // by their lift, so depth cannot order them: they are tested against the mandrel's depth but do
  // not write their own, and are drawn in winding order (later circuits on top, as wound).
  var w = D.band_width > 0 ? D.band_width : size / 100;
  var lift = 0.0015 * size;
  function ribbon(pts, nrms, count, width, h) {  // returns Float32Array of 2*count vertices
    var out = new Float32Array(6 * count), t = new THREE.Vector3(), n = new THREE.Vector3(),
        s = new THREE.Vector3(), p = new THREE.Vector3();
    for (var i = 0; i < count; ++i) {
      var a = Math.max(0, i - 1), b = Math.min(count - 1, i + 1);
      t.set(pts[3 * b] - pts[3 * a], pts[3 * b + 1] - pts[3 * a + 1], pts[3 * b + 2] - pts[3 * a + 2]);
      n.set(nrms[3 * i], nrms[3 * i + 1], nrms[3 * i + 2]);
      s.crossVectors(n, t);
      if (s.lengthSq() === 0) s.set(1, 0, 0);
      s.normalize().multiplyScalar(width / 2);
      n.normalize().multiplyScalar(h);
      p.set(pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]).add(n);
      out[6 * i] = p.x + s.x; out[6 * i + 1] = p.y + s.y; out[6 * i + 2] = p.z + s.z;
      out[6 * i + 3] = p.x - s.x; out[6 * i + 4] = p.y - s.y; out[6 * i + 5] = p.z - s.z;
    }
    return out;
  }
  var layers = layerIds.map(function (lid) {
    var cs = [], nv = 0;
    circuits.forEach(function (c, k) { if (c.layer === lid) { cs.push(k); nv += c.count; } });
    var pos = new Float32Array(6 * nv), col = new Float32Array(6 * nv), idx = [], segEnd = [];
    var pointOf = new Int32Array(nv), circOf = new Int32Array(nv), v = 0;
    var nrm = new Float32Array(6 * nv);
    function tri(i0, i1, i2, q) {
      var ax = pos[3 * i1] - pos[3 * i0], ay = pos[3 * i1 + 1] - pos[3 * i0 + 1], az = pos[3 * i1 + 2] - pos[3 * i0 + 2];
      var bx = pos[3 * i2] - pos[3 * i0], by = pos[3 * i2 + 1] - pos[3 * i0 + 1], bz = pos[3 * i2 + 2] - pos[3 * i0 + 2];
      var d = (ay * bz - az * by) * N[q] + (az * bx - ax * bz) * N[q + 1] + (ax * by - ay * bx) * N[q + 2];
      if (d >= 0) idx.push(i0, i1, i2); else idx.push(i0, i2, i1);
    }
    cs.forEach(function (k) {
      var c = circuits[k];
      var h = lift;
      var r = ribbon(P.subarray(3 * c.first, 3 * (c.first + c.count)),
                     N.subarray(3 * c.first, 3 * (c.first + c.count)), c.count, c.width > 0 ? c.width : w, h);
      pos.set(r, 6 * v);
      for (var i = 0; i < c.count; ++i) {
        pointOf[v + i] = c.first + i;
        circOf[v + i] = k;
        var q = 3 * (c.first + i);
        nrm.set([N[q], N[q + 1], N[q + 2], N[q], N[q + 1], N[q + 2]], 6 * (v + i));
        if (i > 0) {
          var a = 2 * (v + i - 1), b = a + 2;
          // Both triangles facing out (along the point's normal): where the fibre turns sharply
          // the tangent estimate can flip the strip, and a back face would be lit from inside.
          tri(a, a + 1, b, q);
          tri(a + 1, b + 1, b, q);
          segEnd.push(c.first + i);
        }
      }
      v += c.count;
    });
    var g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    g.setAttribute('color', new THREE.BufferAttribute(col, 3));
    g.setAttribute('normal', new THREE.BufferAttribute(nrm, 3));
    g.setIndex(new THREE.BufferAttribute(new Uint32Array(idx), 1));
    var m = new THREE.Mesh(g, new THREE.MeshLambertMaterial({
      vertexColors: THREE.VertexColors, side: THREE.DoubleSide, depthWrite: false }));
    m.renderOrder = 1 + lid;
    root.add(m);
    return { id: lid, mesh: m, geom: g, pointOf: pointOf, circOf: circOf, segEnd: segEnd,
             visible: true };
  });

  // Cut-lines: dark ribbons a fifth of the band wide, on top of the bands.
  var cutGroup = new THREE.Group();
  root.add(cutGroup);
  D.cutlines.forEach(function (cl) {
    var pts = f32(cl.points), n = pts.length / 3;
    if (n < 2) return;
    if (cl.closed) {
      var q = new Float32Array(pts.length + 3);
      q.set(pts);
      q.set(pts.subarray(0, 3), pts.length);
      pts = q;
      n += 1;
    }
    // Normals: from the mandrel's nearest vertex would need a search; the cut-lines are drawn as
    // tubes instead (no normal needed).
    var path = [];
    for (var i = 0; i < n; ++i) path.push(new THREE.Vector3(pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]));
    var curve = new THREE.CatmullRomCurve3(path, false, 'centripetal');
    var tube = new THREE.TubeBufferGeometry(curve, Math.min(2000, 4 * n), Math.max(0.6, w / 8), 6, false);
    var cm = new THREE.Mesh(tube, new THREE.MeshLambertMaterial({ color: 0x111111 }));
    cm.renderOrder = 1000;  // after the bands (which write no depth)
    cutGroup.add(cm);
  });

  // Eye: its whole path (faint), the path so far, the eye and the free fibre.
  var eyePath = new Float32Array(3 * NS);
  for (var i = 0; i < NS; ++i) {
    eyePath[3 * i] = S[SS * i + 6]; eyePath[3 * i + 1] = S[SS * i + 7]; eyePath[3 * i + 2] = S[SS * i + 8];
  }
  var epg = new THREE.BufferGeometry();
  epg.setAttribute('position', new THREE.BufferAttribute(eyePath, 3));
  var reach = size;  // radius about bs.center of everything drawn (the eye goes beyond the mandrel)
  for (var i = 0; i < NS; ++i) {
    var dx = eyePath[3 * i] - bs.center.x, dy = eyePath[3 * i + 1] - bs.center.y,
        dz = eyePath[3 * i + 2] - bs.center.z;
    reach = Math.max(reach, Math.sqrt(dx * dx + dy * dy + dz * dz));
  }
  var eyeAll = new THREE.Line(epg, new THREE.LineBasicMaterial({ color: 0xc9d0d8 }));
  var epg2 = new THREE.BufferGeometry();
  epg2.setAttribute('position', new THREE.BufferAttribute(eyePath, 3));
  var eyeSoFar = new THREE.Line(epg2, new THREE.LineBasicMaterial({ color: 0x6f87a3 }));
  var eyeBall = new THREE.Mesh(new THREE.SphereBufferGeometry(Math.max(2, 0.015 * size), 16, 12),
                               new THREE.MeshLambertMaterial({ color: 0xff3d00 }));
  var fg = new THREE.BufferGeometry();
  fg.setAttribute('position', new THREE.BufferAttribute(new Float32Array(6), 3));
  var freeFibre = new THREE.Line(fg, new THREE.LineBasicMaterial({ color: 0xd00000 }));
  // In the machine frame the eye moves in the plane through the axis (X along it, Y across):
  // its path there is (X, Y, 0), drawn outside the turning group.
  var machinePath = new Float32Array(3 * NS);
  for (var i = 0; i < NS; ++i) { machinePath[3 * i] = S[SS * i + 2]; machinePath[3 * i + 1] = S[SS * i + 3]; }
  var mpg = new THREE.BufferGeometry();
  mpg.setAttribute('position', new THREE.BufferAttribute(machinePath, 3));
  var eyeMachine = new THREE.Line(mpg, new THREE.LineBasicMaterial({ color: 0x6f87a3 }));
  eyeMachine.renderOrder = 1001;
  scene.add(eyeMachine);
  eyeAll.visible = false;
  [eyeAll, eyeSoFar, eyeBall, freeFibre].forEach(function (o) { o.renderOrder = 1001; });
  [eyeAll, eyeSoFar, eyeBall, freeFibre].forEach(function (o) { root.add(o); });

  // ---- colour mode and legend ----
  var mode = 'circuit';
  function recolour() {
    layers.forEach(function (L) {
      var col = L.geom.attributes.color.array;
      for (var v = 0; v < L.pointOf.length; ++v) {
        var c = pointColour(mode, L.circOf[v], L.pointOf[v]);
        col[6 * v] = col[6 * v + 3] = c.r;
        col[6 * v + 1] = col[6 * v + 4] = c.g;
        col[6 * v + 2] = col[6 * v + 5] = c.b;
      }
      L.geom.attributes.color.needsUpdate = true;
    });
    drawLegend();
  }
  function gradient(stops, lo, hi, ticks, unit) {
    var cv = el('canvas', { width: 300, height: 14 }, legend);
    var g = cv.getContext('2d');
    for (var x = 0; x < 300; ++x) {
      g.fillStyle = '#' + ramp(stops, lo + (hi - lo) * x / 299).getHexString();
      g.fillRect(x, 0, 1, 14);
    }
    var row = el('div', { style: 'display:flex;justify-content:space-between;font-size:11px' }, legend);
    ticks.forEach(function (t) { el('span', {}, row, t); });
    el('div', { style: 'font-size:11px;color:#55606c' }, legend, unit);
  }
  function drawLegend() {
    legend.innerHTML = '';
    if (mode === 'angle') {
      gradient(angleStops, 0, 90, ['0', '30', '60', '90'], 'winding angle [deg] from the meridian (0 axial, 90 hoop)');
    } else if (mode === 'slippage') {
      gradient(slipStops, 0, 2, ['0', '0.5', '1', '1.5', '>= 2'],
               '|k_g/k_n| / mu (mu = ' + mu + '): above 1 the fibre may slip');
    } else if (mode === 'layer') {
      layerIds.forEach(function (l) {
        var d = el('div', {}, legend);
        el('span', { 'class': 'sw', style: 'background:#' + layerColour(l).getHexString() }, d);
        d.appendChild(document.createTextNode(' ' + layerName(l)));
      });
    } else {
      var d = el('div', {}, legend);
      circuits.forEach(function (c, k) {
        el('span', { 'class': 'sw', title: 'circuit ' + c.index,
                     style: 'background:#' + circuitColour(k).getHexString() }, d);
      });
      el('div', { style: 'font-size:11px;color:#55606c' }, legend,
         circuits.length + ' circuits, in winding order (hover a swatch for its number)');
    }
  }
  layerIds.forEach(function (lid, i) {
    var c = checkbox('layer-' + lid, layerName(lid), true, layerBox);
    c.addEventListener('change', function () { layers[i].visible = c.checked; update(); });
  });

  // ---- time ----
  var tFrac = 1, stateNow = NS - 1;
  function stateAt(frac) {  // last state with t <= frac * wind time
    var T = frac * (NS ? S[SS * (NS - 1)] : 0), lo = 0, hi = NS - 1;
    if (NS === 0) return -1;
    while (lo < hi) {
      var mid = (lo + hi + 1) >> 1;
      if (S[SS * mid] <= T) lo = mid; else hi = mid - 1;
    }
    return lo;
  }
  function countLE(arr, x) {
    var lo = 0, hi = arr.length;
    while (lo < hi) { var mid = (lo + hi) >> 1; if (arr[mid] <= x) lo = mid + 1; else hi = mid; }
    return lo;
  }
  var drawnSegments = 0;
  function update() {
    stateNow = stateAt(tFrac);
    var gi = stateNow >= 0 ? S[SS * stateNow + 13] : NP;
    drawnSegments = 0;
    layers.forEach(function (L) {
      var n = countLE(L.segEnd, gi);
      drawnSegments += n;
      L.geom.setDrawRange(0, 6 * n);
      L.mesh.visible = L.visible;
    });
    mandrel.visible = cbMandrel.checked;
    cutGroup.visible = cbCut.checked;
    var machineFrame = frameSel.value === 'machine';
    eyeSoFar.visible = cbEye.checked && !machineFrame;
    eyeAll.visible = cbEyeAll.checked && !machineFrame;
    eyeMachine.visible = (cbEye.checked || cbEyeAll.checked) && machineFrame;
    if (stateNow >= 0) {
      var o = SS * stateNow;
      eyeBall.position.set(S[o + 6], S[o + 7], S[o + 8]);
      var fa = fg.attributes.position.array;
      fa[0] = S[o + 9]; fa[1] = S[o + 10]; fa[2] = S[o + 11];
      fa[3] = S[o + 6]; fa[4] = S[o + 7]; fa[5] = S[o + 8];
      fg.attributes.position.needsUpdate = true;
      fg.computeBoundingSphere();
      epg2.setDrawRange(0, stateNow + 1);
      mpg.setDrawRange(0, cbEyeAll.checked ? NS : stateNow + 1);
      root.rotation.x = frameSel.value === 'machine' ? S[o + 1] * Math.PI / 180 : 0;
      axesBox.innerHTML = '';
      var rows = [['t', S[o].toFixed(2) + ' s of ' + D.wind_time.toFixed(1) + ' s'],
                  ['circuit', String(circuitOfPoint(S[o + 13]))],
                  ['A', S[o + 1].toFixed(2) + ' deg'], ['X', S[o + 2].toFixed(2) + ' mm'],
                  ['Y', S[o + 3].toFixed(2) + ' mm'], ['B', S[o + 4].toFixed(2) + ' deg'],
                  ['F', S[o + 5].toFixed(1) + ' ' + D.feed_unit],
                  ['free fibre', S[o + 12].toFixed(1) + ' mm']];
      var t = el('table', {}, axesBox);
      rows.forEach(function (r) { var tr = el('tr', {}, t); el('td', {}, tr, r[0]); el('td', {}, tr, r[1]); });
    }
    render();
  }
  function circuitOfPoint(gi) {
    for (var k = circuits.length - 1; k >= 0; --k) if (circuits[k].first <= gi) return circuits[k].index;
    return 0;
  }

  // ---- camera and orbit control (three r111 in Debian has no examples/js OrbitControls) ----
  var orbit = { az: 0, el: 0, dist: 1, target: bs.center.clone() };
  // The default view: from azimuth -35 deg, elevation 25 deg, framed on the mandrel's extent as
  // seen from there (tighter than its bounding sphere for long or bent shapes).
  function resetView() {
    orbit.az = (params.view !== undefined ? parseFloat(params.view) : -35) * Math.PI / 180;
    orbit.el = 25 * Math.PI / 180;
    var ce = Math.cos(orbit.el);
    var fwd = new THREE.Vector3(-ce * Math.sin(orbit.az), -Math.sin(orbit.el), -ce * Math.cos(orbit.az));
    var right = new THREE.Vector3().crossVectors(fwd, new THREE.Vector3(0, 1, 0)).normalize();
    var up = new THREE.Vector3().crossVectors(right, fwd);
    var mp = mg.attributes.position.array, nv = mp.length / 3, step = Math.max(1, Math.floor(nv / 4000));
    var lo = [1e300, 1e300, 1e300], hi = [-1e300, -1e300, -1e300], q = new THREE.Vector3();
    for (var i = 0; i < nv; i += step) {
      q.set(mp[3 * i], mp[3 * i + 1], mp[3 * i + 2]).sub(bs.center);
      var c = [q.dot(right), q.dot(up), q.dot(fwd)];
      for (var k = 0; k < 3; ++k) { lo[k] = Math.min(lo[k], c[k]); hi[k] = Math.max(hi[k], c[k]); }
    }
    if (!(hi[0] > lo[0])) { lo = [-size, -size, -size]; hi = [size, size, size]; }
    orbit.target.copy(bs.center)
        .addScaledVector(right, (lo[0] + hi[0]) / 2).addScaledVector(up, (lo[1] + hi[1]) / 2)
        .addScaledVector(fwd, (lo[2] + hi[2]) / 2);
    // Perspective fit: a point at lateral offsets (x, y) from the target and depth f beyond it
    // stays in view when dist >= max(|x| / tan(hfov/2), |y| / tan(vfov/2)) - f.
    var tv = Math.tan(camera.fov * Math.PI / 360), th = tv * camera.aspect;
    var cx = (lo[0] + hi[0]) / 2, cy = (lo[1] + hi[1]) / 2, cf = (lo[2] + hi[2]) / 2, need = 0;
    for (var i = 0; i < nv; i += step) {
      q.set(mp[3 * i], mp[3 * i + 1], mp[3 * i + 2]).sub(bs.center);
      var x = q.dot(right) - cx, y = q.dot(up) - cy, f = q.dot(fwd) - cf;
      need = Math.max(need, Math.max(Math.abs(x) / th, Math.abs(y) / tv) - f);
    }
    orbit.dist = 1.06 * (need > 0 ? need : size / tv);
  }
  function placeCamera() {
    var ce = Math.cos(orbit.el);
    camera.position.set(orbit.target.x + orbit.dist * ce * Math.sin(orbit.az),
                        orbit.target.y + orbit.dist * Math.sin(orbit.el),
                        orbit.target.z + orbit.dist * ce * Math.cos(orbit.az));
    camera.up.set(0, 1, 0);
    camera.lookAt(orbit.target);
    // Near plane as far out as the model allows: the bands' lifts (hundredths of a mm between
    // circuits) need the depth resolution.
    var off = bs.center.distanceTo(orbit.target);
    camera.near = Math.max(orbit.dist / 100, orbit.dist - 1.05 * reach - off);
    camera.far = orbit.dist + 1.05 * reach + off;
    camera.updateProjectionMatrix();
  }
  var playing = false;
  function render() {
    placeCamera();
    renderer.render(scene, camera);
    if (!playing) {
      console.log('windplan-viewer: frame t=' + tFrac.toFixed(3) + ' segments=' + drawnSegments +
                  ' mode=' + mode + ' frame=' + frameSel.value);
    }
  }
  var userMoved = false;  // the default view is refitted on resize until the user moves it
  function resize() {
    var wv = view.clientWidth || 800, hv = view.clientHeight || 600;
    renderer.setSize(wv, hv);
    camera.aspect = wv / hv;
    if (!userMoved) resetView();
    render();
  }
  var drag = null;
  var canvas = renderer.domElement;
  canvas.addEventListener('contextmenu', function (e) { e.preventDefault(); });
  canvas.addEventListener('mousedown', function (e) {
    drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey };
  });
  window.addEventListener('mouseup', function () { drag = null; });
  window.addEventListener('mousemove', function (e) {
    if (!drag) return;
    userMoved = true;
    var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    if (drag.pan) {
      var k = orbit.dist * 0.0015;
      var right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
      var up = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1);
      orbit.target.addScaledVector(right, -dx * k).addScaledVector(up, dy * k);
    } else {
      orbit.az -= dx * 0.008;
      orbit.el = Math.max(-1.55, Math.min(1.55, orbit.el + dy * 0.008));
    }
    render();
  });
  canvas.addEventListener('wheel', function (e) {
    e.preventDefault();
    userMoved = true;
    orbit.dist *= Math.pow(1.0015, e.deltaY);
    render();
  }, { passive: false });
  canvas.addEventListener('dblclick', function () { userMoved = false; resetView(); render(); });

  // ---- wiring ----
  slider.addEventListener('input', function () { tFrac = slider.value / 1000; update(); });
  modeSel.addEventListener('change', function () { mode = modeSel.value; recolour(); update(); });
  [cbMandrel, cbCut, cbEye, cbEyeAll].forEach(function (c) { c.addEventListener('change', update); });
  frameSel.addEventListener('change', update);
  play.addEventListener('click', function () {
    if (playing) { playing = false; play.textContent = 'play'; update(); return; }
    playing = true;
    play.textContent = 'pause';
    if (tFrac >= 1) tFrac = 0;
    var last = performance.now();
    function step(now) {
      if (!playing) return;
      tFrac = Math.min(1, tFrac + (now - last) / 30000);  // the whole winding in 30 s
      last = now;
      slider.value = Math.round(tFrac * 1000);
      if (tFrac >= 1) { playing = false; play.textContent = 'play'; }
      update();
      if (playing) requestAnimationFrame(step);
    }
    requestAnimationFrame(step);
  });
  window.addEventListener('resize', resize);

  if (params.mode && ['circuit', 'layer', 'angle', 'slippage'].indexOf(params.mode) >= 0) {
    mode = params.mode;
    modeSel.value = mode;
  }
  if (params.frame === 'machine') frameSel.value = 'machine';
  if (params.t !== undefined && isFinite(parseFloat(params.t))) {
    tFrac = Math.max(0, Math.min(1, parseFloat(params.t)));
    slider.value = Math.round(tFrac * 1000);
  }
  window.windplanViewer = {
    setTime: function (f) { tFrac = f; slider.value = Math.round(f * 1000); update(); },
    setMode: function (m) { mode = m; modeSel.value = m; recolour(); update(); }
  };
  var wv0 = view.clientWidth || 800, hv0 = view.clientHeight || 600;
  renderer.setSize(wv0, hv0);
  camera.aspect = wv0 / hv0;
  resetView();
  recolour();
  update();
})();

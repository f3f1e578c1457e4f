// zipmesh view: a minimal WebGL 1 viewer, hand-written because the page may load nothing
// from outside. Orthographic camera as `zipmesh render`'s (azimuth about +Y from +Z toward
// +X, elevation above the XZ plane), flat Lambert shading, edges, singularities as shaded
// point sprites, picking, and the view in the URL hash: #view=AZ,EL&zoom=Z&pick=A,B.
(function () {
  'use strict';
  var D = JSON.parse(document.getElementById('zipmesh-data').textContent);
  var canvas = document.getElementById('view');
  var S = { az: D.view[0], el: D.view[1], zoom: 1, picks: [], errors: [], gl: [], ui: true };
  // S.gl: WebGL's complaints; S.errors: what the URL had that was ignored.
  var ballOf = {}; // vertex number -> index into D.balls
  D.balls.forEach(function (b, i) { ballOf[b[0]] = i; });
  var P = D.positions;
  function pos(v) { return [P[3 * v], P[3 * v + 1], P[3 * v + 2]]; }
  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function cross(a, b) {
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  }
  function norm(a) {
    var l = Math.sqrt(dot(a, a));
    return l > 0 ? [a[0] / l, a[1] / l, a[2] / l] : [0, 0, 0];
  }

  // Triangles (fans of the faces) with their face's Newell normal, and the unique edges.
  var tris = [], triNormals = [], edges = [], seen = {};
  D.faces.forEach(function (f) {
    var n = [0, 0, 0];
    for (var i = 0; i < f.length; i++) {
      var c = cross(pos(f[i]), pos(f[(i + 1) % f.length]));
      n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
      var a = f[i], b = f[(i + 1) % f.length];
      var key = a < b ? a + ',' + b : b + ',' + a;
      if (!seen[key]) { seen[key] = true; edges.push(a, b); }
    }
    n = norm(n);
    for (var j = 1; j + 1 < f.length; j++) { tris.push(f[0], f[j], f[j + 1]); triNormals.push(n); }
  });

  // The scale at zoom 1: the mesh as seen from the first view fills the page but a margin
  // (decided once per page size, so that orbiting keeps the scale).
  var fitted = {};
  function fit(w, h) {
    var key = w + 'x' + h;
    if (fitted[key]) return fitted[key];
    var az = D.view[0] * Math.PI / 180, el = D.view[1] * Math.PI / 180;
    var toward = [Math.cos(el) * Math.sin(az), Math.sin(el), Math.cos(el) * Math.cos(az)];
    var right = [Math.cos(az), 0, -Math.sin(az)], up = cross(toward, right), ext = 0;
    D.faces.forEach(function (f) {
      f.forEach(function (v) {
        var p = pos(v);
        ext = Math.max(ext, Math.abs(dot(p, right)) / w, Math.abs(dot(p, up)) / h);
      });
    });
    fitted[key] = ext > 0 ? 0.45 / ext : 0.47 * Math.min(w, h);
    return fitted[key];
  }
  function camera() {
    var az = S.az * Math.PI / 180, el = S.el * Math.PI / 180;
    var toward = [Math.cos(el) * Math.sin(az), Math.sin(el), Math.cos(el) * Math.cos(az)];
    var right = [Math.cos(az), 0, -Math.sin(az)];
    var up = cross(toward, right);
    var w = canvas.clientWidth || 1, h = canvas.clientHeight || 1;
    var scale = S.zoom * fit(w, h); // CSS pixels per unit
    var light = norm([toward[0] + 0.6 * up[0] - 0.4 * right[0],
      toward[1] + 0.6 * up[1] - 0.4 * right[1], toward[2] + 0.6 * up[2] - 0.4 * right[2]]);
    return { toward: toward, right: right, up: up, w: w, h: h, scale: scale, light: light };
  }
  // A point on the page: x, y in CSS pixels (y down), z toward the eye.
  function project(cam, p) {
    return [cam.w / 2 + cam.scale * dot(p, cam.right), cam.h / 2 - cam.scale * dot(p, cam.up),
      dot(p, cam.toward)];
  }
  function ballPixels(cam) {
    return Math.max(5, Math.min(D.radius * cam.scale, 0.02 * Math.min(cam.w, cam.h) * S.zoom));
  }

  // Whether a face other than those around vertex v lies between v and the eye.
  function hidden(cam, v) {
    var o = pos(v), d = cam.toward;
    for (var t = 0; t < tris.length; t += 3) {
      var a = tris[t], b = tris[t + 1], c = tris[t + 2];
      if (a === v || b === v || c === v) continue;
      var p0 = pos(a), e1 = sub(pos(b), p0), e2 = sub(pos(c), p0);
      var h = cross(d, e2), det = dot(e1, h);
      if (Math.abs(det) < 1e-12) continue;
      var s = sub(o, p0), u = dot(s, h) / det;
      if (u < 0 || u > 1) continue;
      var q = cross(s, e1), w = dot(d, q) / det;
      if (w < 0 || u + w > 1) continue;
      if (dot(e2, q) / det > 1e-6) return true;
    }
    return false;
  }
  // The seen singularity nearest to the page point (x, y), within its ball and a few pixels.
  function pickAt(x, y) {
    var cam = camera(), reach = ballPixels(cam) + 6, found = [];
    D.balls.forEach(function (b) {
      var q = project(cam, pos(b[0])), dist = Math.hypot(q[0] - x, q[1] - y);
      if (dist <= reach) found.push([dist, b[0]]);
    });
    found.sort(function (a, b) { return a[0] - b[0]; });
    for (var i = 0; i < found.length; i++) {
      if (!hidden(cam, found[i][1])) return found[i][1];
    }
    return null;
  }

  // WebGL: buffers and programs.
  var gl = canvas.getContext('webgl', { antialias: true, preserveDrawingBuffer: true });
  if (!gl) { S.gl.push('WebGL is not available'); }
  function shader(type, src) {
    var s = gl.createShader(type);
    gl.shaderSource(s, src);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) S.gl.push(gl.getShaderInfoLog(s));
    return s;
  }
  function program(vs, fs) {
    var p = gl.createProgram();
    gl.attachShader(p, shader(gl.VERTEX_SHADER, vs));
    gl.attachShader(p, shader(gl.FRAGMENT_SHADER, fs));
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) S.gl.push(gl.getProgramInfoLog(p));
    return p;
  }
  function buffer(values) {
    var b = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(values), gl.STATIC_DRAW);
    return b;
  }
  var G = null;
  function setup() {
    var MVP = 'uniform vec3 right, up, toward; uniform vec2 halfSize; uniform float scale;\n' +
      'vec4 place(vec3 p) { return vec4(scale * dot(p, right) / halfSize.x, scale * dot(p, up) / halfSize.y, -0.5 * dot(p, toward), 1.0); }\n';
    var faces = program(MVP + 'attribute vec3 p, n; uniform vec3 light; varying vec3 c;\n' +
      'void main() { gl_Position = place(p); float k = 0.3 + 0.7 * abs(dot(n, light));\n' +
      '  c = k * (dot(n, toward) < 0.0 ? vec3(0.72, 0.76, 0.86) : vec3(0.88, 0.88, 0.86)); }',
      'precision mediump float; varying vec3 c; void main() { gl_FragColor = vec4(c, 1.0); }');
    var lines = program(MVP + 'attribute vec3 p; uniform float lift;\n' +
      'void main() { gl_Position = place(p + lift * toward); }',
      'precision mediump float; uniform vec3 colour; void main() { gl_FragColor = vec4(colour, 1.0); }');
    var balls = program(MVP + 'attribute vec3 p, c; uniform float lift, size; varying vec3 base;\n' +
      'void main() { gl_Position = place(p + lift * toward); gl_PointSize = size; base = c; }',
      'precision mediump float; varying vec3 base;\n' +
      'void main() { vec2 q = 2.0 * gl_PointCoord - 1.0; float r2 = dot(q, q); if (r2 > 1.0) discard;\n' +
      '  vec3 n = vec3(q.x, -q.y, sqrt(1.0 - r2)); vec3 l = normalize(vec3(-0.4, 0.6, 1.0));\n' +
      '  float k = clamp(0.6 + 0.4 * dot(n, l) / l.z, 0.0, 1.2); vec3 c = base * k + vec3(pow(max(dot(n, l), 0.0), 40.0) * 0.5);\n' +
      '  if (r2 > 0.78) c = vec3(0.125); gl_FragColor = vec4(min(c, 1.0), 1.0); }');
    var tp = [], tn = [];
    for (var t = 0; t < tris.length; t++) {
      var n = triNormals[Math.floor(t / 3)], v = tris[t];
      tp.push(P[3 * v], P[3 * v + 1], P[3 * v + 2]);
      tn.push(n[0], n[1], n[2]);
    }
    var ep = [];
    edges.forEach(function (v) { ep.push(P[3 * v], P[3 * v + 1], P[3 * v + 2]); });
    var pp = [], pathCount = 0;
    D.paths.forEach(function (path) {
      for (var i = 0; i + 5 < path.length; i += 3) { pp.push.apply(pp, path.slice(i, i + 6)); pathCount += 2; }
    });
    var bp = [], bc = [];
    D.balls.forEach(function (b) {
      var rgb = D.colours[b[2]].rgb;
      bp.push.apply(bp, pos(b[0]));
      bc.push(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255);
    });
    G = { faces: faces, lines: lines, balls: balls, tp: buffer(tp), tn: buffer(tn), ep: buffer(ep),
      pp: buffer(pp), bp: buffer(bp), bc: buffer(bc), kp: buffer([]), kc: buffer([]),
      pathCount: pathCount };
  }
  function use(prog, cam) {
    gl.useProgram(prog);
    var u = function (name) { return gl.getUniformLocation(prog, name); };
    gl.uniform3fv(u('right'), cam.right);
    gl.uniform3fv(u('up'), cam.up);
    gl.uniform3fv(u('toward'), cam.toward);
    gl.uniform2f(u('halfSize'), cam.w / 2, cam.h / 2);
    gl.uniform1f(u('scale'), cam.scale);
    return u;
  }
  function attribute(prog, name, buf) {
    var a = gl.getAttribLocation(prog, name);
    gl.bindBuffer(gl.ARRAY_BUFFER, buf);
    gl.enableVertexAttribArray(a);
    gl.vertexAttribPointer(a, 3, gl.FLOAT, false, 0, 0);
    return a;
  }
  function draw() {
    if (!gl || !G) return;
    var dpr = window.devicePixelRatio || 1, cam = camera();
    canvas.width = Math.round(cam.w * dpr);
    canvas.height = Math.round(cam.h * dpr);
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(1, 1, 1, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.enable(gl.POLYGON_OFFSET_FILL);
    gl.polygonOffset(1, 1);
    var u = use(G.faces, cam), a = [];
    gl.uniform3fv(u('light'), cam.light);
    a.push(attribute(G.faces, 'p', G.tp), attribute(G.faces, 'n', G.tn));
    gl.drawArrays(gl.TRIANGLES, 0, tris.length);
    a.forEach(function (i) { gl.disableVertexAttribArray(i); });
    gl.disable(gl.POLYGON_OFFSET_FILL);
    u = use(G.lines, cam);
    var edgePixels = Math.min(1, D.radius * cam.scale / 4);
    var grey = 1 - 0.85 * edgePixels; // thin edges fade instead of covering the faces
    gl.uniform3f(u('colour'), grey, grey, grey);
    gl.uniform1f(u('lift'), 0);
    var e = attribute(G.lines, 'p', G.ep);
    gl.drawArrays(gl.LINES, 0, edges.length);
    gl.uniform3f(u('colour'), 0.773, 0.106, 0.490);
    gl.uniform1f(u('lift'), 0.5 * D.radius);
    attribute(G.lines, 'p', G.pp);
    gl.drawArrays(gl.LINES, 0, G.pathCount);
    gl.disableVertexAttribArray(e);
    u = use(G.balls, cam);
    gl.uniform1f(u('lift'), D.radius);
    gl.uniform1f(u('size'), 2 * ballPixels(cam) * dpr);
    a = [attribute(G.balls, 'p', G.bp), attribute(G.balls, 'c', G.bc)];
    gl.drawArrays(gl.POINTS, 0, D.balls.length);
    // The picks: larger, on top.
    var kp = [], kc = [];
    S.picks.forEach(function (v) {
      var rgb = D.colours[D.balls[ballOf[v]][2]].rgb;
      kp.push.apply(kp, pos(v));
      kc.push(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255);
    });
    gl.bindBuffer(gl.ARRAY_BUFFER, G.kp);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(kp), gl.DYNAMIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, G.kc);
    gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(kc), gl.DYNAMIC_DRAW);
    gl.disable(gl.DEPTH_TEST);
    gl.uniform1f(u('size'), 3.2 * ballPixels(cam) * dpr);
    attribute(G.balls, 'p', G.kp);
    attribute(G.balls, 'c', G.kc);
    gl.drawArrays(gl.POINTS, 0, S.picks.length);
    a.forEach(function (i) { gl.disableVertexAttribArray(i); });
  }
  var queued = false;
  function redraw() {
    if (queued) return;
    queued = true;
    window.requestAnimationFrame(function () { queued = false; draw(); });
  }

  // The panels.
  function text(el, tag, s, cls) {
    var n = document.createElement(tag);
    n.textContent = s;
    if (cls) n.className = cls;
    el.appendChild(n);
    return n;
  }
  function legend() {
    var el = document.getElementById('legend');
    text(el, 'h1', D.file);
    text(el, 'div', D.kind + ' mesh, ' + D.vertices + ' vertices, ' + D.faces.length + ' faces, ' +
      D.balls.length + ' interior singularities');
    D.legend.forEach(function (e) {
      var row = text(el, 'div', '', 'row'), c = D.colours[e.colour];
      var sw = text(row, 'span', '', 'swatch');
      sw.style.background = 'rgb(' + c.rgb.join(',') + ')';
      text(row, 'span', c.name + ': ' + e.valences + ' (' + e.count + ')');
    });
    text(el, 'div', 'drag: orbit; wheel: zoom; click two balls: the commands for the pair', 'help');
  }
  function commands() {
    if (S.picks.length < 2) return '';
    var a = S.picks[0], b = S.picks[1], f = D.command_file;
    if (D.kind === 'triangle') {
      return 'zipmesh tri-move ' + f + ' --pair ' + a + ',' + b + ' --direction 0 -o out.obj';
    }
    return 'zipmesh moves ' + f + ' --from ' + a + ' --to ' + b + '\n' +
      'zipmesh zip ' + f + ' --from ' + a + ' --to ' + b + ' --move LS -o out.obj';
  }
  function describe(v) {
    var b = D.balls[ballOf[v]];
    return v + ' (v' + b[1] + ', ' + D.colours[b[2]].name + ')';
  }
  function panel() {
    var el = document.getElementById('pick');
    el.textContent = '';
    if (S.picks.length === 0) text(el, 'div', 'click a singularity to pick it');
    if (S.picks.length === 1) text(el, 'div', 'picked ' + describe(S.picks[0]) + '; click another');
    if (S.picks.length === 2) {
      text(el, 'div', 'picked ' + describe(S.picks[0]) + ' and ' + describe(S.picks[1]) +
        (D.kind === 'triangle' ? ' (directions 0-5: docs/tri-edit.md)'
          : ' (moves lists the four movements LS, RS, LC, RC and which are realizable)'));
      text(el, 'pre', commands());
    }
    S.gl.concat(S.errors).forEach(function (e) { text(el, 'div', e, 'error'); });
  }

  // The URL hash, read and written.
  function readHash() {
    // The hash says everything: what it leaves out is the default.
    S.errors = [];
    S.az = D.view[0]; S.el = D.view[1]; S.zoom = 1; S.picks = []; S.ui = true;
    location.hash.replace(/^#/, '').split('&').forEach(function (kv) {
      if (!kv) return;
      var i = kv.indexOf('='), k = i < 0 ? kv : kv.slice(0, i), v = i < 0 ? '' : decodeURIComponent(kv.slice(i + 1));
      var nums = v.split(',').map(Number), ok = v !== '' && nums.every(isFinite);
      if (k === 'view' && ok && nums.length === 2 && Math.abs(nums[1]) <= 90) { S.az = nums[0]; S.el = nums[1]; }
      else if (k === 'zoom' && ok && nums.length === 1 && nums[0] > 0) { S.zoom = nums[0]; }
      else if (k === 'ui' && (v === '0' || v === '1')) { S.ui = v === '1'; }
      else if (k === 'pick' && ok && nums.length <= 2 && nums.every(function (n) { return n in ballOf; })) { S.picks = nums; }
      else { S.errors.push('ignored in the URL: ' + kv + (k === 'pick' ? ' (not interior singularities)' : '')); }
    });
  }
  function round(x) { return Math.round(x * 100) / 100; }
  function hash() {
    var h = 'view=' + round(S.az) + ',' + round(S.el) + '&zoom=' + round(S.zoom);
    if (S.picks.length) h += '&pick=' + S.picks.join(',');
    return S.ui ? h : h + '&ui=0';
  }
  function writeHash() {
    try { history.replaceState(null, '', '#' + hash()); } catch (e) { /* a file: URL may refuse */ }
  }

  // The state, for scripts and tests: window.zipmeshView and the hidden <pre id="state">.
  function publish() {
    var cam = camera();
    var screen = S.picks.map(function (v) {
      var q = project(cam, pos(v));
      return { vertex: v, x: round(q[0]), y: round(q[1]), hit: pickAt(q[0], q[1]) };
    });
    var state = { ready: !!G && S.gl.length === 0, singularities: D.balls.length, kind: D.kind,
      view: [round(S.az), round(S.el)], zoom: round(S.zoom), picks: S.picks.slice(),
      picked: screen, ball_pixels: round(ballPixels(cam)), command: commands(), hash: hash(),
      errors: S.gl.concat(S.errors) };
    window.zipmeshView = state;
    document.getElementById('state').textContent = JSON.stringify(state);
  }
  // ui=0 in the URL hides the panels (a clean picture of the mesh).
  function panels() {
    ['legend', 'pick'].forEach(function (id) {
      document.getElementById(id).style.display = S.ui ? '' : 'none';
    });
  }
  function changed() { writeHash(); panel(); publish(); redraw(); }

  // Orbit, zoom and picking.
  var drag = null;
  canvas.addEventListener('mousedown', function (e) { drag = { x: e.clientX, y: e.clientY, moved: 0 }; });
  window.addEventListener('mousemove', function (e) {
    if (!drag) return;
    var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.moved += Math.abs(dx) + Math.abs(dy);
    drag.x = e.clientX; drag.y = e.clientY;
    S.az = ((S.az - 0.4 * dx) % 360 + 540) % 360 - 180;
    S.el = Math.max(-90, Math.min(90, S.el + 0.4 * dy));
    redraw();
  });
  window.addEventListener('mouseup', function (e) {
    if (!drag) return;
    var click = drag.moved < 4;
    drag = null;
    if (click) {
      var r = canvas.getBoundingClientRect(), v = pickAt(e.clientX - r.left, e.clientY - r.top);
      if (v !== null) {
        var i = S.picks.indexOf(v);
        if (i >= 0) S.picks.splice(i, 1);
        else if (S.picks.length === 2) S.picks = [v];
        else S.picks.push(v);
      }
    }
    changed();
  });
  canvas.addEventListener('wheel', function (e) {
    e.preventDefault();
    S.zoom = Math.max(0.1, Math.min(100, S.zoom * Math.exp(-0.0015 * e.deltaY)));
    changed();
  }, { passive: false });
  window.addEventListener('resize', function () { publish(); redraw(); });
  window.addEventListener('hashchange', function () {
    if (location.hash.slice(1) === hash()) return;
    readHash(); panels(); panel(); publish(); redraw();
  });

  readHash();
  if (gl) setup();
  legend();
  panels();
  panel();
  draw();
  publish();
})();

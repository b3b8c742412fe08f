// The explorer's page. Every state is a list of `-D key=value` overrides, exactly as
// `shadowref render` takes them: the server renders the state, and the same -D values on the
// command line give the same picture. Two frame requests are out at a time, so the server renders
// the next frame while it sends this one and the browser decodes and draws the one before; input
// that arrives meanwhile only marks the state as changed, so the newest state is rendered next, no
// stale frame queues up, and a frame older than the one shown is dropped.
'use strict';

const $ = (id) => document.getElementById(id);
const exported = window.SHADOWREF_EXPORT || null;

// Figures for the benchmark and the browser test (tests/browser/explore_bench.mjs, explore.test.mjs).
const exploreStats = { framesShown: 0, serverMs: [], encodeMs: [], latencyMs: [], errors: 0, superseded: 0 };
window.exploreStats = exploreStats;

let scene = null;      // the scene's values as the server summarised them (/api/scene)
let initial = null;    // the state the page started in: a setting is sent only when it differs
const state = {
  eye: [0, 0, 5], target: [0, 0, 0],
  method: 'none', twoSided: true, wrap: true, darken: false, mapSize: 1024, pcf: 1,
  lights: [],          // {name, type, on, position, direction, soft}
  light: 0,            // the light the sliders move
  view: 'frame', index: 0, signed: false,
};
let cameraMoved = false;
let lastImage = null;   // {width, height, values, valueName, info}
let lastInfo = {};      // the X-Info of the frame shown: {text, info, view}

// ---- numbers as the command line gets them: at most 4 decimals, no trailing zeros
const num = (v) => String(Number(Number(v).toFixed(4)));
const vec = (v) => '[' + v.map(num).join(',') + ']';

function overrides() {
  const d = [];
  if (cameraMoved) {
    d.push('camera.eye=' + vec(state.eye));
    d.push('camera.target=' + vec(state.target));
  }
  if (state.method !== initial.method) d.push('shadow.method=' + state.method);
  if (state.twoSided !== initial.twoSided) d.push('shadow.two_sided=' + state.twoSided);
  if (state.wrap !== initial.wrap) d.push('shadow.wrap=' + state.wrap);
  if (state.darken !== initial.darken) d.push('shadow.darken_composite=' + state.darken);
  if (state.mapSize !== initial.mapSize) d.push('shadow.map_size=' + state.mapSize);
  if (state.pcf !== initial.pcf) d.push('shadow.pcf=' + state.pcf);
  state.lights.forEach((l, i) => {
    const first = initial.lights[i];
    if (!l.on) { d.push('lights.' + l.name + '=off'); return; }
    if (l.type !== 'directional' && vec(l.position) !== vec(first.position)) d.push('lights.' + l.name + '.position=' + vec(l.position));
    if (l.type !== 'point' && vec(l.direction) !== vec(first.direction)) d.push('lights.' + l.name + '.direction=' + vec(l.direction));
    if (l.soft !== first.soft) d.push('lights.' + l.name + '.soft.shape=' + l.soft);
  });
  return d;
}

function query(extra) {
  const parts = overrides().map((o) => 'D=' + encodeURIComponent(o));
  for (const [k, v] of Object.entries(extra || {})) parts.push(k + '=' + encodeURIComponent(v));
  return parts.join('&');
}

function showError(text) {
  const box = $('error');
  box.hidden = !text;
  box.textContent = text || '';
}

// ---- frames. The server renders one request at a time. Two requests are out at a time: while the
// server renders one, the next waits at the server, so that it starts the moment the last is done,
// and the browser receives, decodes and draws the frame before; with one out, the server waited a
// round trip for every frame. Input only marks the state as changed: however many mouse moves
// arrive meanwhile, the next request asks for the newest state, and a frame older than the one
// shown is dropped. The server answers a request that waited while a newer one arrived with 204
// and renders only the newer; should the two arrive the other way round, the newest state is the
// one answered 204, and it is asked for again.
let inFlight = 0;       // requests whose answers have not arrived
const kMaxInFlight = 2;
let decoding = 0;       // answers being received, decoded and drawn, or waiting to be
const kMaxDecoding = 2;  // more would only queue behind the decoder
let dirty = false, version = 0, shownVersion = 0, askedVersion = 0;
let statusShown = -Infinity;  // when the server's time was last written under the title
const inputTimes = new Map();  // state version -> time of the input that made it
// For the tests: whether the picture shows the newest state, and the state's -D values.
window.exploreIdle = () => inFlight === 0 && decoding === 0 && !dirty;
window.exploreOverrides = () => overrides();

function changed() {
  version += 1;
  inputTimes.set(version, performance.now());
  dirty = true;
  pump();
}

function pump() {
  if (!dirty || inFlight >= kMaxInFlight || decoding >= kMaxDecoding) return;
  dirty = false;
  inFlight += 1;
  const asked = version;
  askedVersion = asked;
  const d = overrides();
  $('state').textContent = d.map((o) => '-D ' + o).join(' ') || '(the scene as written)';
  // PNG for pictures without per-pixel values: a fraction of the bytes, decoded off the page's
  // thread; the server sends raw pixels and values for the views that have values.
  const params = { view: state.view, seq: asked, encoding: 'png' };
  if (['stencil', 'shadowmap', 'visibility', 'pass'].includes(state.view)) params.index = state.index;
  if (state.signed) params.signed = 1;
  fetch('api/frame?' + query(params), { cache: 'no-store' }).then(
    (response) => receive(asked, response),
    (e) => {
      inFlight -= 1;
      exploreStats.errors += 1;
      showError('the server does not answer: ' + e);
    });
}

// A PNG frame as a picture to draw: createImageBitmap decodes the response's Blob on a worker thread
// into the form the canvas draws without converting it again. The frames are opaque and carry no
// colour profile, so neither premultiplying nor colour management changes a byte: the canvas holds
// the rendered bytes.
async function decodePng(response) {
  return createImageBitmap(await response.blob());
}

// Answers are decoded and drawn one after the other, in the order they were asked for: decoded
// side by side, a later frame could be ready first and the earlier one, rendered for nothing,
// would be dropped.
let decoded = Promise.resolve();
function receive(asked, response) {
  inFlight -= 1;
  decoding += 1;
  pump();  // the newest state renders while this frame is decoded and drawn
  decoded = decoded.then(() => show(asked, response));
}

async function show(asked, response) {
  try {
    if (response.status === 204 || asked < shownVersion) {
      exploreStats.superseded += 1;  // a newer state was asked for, or is shown already
      if (response.status === 204 && asked === askedVersion && asked > shownVersion) dirty = true;
    } else if (!response.ok) {
      exploreStats.errors += 1;
      showError(await response.text());
    } else {
      const png = (response.headers.get('Content-Type') || '').startsWith('image/png');
      const picture = png ? await decodePng(response) : await response.arrayBuffer();
      if (asked > shownVersion) {
        showError('');
        drawFrame(response.headers, picture);
        exploreStats.framesShown += 1;
        exploreStats.serverMs.push(Number(response.headers.get('X-Load-Ms')) + Number(response.headers.get('X-Render-Ms')));
        exploreStats.encodeMs.push(Number(response.headers.get('X-Encode-Ms')));
        // Latency: from the oldest input this frame is the first to show (the one waited for longest).
        let oldest = Infinity;
        for (const [k, t] of inputTimes) if (k <= asked) { oldest = Math.min(oldest, t); inputTimes.delete(k); }
        if (oldest !== Infinity) exploreStats.latencyMs.push(performance.now() - oldest);
        shownVersion = asked;
        // A few times a second: text changed with every frame would be laid out with every frame.
        const now = performance.now();
        if (now - statusShown > 250) {
          const threads = Number(response.headers.get('X-Threads'));
          $('status').textContent = 'server ' + exploreStats.serverMs[exploreStats.serverMs.length - 1].toFixed(1) + ' ms, ' +
            threads + (threads === 1 ? ' thread' : ' threads');
          statusShown = now;
        }
      } else {
        if (picture.close) picture.close();
        exploreStats.superseded += 1;
      }
    }
  } catch (e) {
    exploreStats.errors += 1;
    showError('the server does not answer: ' + e);
  }
  decoding -= 1;
  pump();
}

// `picture`: an ImageBitmap (PNG) or an ArrayBuffer of RGBA pixels, then the values if any.
function drawFrame(headers, picture) {
  const width = Number(headers.get('X-Width')), height = Number(headers.get('X-Height'));
  const infoText = headers.get('X-Info') || '{}';
  const info = infoText === lastInfo.text ? lastInfo.info : JSON.parse(infoText);
  const valueName = headers.get('X-Values') || '';
  const raw = picture instanceof ArrayBuffer;
  const values = raw && valueName ? new Float32Array(picture, width * height * 4, width * height) : null;
  const canvas = $('image');
  if (canvas.width !== width || canvas.height !== height) {
    canvas.width = $('marks').width = width;
    canvas.height = $('marks').height = height;
  }
  const context = canvas.getContext('2d');
  if (raw) {
    context.putImageData(new ImageData(new Uint8ClampedArray(picture, 0, width * height * 4), width, height), 0, 0);
  } else {
    context.drawImage(picture, 0, 0);
    picture.close();
  }
  const viewChanged = !lastImage || valueName !== lastImage.valueName || state.view !== lastInfo.view;
  lastImage = { width, height, values, valueName, info };
  if (mouseOver && (values || viewChanged)) probe(mouseOver);
  // The markers of the state of this frame or later, drawn with it: redrawn with every mouse move
  // while orbiting, the overlay was drawn and composited two to three times for every frame shown.
  drawLightMarks();
  // While orbiting, the key stays the same frame after frame: rebuilt only when it changes.
  if (infoText !== lastInfo.text || state.view !== lastInfo.view) {
    showKey(info);
    updateIndexChoices(info);
  }
  lastInfo = { text: infoText, info, view: state.view };
}

// ---- the key of a view: the stencil legend (only the counts present) or the range's colour bar
function showKey(info) {
  const legend = $('legend');
  legend.textContent = '';
  for (const entry of info.legend || []) {
    const item = document.createElement('span');
    const swatch = document.createElement('i');
    swatch.style.background = 'rgb(' + entry.rgb.join(',') + ')';
    item.append(swatch, String(entry.count));
    legend.append(item);
  }
  // The lines over a shadow map: the camera frustum, and TSM's trapezoid in its unwarped view.
  for (const line of info.outlines || []) {
    const item = document.createElement('span');
    item.className = 'outline';
    const swatch = document.createElement('i');
    swatch.style.background = 'rgb(' + line.rgb.join(',') + ')';
    item.append(swatch, line.what);
    legend.append(item);
  }
  const bar = $('colourbar');
  bar.hidden = !info.range;
  if (info.range) {
    const c = $('bar').getContext('2d');
    // The view's colour map (viridis for depths and many counts), else a grey ramp.
    for (let i = 0; i < 256; i++) {
      const rgb = info.ramp ? info.ramp[i] : [i, i, i];
      c.fillStyle = 'rgb(' + rgb.join(',') + ')';
      c.fillRect(i, 0, 1, 12);
    }
    $('bar-lo').textContent = Number(info.range[0]).toPrecision(5);
    $('bar-hi').textContent = Number(info.range[1]).toPrecision(5);
  }
  $('strip').hidden = state.view !== 'pass';
  if (info.passes) {
    $('pass').max = String(info.passes.length - 1);
    $('pass-name').textContent = state.view === 'pass' ? (info.pass || '') : '';
  }
}

function updateIndexChoices(info) {
  const select = $('index');
  let names = [];
  if (state.view === 'stencil') names = (info.passes || []).filter((p) => p.includes('-stencil-')).map((p) => p.split('-stencil-')[1]);
  else if (state.view === 'shadowmap') names = info.shadowMaps || [];
  else if (state.view === 'visibility') names = info.lights || [];
  $('index-label').hidden = names.length === 0;
  const text = names.join('\n');
  if (select.dataset.names === text) return;
  select.dataset.names = text;
  select.textContent = '';
  names.forEach((n, i) => select.append(new Option(n, String(i))));
  select.value = String(Math.min(state.index, Math.max(0, names.length - 1)));
}

// ---- the value under the mouse and the pixel it is
function pixelAt(event) {
  const canvas = $('image');
  const rect = canvas.getBoundingClientRect();
  const col = Math.floor((event.clientX - rect.left) * canvas.width / rect.width);
  const row = Math.floor((event.clientY - rect.top) * canvas.height / rect.height);
  if (col < 0 || row < 0 || col >= canvas.width || row >= canvas.height) return null;
  return { col, row, x: col, y: canvas.height - 1 - row };  // y: framebuffer row, 0 at the bottom
}

// The mouse over the picture ({clientX, clientY}, null when it left): a frame of another view
// shows its value there without waiting for the mouse to move.
let mouseOver = null;

function probe(event) {
  mouseOver = { clientX: event.clientX, clientY: event.clientY };
  const p = pixelAt(event);
  if (!p || !lastImage) return;
  let text = 'pixel ' + p.x + ',' + p.y + ' (row 0 is the bottom)';
  if (lastImage.values) {
    const v = lastImage.values[p.row * lastImage.width + p.col];
    text += '  ' + lastImage.valueName + ' ' + (Number.isFinite(v) ? Number(v.toPrecision(6)) : 'nothing drawn');
  }
  $('probe').textContent = text;
}

// ---- camera: orbit about the target, pan, zoom, walk
const sub = (a, b) => a.map((v, i) => v - b[i]);
const add = (a, b) => a.map((v, i) => v + b[i]);
const scale = (a, s) => a.map((v) => v * s);
const length = (a) => Math.hypot(...a);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normal = (a) => scale(a, 1 / (length(a) || 1));

function orbit(dx, dy) {
  const offset = sub(state.eye, state.target);
  const r = length(offset);
  let yaw = Math.atan2(offset[0], offset[2]);
  let pitch = Math.asin(Math.max(-1, Math.min(1, offset[1] / r)));
  yaw -= dx * 0.01;
  pitch = Math.max(-1.5, Math.min(1.5, pitch + dy * 0.01));
  state.eye = add(state.target, [r * Math.cos(pitch) * Math.sin(yaw), r * Math.sin(pitch), r * Math.cos(pitch) * Math.cos(yaw)]);
  cameraMoved = true;
  changed();
}

function pan(dx, dy) {
  const forward = normal(sub(state.target, state.eye));
  const right = normal(cross(forward, [0, 1, 0]));
  const up = cross(right, forward);
  const r = length(sub(state.eye, state.target));
  const move = add(scale(right, -dx * r * 0.002), scale(up, dy * r * 0.002));
  state.eye = add(state.eye, move);
  state.target = add(state.target, move);
  cameraMoved = true;
  changed();
}

function zoom(factor) {
  const offset = sub(state.eye, state.target);
  if (length(offset) * factor < 0.01) return;
  state.eye = add(state.target, scale(offset, factor));
  cameraMoved = true;
  changed();
}

function walk(step) {
  const forward = normal(sub(state.target, state.eye));
  const move = scale(forward, step * Math.max(0.05, length(sub(state.eye, state.target)) * 0.05));
  state.eye = add(state.eye, move);
  state.target = add(state.target, move);
  cameraMoved = true;
  changed();
}

// ---- pixel history: every fragment, clear and shadow-map lookup, from the server's
// views::PixelHistory (the one `shadowref render --pixel-history` prints), and why the pixel is
// what it is
async function history(p) {
  if (state.view === 'shadowmap') {  // a texel of the light's map, not a pixel of the frame
    $('history').textContent = 'A shadow map shows the light\'s view: click a pixel of a camera view (frame, stencil, depth ...) ' +
      'for its history; its lookups name the texels they read.';
    return;
  }
  $('history').textContent = 'rendering the history of pixel ' + p.x + ',' + p.y + ' ...';
  const params = { x: p.x, y: p.y };
  if (state.signed) params.signed = 1;
  const response = await fetch('api/history?' + query(params));
  if (!response.ok) { $('history').textContent = await response.text(); return; }
  showHistory(await response.json());
}

const lightLabel = (s) => s.light ? s.light + (s.lightName ? " '" + s.lightName + "'" : '') : '';

function lookupText(l) {
  let text = 'lookup ' + l.light + " '" + l.lightName + "'" + (l.face !== undefined ? ' cube face ' + l.face : '') +
    ': strq (' + l.strq.map((v) => Number(v.toPrecision(6))).join(', ') + ')  s,t,r (' +
    l.str.map((v) => Number(v.toPrecision(6))).join(', ') + ')';
  if (l.texel) {
    text += '  texel (' + l.texel.join(', ') + ') of ' + l.mapSize.join('x') + '  stored D ' + Number(l.stored.toPrecision(9)) +
      '  compared r ' + Number(l.compared.toPrecision(9)) + (l.passed ? ' <= D: lit' : ' > D: shadowed');
    if (l.pcf > 1) text += '  (nearest texel; ' + l.pcf + 'x' + l.pcf + ' PCF mean)';
  } else {
    text += '  ' + l.outcome;
  }
  return text + '  result ' + Number(l.result.toPrecision(6));
}

// One sentence per light: the stencil its lit pass found (shadow volumes), or what the visible
// fragment's lookup into its map compared (shadow maps).
function verdict(h) {
  const lines = [];
  const fragments = h.steps.filter((s) => s.type === 'fragment');
  const lights = [...new Set(h.steps.map((s) => s.light).filter((l) => l))];
  for (const light of lights) {
    const mine = fragments.filter((f) => f.light === light);
    const label = lightLabel(mine[0] || h.steps.find((s) => s.light === light));
    const lit = mine.filter((f) => f.pass.includes('lit'));
    const volume = mine.filter((f) => f.pass.includes('stencil'));
    const clear = h.steps.find((s) => s.type === 'clear' && s.light === light && s.stencil);
    const count = lit.length ? lit[0].stencilBefore : volume.length ? volume[volume.length - 1].stencilAfter : null;
    if (lit.some((f) => f.stencilTest && f.depthTest))
      lines.push('lit by ' + label + ': the stencil held 0 when its lit pass was drawn, so the lit pass reached the pixel');
    else if (lit.some((f) => !f.stencilTest))
      lines.push('in the shadow of ' + label + ': ' + (clear ? 'cleared to ' + clear.stencil[1] + ', ' : '') + volume.length +
        ' volume fragments left the stencil at ' + count + ' (not 0), so the stencil test of its lit pass failed');
    else if (volume.length) lines.push(label + ': ' + volume.length + ' volume fragments left the stencil at ' + count);
  }
  // Shadow maps: the last shaded fragment is the one seen; its lookups say lit or shadowed.
  const shaded = fragments.filter((f) => f.lookups && f.depthTest);
  if (shaded.length) {
    for (const l of shaded[shaded.length - 1].lookups) {
      const who = l.light + " '" + l.lightName + "'";
      if (!l.texel) lines.push('lit by ' + who + ': ' + l.outcome);
      else if (l.passed) lines.push('lit by ' + who + ': r = ' + Number(l.compared.toPrecision(7)) + ' is not farther than the stored D = ' +
        Number(l.stored.toPrecision(7)) + ' at texel (' + l.texel.join(', ') + ')');
      else lines.push('in the shadow of ' + who + ': r = ' + Number(l.compared.toPrecision(7)) + ' lies behind the stored D = ' +
        Number(l.stored.toPrecision(7)) + ' at texel (' + l.texel.join(', ') + '): something nearer the light covers it');
    }
  }
  for (const [name, v] of Object.entries(h.visibility || {})) lines.push('visibility of ' + name + ': ' + v);
  return lines;
}

function showHistory(h) {
  const box = $('history');
  box.textContent = '';
  const title = document.createElement('h2');
  title.textContent = 'pixel ' + h.x + ',' + h.y + ': ' + h.fragments + ' fragments, final colour (' + h.colour.join(', ') + ')' +
    '; stencil ' + (h.signed ? 'signed' : 'unsigned');
  box.append(title);
  for (const line of verdict(h)) {
    const p = document.createElement('p');
    p.className = 'why';
    p.textContent = line;
    box.append(p);
  }
  const table = document.createElement('table');
  const head = ['#', 'pass', 'light', 'draw', 'object', 'facing', 'z', 'stored z', 'stencil test', 'depth test', 'stencil', 'colour'];
  table.append(row(head, 'th'));
  let n = 0;
  for (const s of h.steps) {
    if (s.type === 'clear') {
      const what = [];
      if (s.stencil) what.push('stencil ' + s.stencil[0] + ' → ' + s.stencil[1]);
      if (s.depth) what.push('depth ' + s.depth[0] + ' → ' + s.depth[1]);
      if (s.colour) what.push('colour');
      const r = row(['', s.pass, lightLabel(s) || '-', 'clear', what.join(', ')], 'td');
      r.className = 'clear';
      r.lastChild.colSpan = head.length - 4;
      table.append(r);
      continue;
    }
    const r = row([n++, s.pass, lightLabel(s) || '-', s.draw, s.what, s.facing, s.depth.toPrecision(7), s.storedDepth.toPrecision(7),
      s.stencilTest ? 'pass' : 'FAIL', s.depthTest === null ? '-' : s.depthTest ? 'pass' : 'FAIL',
      s.stencilBefore + ' → ' + s.stencilAfter, s.colour ? s.colour.map((c) => c.toFixed(3)).join(' ') : ''], 'td');
    r.className = 'fragment';
    r.children[8].className = s.stencilTest ? 'pass' : 'fail';
    r.children[9].className = s.depthTest ? 'pass' : 'fail';
    table.append(r);
    for (const l of s.lookups || []) {
      const lr = row(['', '', l.light, '', lookupText(l)], 'td');
      lr.className = 'lookup ' + (l.result < 1 ? 'fail' : 'pass');
      lr.lastChild.colSpan = head.length - 4;
      table.append(lr);
    }
  }
  box.append(table);
}

function row(cells, tag) {
  const tr = document.createElement('tr');
  for (const c of cells) {
    const td = document.createElement(tag);
    td.textContent = String(c);
    tr.append(td);
  }
  return tr;
}

// ---- lights on the picture: a marker at each point and spot light, dragged to move the light
// parallel to the picture plane (its distance along the view axis kept). The projection is the
// camera's (gluPerspective with the scene's vertical field of view and up vector, as the server
// renders it), so a marker sits on the light in a camera view.
function cameraBasis() {
  const f = normal(sub(state.target, state.eye));
  const r = normal(cross(f, scene.camera.up));
  const u = cross(r, f);
  const canvas = $('image');
  const tanY = Math.tan(scene.camera.fov * Math.PI / 360);
  return { f, r, u, tanY, tanX: tanY * canvas.width / canvas.height, width: canvas.width, height: canvas.height };
}

function projectPoint(p) {
  const c = cameraBasis();
  const d = sub(p, state.eye);
  const z = dot(d, c.f);
  if (!(z > scene.camera.near)) return null;
  const x = dot(d, c.r) / (z * c.tanX), y = dot(d, c.u) / (z * c.tanY);
  return { col: (x + 1) / 2 * c.width, row: (1 - y) / 2 * c.height, z };
}

function unprojectPoint(col, row, z) {
  const c = cameraBasis();
  const x = col / c.width * 2 - 1, y = 1 - row / c.height * 2;
  return add(state.eye, add(scale(c.f, z), add(scale(c.r, x * z * c.tanX), scale(c.u, y * z * c.tanY))));
}

const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
// The markers show on the pictures the camera sees, not on a shadow map.
const cameraPicture = () => scene && !exported && state.view !== 'shadowmap' && $('image').width === scene.width &&
  $('image').height === scene.height;
const kMarkerRadius = 7;

function lightMarkers() {
  if (!cameraPicture()) return [];
  const marks = [];
  state.lights.forEach((l, i) => {
    if (l.type === 'directional') return;
    const p = projectPoint(l.position);
    if (p) marks.push({ i, ...p });
  });
  return marks;
}

let drawnMarks = '';
function drawLightMarks() {
  const marks = lightMarkers();
  const key = JSON.stringify([marks, state.lights.map((l) => l.on), state.light]);
  if (key !== drawnMarks) {
    drawnMarks = key;
    const canvas = $('marks');
    const g = canvas.getContext('2d');
    g.clearRect(0, 0, canvas.width, canvas.height);
    for (const m of marks) {
      const l = state.lights[m.i];
      g.beginPath();
      g.arc(m.col, m.row, kMarkerRadius, 0, 2 * Math.PI);
      g.lineWidth = m.i === state.light ? 3 : 1.5;
      g.strokeStyle = '#000';
      g.stroke();
      g.lineWidth = m.i === state.light ? 1.5 : 1;
      g.strokeStyle = '#ffd84a';
      g.stroke();
      if (l.on) { g.fillStyle = 'rgba(255, 216, 74, 0.5)'; g.fill(); }
      g.font = '12px sans-serif';
      g.fillStyle = '#ffd84a';
      g.fillText(l.name + (l.on ? '' : ' (off)'), m.col + kMarkerRadius + 3, m.row + 4);
    }
  }
}

function wireLightDrag() {
  const canvas = $('image');
  let dragging = null;
  const canvasPoint = (e) => {
    const rect = canvas.getBoundingClientRect();
    return [(e.clientX - rect.left) * canvas.width / rect.width, (e.clientY - rect.top) * canvas.height / rect.height];
  };
  // Captured on the way down to the picture: a press on a marker moves the light, not the camera.
  $('stage').addEventListener('mousedown', (e) => {
    if (e.button !== 0) return;
    const [col, row] = canvasPoint(e);
    const hit = lightMarkers().find((m) => Math.hypot(m.col - col, m.row - row) <= kMarkerRadius + 2);
    if (!hit) return;
    e.stopPropagation();
    e.preventDefault();
    selectLight(hit.i);
    dragging = { i: hit.i, z: hit.z };
  }, { capture: true });
  window.addEventListener('mousemove', (e) => {
    if (!dragging) return;
    const [col, row] = canvasPoint(e);
    const l = state.lights[dragging.i];
    l.position = unprojectPoint(col, row, dragging.z);
    selectLight(dragging.i);
    changed();
  });
  window.addEventListener('mouseup', () => { dragging = null; });
}
// For the tests: where light i's marker is on the picture (canvas pixels), or null.
window.exploreLightMarker = (i) => lightMarkers().find((m) => m.i === i) || null;

// ---- controls
function fillSelect(select, values, labels) {
  select.textContent = '';
  values.forEach((v, i) => select.append(new Option(labels ? labels[i] : String(v), String(v))));
}

function stencilMethod() {
  const m = scene.methods.find((x) => x.name === state.method);
  return m && m.stencil;
}

function fillViews() {
  const views = [['frame', 'frame']];
  if (stencilMethod()) views.push(['stencil', 'stencil counts'], ['volumes', 'volumes'], ['overlay', 'translucent volumes']);
  views.push(['depth', 'depth']);
  if (state.method === 'shadowmap' || state.method === 'tsm') views.push(['shadowmap', 'shadow map']);
  views.push(['visibility', 'visibility'], ['pass', 'passes']);
  fillSelect($('view'), views.map((v) => v[0]), views.map((v) => v[1]));
  if (!views.some((v) => v[0] === state.view)) state.view = 'frame';
  $('view').value = state.view;
  $('signed-label').hidden = !['stencil', 'pass'].includes(state.view);
}

// The method controls of the shadow.* keys the method does not read are disabled: they would
// change nothing in its frames (the registry's list; render's flags for them are errors).
const settingControls = [['two-sided', 'two_sided'], ['wrap', 'wrap'], ['darken', 'darken_composite'],
  ['map-size', 'map_size'], ['pcf', 'pcf']];

function offerSettings() {
  const m = scene.methods.find((x) => x.name === state.method);
  const reads = m ? m.settings : [];
  for (const [id, key] of settingControls) {
    const control = $(id);
    control.disabled = !reads.includes(key);
    const users = scene.methods.filter((x) => x.settings.includes(key)).map((x) => x.name);
    control.closest('label').title = control.disabled
      ? 'shadow.' + key + ': ' + state.method + ' does not read it (' + users.join(', ') + ' do)'
      : 'shadow.' + key;
  }
}

function setMethod(name) {
  state.method = name;
  $('method').value = name;
  fillViews();
  offerSettings();
  changed();
}

function setView(name) {
  state.view = name;
  state.index = 0;
  fillViews();
  changed();
}

function selectLight(i) {
  const another = i !== state.light;
  state.light = i;
  $('light').value = String(i);
  if (another) drawLightMarks();  // the selected light's marker is drawn bold; no frame is asked for
  const l = state.lights[i];
  const b = scene.bounds;
  // A directional light has no position, a point light no direction (the scene format's rule).
  $('light-position').hidden = l.type === 'directional';
  $('light-direction').hidden = l.type === 'point';
  ['lx', 'ly', 'lz'].forEach((id, k) => {
    const input = $(id);
    input.min = String(Math.min(b.min[k], l.position[k]));
    input.max = String(Math.max(b.max[k], l.position[k]));
    input.value = String(l.position[k]);
  });
  ['dx', 'dy', 'dz'].forEach((id, k) => { $(id).value = String(l.direction[k]); });
  $('soft').value = l.soft;
}

function fillLights() {
  const box = $('lights');
  box.textContent = '';
  state.lights.forEach((l, i) => {
    const label = document.createElement('label');
    const box2 = document.createElement('input');
    box2.type = 'checkbox';
    box2.checked = l.on;
    box2.addEventListener('change', () => { l.on = box2.checked; changed(); });
    label.append(box2, ' ' + l.name + ' (' + l.type + ')');
    box.append(label);
  });
  fillSelect($('light'), state.lights.map((l, i) => i), state.lights.map((l) => l.name));
  fillSelect($('soft'), scene.softShapes);
  if (state.lights.length) selectLight(0);
}

function wireControls() {
  $('method').addEventListener('change', (e) => setMethod(e.target.value));
  $('two-sided').addEventListener('change', (e) => { state.twoSided = e.target.checked; changed(); });
  $('wrap').addEventListener('change', (e) => { state.wrap = e.target.checked; changed(); });
  $('darken').addEventListener('change', (e) => { state.darken = e.target.checked; changed(); });
  $('map-size').addEventListener('change', (e) => { state.mapSize = Number(e.target.value); changed(); });
  $('pcf').addEventListener('change', (e) => { state.pcf = Number(e.target.value); changed(); });
  $('view').addEventListener('change', (e) => { if (!exported) setView(e.target.value); });
  $('index').addEventListener('change', (e) => { state.index = Number(e.target.value); changed(); });
  $('signed').addEventListener('change', (e) => { state.signed = e.target.checked; changed(); });
  $('pass').addEventListener('input', (e) => { state.index = Number(e.target.value); changed(); });
  $('light').addEventListener('change', (e) => selectLight(Number(e.target.value)));
  $('soft').addEventListener('change', (e) => { state.lights[state.light].soft = e.target.value; changed(); });
  ['lx', 'ly', 'lz'].forEach((id, k) => $(id).addEventListener('input', (e) => {
    state.lights[state.light].position[k] = Number(e.target.value);
    changed();
  }));
  ['dx', 'dy', 'dz'].forEach((id, k) => $(id).addEventListener('input', (e) => {
    state.lights[state.light].direction[k] = Number(e.target.value);
    changed();
  }));
  wireLightDrag();
  $('reset').addEventListener('click', () => {
    state.eye = [...scene.camera.eye];
    state.target = [...scene.camera.target];
    cameraMoved = false;
    changed();
  });
  $('stats-button').addEventListener('click', async () => {
    const response = await fetch('api/stats?' + query());
    $('stats').textContent = response.ok ? formatStats(await response.json()) : await response.text();
  });
  $('save').addEventListener('click', async () => {
    const response = await fetch('api/save?' + query());
    if (!response.ok) { showError(await response.text()); return; }
    const link = document.createElement('a');
    link.href = URL.createObjectURL(new Blob([await response.text()], { type: 'text/yaml' }));
    link.download = 'explore-state.yaml';
    link.click();
  });

  const canvas = $('image');
  let drag = null;
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('mousedown', (e) => {
    drag = { x: e.clientX, y: e.clientY, moved: false, pan: e.button === 2 || e.shiftKey };
  });
  window.addEventListener('mouseup', (e) => {
    if (drag && !drag.moved && e.target === canvas && e.button === 0) {
      const p = pixelAt(e);
      if (p) (exported ? exportedHistory(p) : history(p));
    }
    drag = null;
  });
  canvas.addEventListener('mouseleave', () => { mouseOver = null; });
  canvas.addEventListener('mousemove', (e) => {
    // Not while orbiting: the picture moves under the mouse, and a line of text changed with every
    // mouse move is laid out and painted with every mouse move.
    if (!drag || !drag.moved) probe(e);
    else mouseOver = null;  // orbiting: no value shown until the mouse moves again after it
    if (!drag || exported) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    if (!drag.moved && Math.abs(dx) + Math.abs(dy) < 3) return;
    drag.moved = true;
    drag.x = e.clientX;
    drag.y = e.clientY;
    if (drag.pan) pan(dx, dy); else orbit(dx, dy);
  });
  canvas.addEventListener('wheel', (e) => {
    if (exported) return;
    e.preventDefault();
    zoom(Math.exp(e.deltaY * 0.001));
  }, { passive: false });
  window.addEventListener('keydown', (e) => {
    if (exported || e.target.tagName === 'INPUT' && e.target.type !== 'checkbox' && e.target.type !== 'range') return;
    const key = e.key.toLowerCase();
    // The Devil Shadow System's render modes [DSS article]: 0 the frame, 1 the volumes, 2 the
    // translucent volumes; z toggles z-pass and z-fail; l moves the sliders to the next light.
    if (key === '0') setView('frame');
    else if (key === '1' && stencilMethod()) setView('volumes');
    else if (key === '2' && stencilMethod()) setView('overlay');
    else if (key === 'z') setMethod(state.method === 'zpass' ? 'zfail' : 'zpass');
    else if (key === 'l' && state.lights.length) selectLight((state.light + 1) % state.lights.length);
    else if (key === 'w') walk(1);
    else if (key === 's') walk(-1);
    else return;
    e.preventDefault();
  });
}

function formatStats(s) {
  const lines = ['triangles in ' + s.triangles.in + ', clipped ' + s.triangles.clipped + ', culled ' + s.triangles.culled +
    ', rasterized ' + s.triangles.rasterized,
    'fragments ' + s.fragments.all + ', stencil failed ' + s.fragments.stencilFailed + ', depth failed ' +
    s.fragments.depthFailed + ', stencil writes ' + s.fragments.stencilWrites + ', colour writes ' + s.fragments.colourWrites];
  lines.push(...s.notes);
  for (const t of s.timings) lines.push('time ' + t.pass.padEnd(24) + t.ms.toFixed(3).padStart(9) + ' ms');
  for (const w of s.warnings) lines.push('warning: ' + w);
  return lines.join('\n');
}

// ---- start
async function start() {
  const response = await fetch('api/scene');
  const summary = await response.json();
  if (summary.error) {
    showError(summary.error);  // the scene's file:line:col message
    return;
  }
  scene = summary;
  $('source').textContent = scene.source + (scene.baseOverrides.length ? ' ' + scene.baseOverrides.map((o) => '-D ' + o).join(' ') : '');
  state.eye = [...scene.camera.eye];
  state.target = [...scene.camera.target];
  state.method = scene.shadow.method;
  state.twoSided = scene.shadow.two_sided;
  state.wrap = scene.shadow.wrap;
  state.darken = scene.shadow.darken_composite;
  state.mapSize = scene.shadow.map_size;
  state.pcf = scene.shadow.pcf;
  state.lights = scene.lights.map((l) => ({ name: l.name, type: l.type, on: true, position: [...l.position], direction: [...l.direction], soft: l.soft }));
  initial = JSON.parse(JSON.stringify(state));
  fillSelect($('method'), scene.methods.map((m) => m.name));
  $('method').value = state.method;
  $('two-sided').checked = state.twoSided;
  $('wrap').checked = state.wrap;
  $('darken').checked = state.darken;
  const sizes = [64, 128, 256, 512, 1024, 2048, 4096];
  if (!sizes.includes(state.mapSize)) sizes.push(state.mapSize);
  fillSelect($('map-size'), sizes.sort((a, b) => a - b));
  $('map-size').value = String(state.mapSize);
  const kernels = [1, 3, 5, 7, 9];
  if (!kernels.includes(state.pcf)) kernels.push(state.pcf);
  fillSelect($('pcf'), kernels.sort((a, b) => a - b), kernels.map((k) => k === 1 ? 'off' : k + ' x ' + k));
  $('pcf').value = String(state.pcf);
  $('image').width = $('marks').width = scene.width;
  $('image').height = $('marks').height = scene.height;
  fillLights();
  fillViews();
  offerSettings();
  wireControls();
  changed();
}

// ---- the exported page: the views and their values are files beside it, no server
function decodeValues(text) {
  const bytes = Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
  return new Float32Array(bytes.buffer);
}

function showExported(id) {
  const v = exported.views.find((x) => x.id === id);
  const image = new Image();
  image.onload = () => {
    const canvas = $('image');
    canvas.width = $('marks').width = v.width;
    canvas.height = $('marks').height = v.height;
    canvas.getContext('2d').drawImage(image, 0, 0);
    exploreStats.framesShown += 1;
  };
  image.src = id + '.png';
  const text = window.SHADOWREF_VALUES[id];
  lastImage = { width: v.width, height: v.height, valueName: v.values, values: text ? decodeValues(text) : null, info: v.info };
  state.view = v.info.view;
  showKey(v.info);
  $('strip').hidden = true;
}

function exportedHistory(p) {
  const box = $('history');
  box.textContent = '';
  const title = document.createElement('h2');
  title.textContent = 'pixel ' + p.x + ',' + p.y + ' (row 0 is the bottom) in every view of this handout';
  box.append(title);
  const table = document.createElement('table');
  table.append(row(['view', 'value'], 'th'));
  for (const v of exported.views) {
    const text = window.SHADOWREF_VALUES[v.id];
    if (!text) continue;
    const values = decodeValues(text);
    const value = values[p.row * v.width + p.col];
    table.append(row([v.label, v.values + ' ' + (Number.isFinite(value) ? Number(value.toPrecision(6)) : 'nothing drawn')], 'td'));
  }
  box.append(table);
  const note = document.createElement('p');
  note.textContent = 'Every fragment of the pixel: shadowref explore ' + (exported.scene.source || '') + ', or shadowref render --pixel-history ' + p.x + ',' + p.y;
  box.append(note);
}

function startExported() {
  document.body.classList.add('export');
  scene = exported.scene;
  $('source').textContent = scene.source + ' (handout: no server; the views were rendered by shadowref explore --export)';
  $('state').textContent = exported.overrides.map((o) => '-D ' + o).join(' ');
  fillSelect($('view'), exported.views.map((v) => v.id), exported.views.map((v) => v.label));
  $('index-label').hidden = true;
  $('signed-label').hidden = true;
  $('view').addEventListener('change', (e) => showExported(e.target.value));
  wireControls();
  showExported(exported.views[0].id);
}

if (exported) startExported(); else start().catch((e) => showError('the page could not start: ' + e));

// The explorer in a real browser: starts `shadowref explore scenes/pumpkins.yaml`, loads its page
// in headless Chromium, orbits, switches method and view with the documents' keys, clicks a pixel
// and reads its history, compares the picture on the screen with `shadowref render` for the same
// -D values, and checks that bad requests get a 400 and a broken scene its file:line:col on the
// page, and that --export's handout works from file:// with no server. The history on the page is
// checked step for step against `render --pixel-history` (clears and shadow-map lookups too); a
// light dragged on the picture, switched off, or turned with the sliders renders as `shadowref
// render` with the state's -D values; TSM's map views show the camera frustum and the trapezoid
// as `--dump shadowmap` draws them. It saves the screenshots of docs/teaching.md into SCREENSHOT_DIR.
//   node tests/browser/explore.test.mjs SHADOWREF_BINARY [SCREENSHOT_DIR]
// Run from the source folder (ctest does; label "browser").
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {
  launchBrowser, orbit, pressAndWait, settle, startExplorer, stopExplorer, waitForFrames, framesShown, imageBox,
} from './explore_harness.mjs';

const binary = process.argv[2];
const shots = process.argv[3] || fs.mkdtempSync(path.join(os.tmpdir(), 'explore-shots-'));
if (!binary) {
  console.error('usage: node tests/browser/explore.test.mjs SHADOWREF_BINARY [SCREENSHOT_DIR]');
  process.exit(2);
}
fs.mkdirSync(shots, { recursive: true });
const scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'explore-test-'));
const started = Date.now();
const step = (what) => console.log(`[${((Date.now() - started) / 1000).toFixed(1)} s] ${what}`);

// The picture area of the page (the canvas) as a screenshot, PNG bytes: the rendered picture
// alone, or with `marks` the lights' markers drawn over it too.
async function pictureShot(page, name, marks = false) {
  const box = await imageBox(page);
  if (!marks) await page.$eval('#marks', (m) => { m.style.visibility = 'hidden'; });
  const png = await page.screenshot({ clip: box, type: 'png' });
  await page.$eval('#marks', (m) => { m.style.visibility = ''; });
  if (name) fs.writeFileSync(path.join(shots, name), png);
  return png;
}

// Decodes two PNGs in the page and counts the pixels whose R, G or B differ; with `region`
// ([width, height]) only in that rectangle at the top left of each (a view beside its legend).
async function differingPixels(page, pngA, pngB, region = null) {
  return page.evaluate(async (a, b, r) => {
    const decode = async (b64) => {
      const image = new Image();
      image.src = 'data:image/png;base64,' + b64;
      await image.decode();
      const c = document.createElement('canvas');
      c.width = image.width;
      c.height = image.height;
      const g = c.getContext('2d');
      g.drawImage(image, 0, 0);
      return g.getImageData(0, 0, c.width, c.height);
    };
    const [x, y] = [await decode(a), await decode(b)];
    const [w, h] = r || [x.width, x.height];
    if (!r && (x.width !== y.width || x.height !== y.height)) return { size: [x.width, x.height, y.width, y.height] };
    if (w > x.width || w > y.width || h > x.height || h > y.height) return { size: [x.width, x.height, y.width, y.height] };
    let differing = 0;
    for (let row = 0; row < h; row++)
      for (let col = 0; col < w; col++) {
        const i = (row * x.width + col) * 4, j = (row * y.width + col) * 4;
        if (x.data[i] !== y.data[j] || x.data[i + 1] !== y.data[j + 1] || x.data[i + 2] !== y.data[j + 2]) differing += 1;
      }
    return { differing, pixels: w * h };
  }, Buffer.from(pngA).toString('base64'), Buffer.from(pngB).toString('base64'), region);
}

// The steps of a pixel history as `render --pixel-history` prints them: per clear its stencil,
// per fragment its draw, facing, test outcomes and stencil before and after, per shadow-map lookup
// its light, texel and result.
function cliSteps(text) {
  const out = [];
  for (const line of text.split('\n')) {
    let m;
    if ((m = line.match(/^  clear(?:  stencil (-?\d+) -> (-?\d+))?/))) out.push('clear ' + (m[1] !== undefined ? m[1] + '>' + m[2] : '-'));
    else if ((m = line.match(/^  draw (\d+) .*  (front|back)  z=.*stencil test (pass|FAIL)  depth test (pass|FAIL|-)  stencil (-?\d+) -> (-?\d+)/)))
      out.push(`draw ${m[1]} ${m[2]} ${m[3]} ${m[4]} ${m[5]}>${m[6]}`);
    else if ((m = line.match(/^      lookup light (L\d+) .*?(?:texel \((\d+), (\d+)\).*)?result (\S+)$/)))
      out.push(`lookup ${m[1]} ${m[2] ?? '-'},${m[3] ?? '-'} ${Number(m[4])}`);
  }
  return out;
}

// The same from the history table on the page.
async function pageSteps(page) {
  return page.$$eval('#history table tr', (rows) => rows.slice(1).map((r) => {
    const c = [...r.children].map((x) => x.textContent);
    if (r.className === 'clear') {
      const m = c[4].match(/stencil (-?\d+) → (-?\d+)/);
      return 'clear ' + (m ? m[1] + '>' + m[2] : '-');
    }
    if (r.className === 'fragment') {
      const st = c[10].split(' → ');
      return `draw ${c[3]} ${c[5]} ${c[8]} ${c[9]} ${st[0]}>${st[1]}`;
    }
    const m = c[4].match(/^lookup (L\d+) .*?(?:texel \((\d+), (\d+)\).*)?result (\S+)$/);
    return m ? `lookup ${m[1]} ${m[2] ?? '-'},${m[3] ?? '-'} ${Number(m[4])}` : 'unreadable row: ' + c.join('|');
  }));
}

// Clicks picture pixel (col, row) and waits for its history; resolves to the table's steps and
// `render --pixel-history` for the page's state at the same pixel.
async function historyAgainstCli(page, col, row, scene) {
  const box = await imageBox(page);
  await page.$eval('#history', (h) => { h.textContent = ''; });
  await page.mouse.click(box.x + col + 0.5, box.y + row + 0.5);
  await page.waitForSelector('#history table', { timeout: 60000 });
  const height = await page.$eval('#image', (c) => c.height);
  const y = height - 1 - row;
  const overrides = await page.evaluate(() => window.exploreOverrides());
  const printed = cliRender(overrides, ['--pixel-history', `${col},${y}`], scene).stdout;
  return { page: await pageSteps(page), cli: cliSteps(printed), printed, y };
}

function cliRender(overrides, extra = [], scene = 'scenes/pumpkins.yaml') {
  const out = path.join(scratch, 'cli.png');
  const args = ['render', scene, '--quiet', '-o', out, ...extra];
  for (const o of overrides) args.push('-D', o);
  const stdout = execFileSync(binary, args, { encoding: 'utf8' });
  return { png: fs.readFileSync(out), stdout };
}

const server = await startExplorer(binary, ['scenes/pumpkins.yaml']);
const browser = await launchBrowser();
let failed = false;
try {
  const page = await browser.newPage();
  page.on('pageerror', (e) => { failed = true; console.error('page error:', e.message); });
  await page.goto(server.url);
  await waitForFrames(page, 1);
  await settle(page);
  step('page loaded, first frame shown');
  assert.equal(await page.$eval('#method', (s) => s.value), 'zfail');
  const zfailStart = await pictureShot(page, 'explore-pumpkins-zfail.png');

  // Orbit: every mouse move is a new camera; the state names it as -D camera.eye.
  await orbit(page, -60, 10);
  await settle(page);
  const orbited = await page.evaluate(() => window.exploreOverrides());
  assert.ok(orbited.some((o) => o.startsWith('camera.eye=')), 'orbiting sets camera.eye: ' + orbited);
  const afterOrbit = await pictureShot(page);
  assert.ok((await differingPixels(page, zfailStart, afterOrbit)).differing > 1000, 'the orbit changed the picture');
  step('orbited: ' + orbited.join(' '));

  // The same bytes: the picture on the screen is `shadowref render` with the state's -D values.
  const cli = cliRender(orbited);
  const same = await differingPixels(page, await pictureShot(page), cli.png);
  assert.deepEqual(same, { differing: 0, pixels: 800 * 640 }, 'screen vs shadowref render ' + orbited.join(' '));
  step('the picture equals shadowref render pixel for pixel');

  // Back to the scene's camera: inside the candle's shadow volume. Key Z switches to z-pass,
  // which counts wrongly there ([Kuhn 2016, Fig. 5.8]); the picture changes.
  await page.click('#reset');
  await settle(page);
  await pressAndWait(page, 'z');
  assert.equal(await page.$eval('#method', (s) => s.value), 'zpass');
  const zpass = await pictureShot(page, 'explore-pumpkins-zpass.png');
  const inverted = await differingPixels(page, zfailStart, zpass);
  assert.ok(inverted.differing > 10000, 'z-pass with the camera in the volume differs from z-fail: ' + JSON.stringify(inverted));
  step(`z-pass differs from z-fail in ${inverted.differing} pixels`);

  // Orbit up until the eye looks down through the lantern's lid: out of every volume, z-pass
  // counts right and its picture is z-fail's. Reset walks back into the volume.
  const centre = await imageBox(page);
  await page.mouse.move(centre.x + 400, centre.y + 320);
  const beforeZoom = await framesShown(page);
  await page.mouse.wheel({ deltaY: -500 });  // closer to the target: under the porch's roof
  await waitForFrames(page, beforeZoom + 1);
  await settle(page);
  await orbit(page, 0, 250);
  await settle(page);
  const above = await pictureShot(page, 'explore-pumpkins-zpass-above.png');
  await pressAndWait(page, 'z');
  const aboveZfail = await pictureShot(page);
  const agree = await differingPixels(page, above, aboveZfail);
  assert.equal(agree.differing, 0, 'above the lid z-pass equals z-fail: ' + JSON.stringify(agree));
  await pressAndWait(page, 'z');
  await page.click('#reset');
  await settle(page);
  step('above the lid z-pass and z-fail agree; back inside the volume');

  // The stencil counts of z-pass: the legend lists the counts present, 255 (-1 wrapped) among them.
  // The mouse rests over the picture: the new view shows the count under it without a move, the
  // count `render --dump-region` prints there.
  const rest = await imageBox(page);
  const [restCol, restRow] = [700, 150];
  await page.mouse.move(rest.x + restCol + 0.5, rest.y + restRow + 0.5);
  await page.select('#view', 'stencil');
  await settle(page);
  const legend = await page.$$eval('#legend span', (s) => s.map((x) => x.textContent));
  assert.ok(legend.length >= 2 && legend.length < 20, 'a compact legend: ' + legend);
  const restY = 640 - 1 - restRow;
  const region = cliRender(await page.evaluate(() => window.exploreOverrides()), ['--dump-region', `${restCol},${restY},1,1`]).stdout;
  const dumped = region.trim().split('\n').pop().trim().split(/\s+/)[1];
  const probed = await page.$eval('#probe', (p) => p.textContent);
  assert.equal(probed, `pixel ${restCol},${restY} (row 0 is the bottom)  count ${dumped}`, 'the count under the resting mouse');
  await pictureShot(page, 'explore-pumpkins-zpass-stencil.png');
  await page.screenshot({ path: path.join(shots, 'explore-page-stencil.png') });
  step('stencil view, legend ' + legend.join(' ') + '; ' + probed);

  // Mode 1 of the Devil Shadow System: the volumes.
  await pressAndWait(page, '1');
  assert.equal(await page.$eval('#view', (s) => s.value), 'volumes');
  await pictureShot(page, 'explore-pumpkins-volumes.png');
  await pressAndWait(page, 'z');  // back to z-fail
  await pressAndWait(page, '0');
  assert.equal(await page.$eval('#view', (s) => s.value), 'frame');
  step('volumes view, back to z-fail and the frame');

  // Click a pixel on the lit floor in front of the hollow pumpkin: its history lists the same
  // fragments as `render --pixel-history` prints.
  const box = await imageBox(page);
  const col = 240, row = 420;
  await page.mouse.click(box.x + col + 0.5, box.y + row + 0.5);
  await page.waitForSelector('#history table', { timeout: 60000 });
  const rows = await page.$$eval('#history table tr.fragment', (r) => r.length);
  const title = await page.$eval('#history h2', (h) => h.textContent);
  const y = 640 - 1 - row;
  assert.ok(title.startsWith(`pixel ${col},${y}:`), title);
  const printed = cliRender(await page.evaluate(() => window.exploreOverrides()), ['--pixel-history', `${col},${y}`]).stdout;
  const count = Number(printed.match(/: (\d+) fragments/)[1]);
  assert.equal(rows, count, 'the page lists the fragments render --pixel-history prints');
  const why = await page.$$eval('#history .why', (p) => p.map((x) => x.textContent));
  assert.ok(why.length > 0, 'the history says why');
  await page.screenshot({ path: path.join(shots, 'explore-page-history.png'), fullPage: true });
  step(`pixel ${col},${y}: ${rows} fragments; ${why[0]}`);

  // The page's history is the one `render --pixel-history` prints: the same steps in the same
  // order, the stencil clear before the lantern's volumes among them.
  const zfailHistory = await historyAgainstCli(page, col, row);
  assert.deepEqual(zfailHistory.page, zfailHistory.cli, 'page and --pixel-history agree (z-fail)');
  assert.ok(zfailHistory.page.some((s) => s.startsWith('clear 0>0')), 'the stencil clear is listed: ' + zfailHistory.page);
  assert.ok(why.some((w) => w.startsWith('in the shadow of L0') || w.startsWith('lit by L0')), 'a verdict per light: ' + why);
  // With a shadow map: the lookups of the visible fragment, light-space texel and result.
  await page.select('#method', 'shadowmap');
  await settle(page);
  const mapHistory = await historyAgainstCli(page, col, row);
  assert.deepEqual(mapHistory.page, mapHistory.cli, 'page and --pixel-history agree (shadowmap)');
  assert.ok(mapHistory.page.some((s) => s.startsWith('lookup L0')), 'the lookups are listed: ' + mapHistory.page);
  const mapWhy = await page.$$eval('#history .why', (p) => p.map((x) => x.textContent));
  assert.ok(mapWhy.some((w) => w.includes('stored D')), 'the verdict reads the lookup: ' + mapWhy);
  await page.screenshot({ path: path.join(shots, 'explore-page-history-shadowmap.png'), fullPage: true });
  step(`shadowmap history at ${col},${mapHistory.y}: ${mapHistory.page.length} steps as printed; ${mapWhy[0]}`);

  // The cube map's face with the camera frustum drawn: white lines on the map.
  await page.select('#view', 'shadowmap');
  await settle(page);
  const outlines = await page.$$eval('#legend .outline', (s) => s.map((x) => x.textContent));
  assert.deepEqual(outlines, ['camera frustum'], 'the map view names its outline');
  // The controls offered are the settings the method reads (the technique registry's list).
  const enabled = () => page.evaluate(() => Object.fromEntries(
    ['two-sided', 'wrap', 'darken', 'map-size', 'pcf'].map((id) => [id, !document.getElementById(id).disabled])));
  assert.deepEqual(await enabled(), { 'two-sided': false, wrap: false, darken: false, 'map-size': true, pcf: true },
    'shadowmap reads the map size and PCF, not the stencil settings');
  await page.select('#view', 'frame');
  await page.select('#method', 'zfail');
  await settle(page);
  assert.deepEqual(await enabled(), { 'two-sided': true, wrap: true, darken: true, 'map-size': false, pcf: false },
    'z-fail reads the stencil settings, not the map size or PCF');
  const unread = await page.$eval('#map-size', (c) => c.closest('label').title);
  assert.equal(unread, 'shadow.map_size: zfail does not read it (shadowmap, tsm do)');

  // Drag the candle's marker: the light moves in the picture plane, and the picture is
  // `shadowref render` with the moved light's -D value.
  const marker = await page.evaluate(() => window.exploreLightMarker(0));
  assert.ok(marker, 'the candle has a marker on the picture');
  const markerBox = await imageBox(page);
  await page.mouse.move(markerBox.x + marker.col, markerBox.y + marker.row);
  await page.mouse.down();
  for (let i = 1; i <= 5; i++) await page.mouse.move(markerBox.x + marker.col + 8 * i, markerBox.y + marker.row - 6 * i);
  await page.mouse.up();
  await settle(page);
  const moved = await page.evaluate(() => window.exploreOverrides());
  assert.ok(moved.some((o) => o.startsWith('lights.candle.position=')), 'dragging moves the light: ' + moved);
  assert.ok(!moved.some((o) => o.startsWith('camera.')), 'dragging a marker does not orbit: ' + moved);
  await pictureShot(page, 'explore-pumpkins-light-moved.png', true);
  const movedShot = await pictureShot(page);
  assert.deepEqual(await differingPixels(page, movedShot, cliRender(moved).png), { differing: 0, pixels: 800 * 640 },
    'moved light vs shadowref render ' + moved.join(' '));
  assert.ok((await differingPixels(page, movedShot, zfailStart)).differing > 1000, 'moving the light changed the picture');
  step('dragged the light: ' + moved.join(' ') + '; equals shadowref render');
  // Switched off: the scene without the light, as -D lights.candle=off renders it.
  await page.click('#lights input[type=checkbox]');
  await settle(page);
  const off = await page.evaluate(() => window.exploreOverrides());
  assert.ok(off.includes('lights.candle=off'), 'the check box switches the light off: ' + off);
  assert.deepEqual(await differingPixels(page, await pictureShot(page), cliRender(off).png), { differing: 0, pixels: 800 * 640 },
    'light off vs shadowref render ' + off.join(' '));
  await page.click('#lights input[type=checkbox]');
  await page.click('#reset');
  await settle(page);
  step('switched the light off and on: equals shadowref render');

  // Bad requests: a 400 with the reason, and the server keeps serving.
  const bad = await page.evaluate(async () => {
    const answers = [];
    for (const q of ['view=nope', 'index=-1', 'D=' + encodeURIComponent('shadow.map_size=3'), 'x=1', 'view=frame&view=depth',
      'D=' + encodeURIComponent('camera.eye=[1,2')]) {
      const r = await fetch('api/frame?' + q);
      answers.push([q, r.status, await r.text()]);
    }
    const ok = await fetch('api/frame?view=frame');
    answers.push(['ok', ok.status, '']);
    return answers;
  });
  for (const [q, status, text] of bad.slice(0, -1)) {
    assert.equal(status, 400, q + ': ' + text);
    assert.ok(text.length > 5, q + ' has a message');
  }
  assert.ok(bad[2][2].includes('<command line>:1:'), 'an override error names its place: ' + bad[2][2]);
  assert.equal(bad[bad.length - 1][1], 200);
  step('bad requests: ' + bad.slice(0, -1).map((b) => b[1]).join(' '));
  await page.close();

  // TSM's maps with the camera frustum and the trapezoid; the sun turned with the direction
  // sliders renders as `shadowref render` with its -D value.
  const outdoor = await startExplorer(binary, ['scenes/outdoor.yaml']);
  try {
    const p4 = await browser.newPage();
    p4.on('pageerror', (e) => { failed = true; console.error('outdoor page error:', e.message); });
    await p4.goto(outdoor.url);
    await waitForFrames(p4, 1);
    await settle(p4);
    assert.equal(await p4.$eval('#method', (s) => s.value), 'tsm');
    await p4.select('#map-size', '256');
    await p4.select('#view', 'shadowmap');
    await settle(p4);
    const maps = await p4.$$eval('#index option', (o) => o.map((x) => x.textContent));
    const plain = maps.indexOf('L0.plain');
    assert.ok(plain >= 0, 'TSM has an unwarped view: ' + maps);
    await p4.select('#index', String(plain));
    await settle(p4);
    const lines = await p4.$$eval('#legend .outline', (s) => s.map((x) => x.textContent));
    assert.deepEqual(lines, ['camera frustum', 'trapezoid']);
    const plainShot = await pictureShot(p4, 'explore-outdoor-tsm-plain.png');
    const mapState = await p4.evaluate(() => window.exploreOverrides());
    cliRender(mapState, ['--dump', 'shadowmap'], 'scenes/outdoor.yaml');
    const dumped = fs.readFileSync(path.join(scratch, 'cli.shadowmap-L0.plain.png'));
    assert.deepEqual(await differingPixels(p4, plainShot, dumped, [256, 256]), { differing: 0, pixels: 256 * 256 },
      'the page\'s map view is --dump shadowmap\'s picture');
    const colours = await p4.evaluate(() => {
      const c = document.getElementById('image');
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let white = 0, red = 0;
      for (let i = 0; i < d.length; i += 4) {
        if (d[i] === 255 && d[i + 1] === 255 && d[i + 2] === 255) white += 1;
        if (d[i] === 255 && d[i + 1] === 48 && d[i + 2] === 48) red += 1;
      }
      return { white, red };
    });
    assert.ok(colours.white > 50 && colours.red > 50, 'frustum and trapezoid drawn: ' + JSON.stringify(colours));
    await p4.select('#index', String(maps.indexOf('L0')));
    await settle(p4);
    await pictureShot(p4, 'explore-outdoor-tsm-warped.png');
    step(`TSM maps: frustum ${colours.white} px, trapezoid ${colours.red} px; equals --dump shadowmap`);

    await p4.select('#view', 'frame');
    await settle(p4);
    const before = await pictureShot(p4);
    await p4.$eval('#dx', (input) => { input.value = String(Number(input.value) + 0.3); input.dispatchEvent(new Event('input')); });
    await settle(p4);
    const turned = await p4.evaluate(() => window.exploreOverrides());
    assert.ok(turned.some((o) => /^lights\.[^.]+\.direction=/.test(o)), 'the slider turns the sun: ' + turned);
    const turnedShot = await pictureShot(p4);
    const size = await p4.$eval('#image', (c) => c.width * c.height);
    assert.deepEqual(await differingPixels(p4, turnedShot, cliRender(turned, [], 'scenes/outdoor.yaml').png), { differing: 0, pixels: size },
      'turned sun vs shadowref render ' + turned.join(' '));
    assert.ok((await differingPixels(p4, before, turnedShot)).differing > 100, 'turning the sun moved the shadows');
    step('turned the sun: ' + turned.join(' ') + '; equals shadowref render');
    await p4.close();
  } finally {
    assert.equal(await stopExplorer(outdoor, 'SIGTERM'), 0);
  }

  // A scene that does not load: its file:line:col message on the page.
  const broken = path.join(scratch, 'broken.yaml');
  fs.writeFileSync(broken, 'camera:\n  fov: 200\n');
  const brokenServer = await startExplorer(binary, [broken]);
  try {
    const p2 = await browser.newPage();
    await p2.goto(brokenServer.url);
    await p2.waitForFunction(() => !document.getElementById('error').hidden, { timeout: 20000 });
    const message = await p2.$eval('#error', (e) => e.textContent);
    assert.ok(message.startsWith(broken + ':2:8:'), 'the page shows file:line:col: ' + message);
    step('broken scene: ' + message);
  } finally {
    assert.equal(await stopExplorer(brokenServer, 'SIGTERM'), 0, 'SIGTERM stops the server cleanly');
  }

  // The handout: --export's folder opened from the file system, no server.
  const handout = path.join(scratch, 'handout');
  execFileSync(binary, ['explore', 'scenes/pumpkins.yaml', '--export', handout, '-D', 'shadow.method=zpass',
    '-D', 'image.width=400', '-D', 'image.height=320'], { stdio: 'ignore' });
  const p3 = await browser.newPage();
  p3.on('pageerror', (e) => { failed = true; console.error('handout page error:', e.message); });
  await p3.goto('file://' + path.join(handout, 'index.html'));
  await waitForFrames(p3, 1);
  await p3.select('#view', 'stencil-0');
  await waitForFrames(p3, 2);
  const hb = await imageBox(p3);
  await p3.mouse.move(hb.x + 200.5, hb.y + 150.5);
  const probe = await p3.$eval('#probe', (e) => e.textContent);
  assert.ok(/^pixel 200,169 .*count \d+$/.test(probe), 'hovering the handout shows the count: ' + probe);
  await p3.mouse.click(hb.x + 200.5, hb.y + 150.5);
  await p3.waitForSelector('#history table');
  const handoutRows = await p3.$$eval('#history table tr', (r) => r.length - 1);
  assert.ok(handoutRows >= 4, 'the handout lists the pixel in every view with values');
  step(`handout from file://: ${probe}; ${handoutRows} views at the clicked pixel`);
} catch (e) {
  failed = true;
  console.error(e);
} finally {
  await browser.close();
  const code = await stopExplorer(server, 'SIGINT');
  if (code !== 0) {
    failed = true;
    console.error('explore did not stop cleanly on SIGINT: exit', code, server.stderr());
  }
  fs.rmSync(scratch, { recursive: true, force: true });
}
step(failed ? 'FAILED' : `passed; screenshots in ${shots}`);
process.exit(failed ? 1 : 0);

// The explorer's frame rate as a user sees it: the real page in headless Chromium, the camera
// orbited by mouse moves at 60 per second for a while, then the figures the page counted
// (window.exploreStats) and the CPU time the processes spent:
//   fps        frames shown per second in the browser;
//   render     the server's time per frame, loading the state and rendering it (median, p90 ms);
//   encode     the server's time to encode the frame for the wire (median ms);
//   latency    from a mouse move to the first frame on the screen that shows it (median, p90 ms);
//   CPU/frame  CPU time per frame shown of the server, of Chromium's renderer process (the page:
//              input, fetch, decode, drawing, layout) and of Chromium's other processes (browser,
//              network, GPU/compositor), the latter two above their idle rate; unlike the
//              wall-clock figures these do not grow with whatever else the machine runs;
//   bound      2000 ms / the sum of the three: the frame rate the work allows on two idle cores.
// Each scene's line starts with the load average when it started (the machine may be shared).
//   node tests/browser/explore_bench.mjs SHADOWREF_BINARY [SECONDS] [SCENE...]
// A benchmark, not a test: scripts/bench-explore.sh runs it.
import fs from 'node:fs';
import os from 'node:os';
import { launchBrowser, settle, startExplorer, stopExplorer, waitForFrames, imageBox } from './explore_harness.mjs';

const [binary, secondsText, ...scenes] = process.argv.slice(2);
const seconds = Number(secondsText || 10);
if (!binary) {
  console.error('usage: node tests/browser/explore_bench.mjs SHADOWREF_BINARY [SECONDS] [SCENE...]');
  process.exit(2);
}
const quantile = (values, q) => {
  if (!values.length) return NaN;
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];
};
const f1 = (v) => v.toFixed(1);
const f0 = (v) => v.toFixed(0);

// CPU time (user + system, ms) of a process and all its descendants, from /proc, summed by kind:
// 'main' for the root process itself and the children without a --type, else Chromium's process
// type (renderer, gpu-process, utility) -- the work a frame costs whatever else the machine runs.
const msPerTick = 1000 / 100;  // USER_HZ is 100 on Linux
function cpuMs(rootPid) {
  const children = new Map();
  const info = new Map();
  for (const entry of fs.readdirSync('/proc')) {
    if (!/^\d+$/.test(entry)) continue;
    let stat, cmdline;
    try {
      stat = fs.readFileSync(`/proc/${entry}/stat`, 'utf8');
      cmdline = fs.readFileSync(`/proc/${entry}/cmdline`, 'utf8');
    } catch { continue; }
    const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
    const pid = Number(entry), ppid = Number(fields[1]);
    const type = cmdline.match(/--type=([^\s\0]+)/);
    // Chromium's own pages (the omnibox popup it loads at start) are not the explorer's renderer.
    const kind = !type ? 'main' : type[1] === 'renderer' && cmdline.includes('webui') ? 'webui' : type[1];
    info.set(pid, { ms: (Number(fields[11]) + Number(fields[12])) * msPerTick, kind });
    if (!children.has(ppid)) children.set(ppid, []);
    children.get(ppid).push(pid);
  }
  const byKind = { all: 0 };
  const stack = [rootPid];
  while (stack.length) {
    const pid = stack.pop();
    const i = info.get(pid);
    if (i) {
      byKind[i.kind] = (byKind[i.kind] || 0) + i.ms;
      byKind.all += i.ms;
    }
    stack.push(...(children.get(pid) || []));
  }
  return byKind;
}
const renderer = (c) => c.renderer || 0;
const others = (c) => c.all - renderer(c);

const browser = await launchBrowser({ networkEnabled: false });
// Chromium loads its own pages for some seconds after it starts (hundreds of ms of CPU a second):
// the measurements begin once it is quiet.
for (let i = 0; i < 30; i++) {
  const a = cpuMs(browser.process().pid).all;
  await new Promise((r) => setTimeout(r, 1000));
  if (cpuMs(browser.process().pid).all - a < 50) break;
}
console.log('load = load average (1 min) at the start; render, encode, latency: median (p90) ms; CPU: ms per frame shown');
console.log('scene                    load    fps   render ms      encode   latency ms       frames/inputs   CPU server  renderer  other   bound fps');
let status = 0;
for (const scene of scenes.length ? scenes : ['scenes/room.yaml', 'scenes/pumpkins.yaml', 'scenes/city.yaml']) {
  const server = await startExplorer(binary, [scene]);
  try {
    const page = await browser.newPage();
    await page.goto(server.url);
    await waitForFrames(page, 1, 60000);
    await settle(page, 60000);
    const box = await imageBox(page);
    const cx = box.x + box.width / 2, cy = box.y + box.height / 2;
    await page.mouse.move(cx, cy);
    await page.mouse.down();
    // Warm-up: the first orbit frames load the scene once and start the threads.
    for (let i = 0; i < 10; i++) {
      await page.mouse.move(cx + i * 4, cy);
      await new Promise((r) => setTimeout(r, 16));
    }
    await settle(page, 60000);
    await page.evaluate(() => {
      const s = window.exploreStats;
      s.framesShown = 0; s.serverMs.length = 0; s.encodeMs.length = 0; s.latencyMs.length = 0;
    });
    // The browser's own rate while nothing happens (headless Chromium ticks even when idle).
    const idle0 = cpuMs(browser.process().pid);
    await new Promise((r) => setTimeout(r, 2000));
    const idle1 = cpuMs(browser.process().pid);
    const idleRenderer = (renderer(idle1) - renderer(idle0)) / 2, idleOthers = (others(idle1) - others(idle0)) / 2;
    const load = os.loadavg()[0];
    const server0 = cpuMs(server.process.pid), browser0 = cpuMs(browser.process().pid);
    const start = Date.now();
    let inputs = 0;
    // A slow circle: 60 mouse moves a second, each one a new camera.
    while (Date.now() - start < seconds * 1000) {
      const t = (Date.now() - start) / 1000;
      await page.mouse.move(cx + 150 * Math.sin(t * 0.8), cy + 40 * Math.sin(t * 1.3));
      inputs += 1;
      const next = start + inputs * (1000 / 60);
      const wait = next - Date.now();
      if (wait > 0) await new Promise((r) => setTimeout(r, wait));
    }
    const stats = await page.evaluate(() => window.exploreStats);
    const elapsed = (Date.now() - start) / 1000;
    const server1 = cpuMs(server.process.pid), browser1 = cpuMs(browser.process().pid);
    await page.mouse.up();
    const frames = stats.framesShown;
    const serverCpu = (server1.all - server0.all) / frames;
    const rendererCpu = (renderer(browser1) - renderer(browser0) - idleRenderer * elapsed) / frames;
    const othersCpu = (others(browser1) - others(browser0) - idleOthers * elapsed) / frames;
    const fps = frames / elapsed;
    const pair = (values) => `${f1(quantile(values, 0.5)).padStart(5)} (${f0(quantile(values, 0.9)).padStart(3)})`;
    console.log(`${scene.padEnd(24)} ${f1(load).padStart(4)}  ${f1(fps).padStart(5)}   ${pair(stats.serverMs)}   ${f1(quantile(stats.encodeMs, 0.5)).padStart(5)}` +
      `   ${pair(stats.latencyMs)}   ${String(frames).padStart(6)}/${String(inputs).padEnd(6)}` +
      `   ${f1(serverCpu).padStart(9)} ${f1(rendererCpu).padStart(9)} ${f1(othersCpu).padStart(6)}   ${f1(2000 / (serverCpu + rendererCpu + othersCpu)).padStart(6)}`);
    if (stats.errors) { console.error(scene + ': ' + stats.errors + ' failed frame requests'); status = 1; }
    await page.close();
  } finally {
    await stopExplorer(server);
  }
}
await browser.close();
process.exit(status);

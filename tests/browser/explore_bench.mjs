// The explorer's frame rate as a user sees it: the real page in headless Chromium, the camera
// orbited by mouse moves at 60 per second for a while, then the figures the page counted
// (window.exploreStats): frames shown per second, the server's time per frame (loading the state
// and rendering it) and the latency from an input to the first frame showing it; and the CPU time
// per frame shown of the server and of the browser, which, unlike the wall-clock figures, do not
// grow with whatever else the machine runs (2000 / their sum bounds the frame rate on two idle cores).
//   node tests/browser/explore_bench.mjs SHADOWREF_BINARY [SECONDS] [SCENE...]
// A benchmark, not a test: scripts/bench-explore.sh runs it.
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

// CPU time (user + system, ms) of a process and all its descendants, from /proc: the work a frame
// costs whatever else the machine runs, where wall-clock times grow with its load.
import fs from 'node:fs';
const ticksPerMs = 100 / 1000;  // USER_HZ is 100 on Linux
function cpuMs(rootPid) {
  const children = new Map();
  const times = new Map();
  for (const entry of fs.readdirSync('/proc')) {
    if (!/^\d+$/.test(entry)) continue;
    let stat;
    try { stat = fs.readFileSync(`/proc/${entry}/stat`, 'utf8'); } catch { continue; }
    const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
    const pid = Number(entry), ppid = Number(fields[1]);
    times.set(pid, Number(fields[11]) + Number(fields[12]));
    if (!children.has(ppid)) children.set(ppid, []);
    children.get(ppid).push(pid);
  }
  let total = 0;
  const stack = [rootPid];
  while (stack.length) {
    const pid = stack.pop();
    total += times.get(pid) || 0;
    stack.push(...(children.get(pid) || []));
  }
  return total / ticksPerMs;
}

const browser = await launchBrowser();
console.log('scene                     fps    server ms (median, p90)   latency ms (median, p90)   frames  inputs   CPU ms/frame: server, browser above idle (idle ms/s)');
let status = 0;
for (const scene of scenes.length ? scenes : ['scenes/pumpkins.yaml', 'scenes/room.yaml']) {
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
      s.framesShown = 0; s.serverMs.length = 0; s.latencyMs.length = 0;
    });
    // The browser's own rate while nothing happens (headless Chromium ticks even on about:blank).
    const idle0 = cpuMs(browser.process().pid);
    await new Promise((r) => setTimeout(r, 2000));
    const idlePerS = (cpuMs(browser.process().pid) - idle0) / 2;
    const serverCpu0 = cpuMs(server.process.pid), browserCpu0 = cpuMs(browser.process().pid);
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
    const serverCpu = (cpuMs(server.process.pid) - serverCpu0) / stats.framesShown;
    const browserCpu = (cpuMs(browser.process().pid) - browserCpu0 - idlePerS * elapsed) / stats.framesShown;
    await page.mouse.up();
    const fps = stats.framesShown / elapsed;
    console.log(`${scene.padEnd(24)} ${f1(fps).padStart(5)}    ${f1(quantile(stats.serverMs, 0.5)).padStart(6)}, ${f1(quantile(stats.serverMs, 0.9)).padStart(6)}` +
      `           ${f1(quantile(stats.latencyMs, 0.5)).padStart(6)}, ${f1(quantile(stats.latencyMs, 0.9)).padStart(6)}` +
      `              ${String(stats.framesShown).padStart(5)}  ${String(inputs).padStart(6)}` +
      `   ${f1(serverCpu).padStart(6)}, ${f1(browserCpu).padStart(6)} (${f1(idlePerS)})`);
    if (stats.errors) { console.error(scene + ': ' + stats.errors + ' failed frame requests'); status = 1; }
    await page.close();
  } finally {
    await stopExplorer(server);
  }
}
await browser.close();
process.exit(status);

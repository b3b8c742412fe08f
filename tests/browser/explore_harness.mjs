// What the browser test and the frame-rate benchmark share: starting `shadowref explore`, starting
// Debian's Chromium headless through puppeteer-core, and driving the page as a user does.
import { spawn } from 'node:child_process';
import { once } from 'node:events';
import puppeteer from 'puppeteer-core';

export const chromiumPath = process.env.CHROMIUM || '/usr/bin/chromium';

// Starts the explorer on a free port; resolves to {url, process} once it printed its URL.
export async function startExplorer(binary, args) {
  const child = spawn(binary, ['explore', ...args, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  let out = '', err = '';
  child.stderr.on('data', (d) => { err += d; });
  const url = await new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error('explore printed no URL in 20 s: ' + out + err)), 20000);
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/\S+\//);
      if (m) { clearTimeout(timer); resolve(m[0]); }
    });
    child.on('exit', (code) => reject(new Error('explore exited with ' + code + ': ' + out + err)));
  });
  return { url, process: child, stderr: () => err };
}

// Sends the signal and resolves to the exit code (null when it had to be killed after 10 s).
export async function stopExplorer(server, signal = 'SIGINT') {
  if (server.process.exitCode !== null) return server.process.exitCode;
  server.process.kill(signal);
  const timer = setTimeout(() => server.process.kill('SIGKILL'), 10000);
  const [code] = await once(server.process, 'exit');
  clearTimeout(timer);
  return code;
}

// `options` go to puppeteer.launch (the benchmark passes networkEnabled: false: with DevTools'
// network domain on, Chromium keeps a copy of every response for the inspector, which no user's
// browser does).
export async function launchBrowser(options = {}) {
  return puppeteer.launch({
    executablePath: chromiumPath,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage', '--force-color-profile=srgb'],
    defaultViewport: { width: 1200, height: 1000, deviceScaleFactor: 1 },
    ...options,
  });
}

// Resolves once the page has shown `count` frames in all (window.exploreStats.framesShown).
export async function waitForFrames(page, count, timeout = 30000) {
  await page.waitForFunction((n) => window.exploreStats && window.exploreStats.framesShown >= n, { timeout, polling: 20 }, count);
}

export const framesShown = (page) => page.evaluate(() => window.exploreStats.framesShown);

// Presses a key and waits for the frame it causes.
export async function pressAndWait(page, key) {
  const before = await framesShown(page);
  await page.keyboard.press(key);
  await waitForFrames(page, before + 1);
  await settle(page);
}

// Waits until no frame is in flight and none is wanted: the picture shows the newest state.
// Chromium may hand a mouse move to the page up to a frame after puppeteer's call returned, so the
// page must stay idle across a pause.
export async function settle(page, timeout = 30000) {
  for (;;) {
    await page.waitForFunction(() => window.exploreIdle && window.exploreIdle(), { timeout, polling: 20 });
    const shown = await framesShown(page);
    await new Promise((r) => setTimeout(r, 150));
    if (await page.evaluate((n) => window.exploreIdle() && window.exploreStats.framesShown === n, shown)) return;
  }
}

// The centre of the picture in page coordinates.
export async function imageBox(page) {
  return page.$eval('#image', (c) => {
    const r = c.getBoundingClientRect();
    return { x: r.left, y: r.top, width: r.width, height: r.height };
  });
}

// Drags across the picture: an orbit of the camera (steps mouse moves, each a new state).
export async function orbit(page, dx, dy, steps = 10) {
  const box = await imageBox(page);
  const x = box.x + box.width / 2, y = box.y + box.height / 2;
  await page.mouse.move(x, y);
  await page.mouse.down();
  for (let i = 1; i <= steps; i++) await page.mouse.move(x + (dx * i) / steps, y + (dy * i) / steps);
  await page.mouse.up();
}

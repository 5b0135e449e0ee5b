// A real browser against a running slide-viewer (test_viewer_browser drives it):
//   node browser_check.mjs BROWSER URL OUT_DIR   (BROWSER: chromium or firefox; launch_browser.mjs)
// 1. opens the page, waits for robot 0's scene (car, trunk, bush; its trajectory and robot 1's;
//    key pose, instances, loop closure, team link), takes OUT_DIR/viewer.png and checks pixel
//    colours where the car (red) and the trunk (green) project;
// 2. writes OUT_DIR/phase1 and waits for a fourth object (a pole the test then appends to the log);
// 3. pauses, seeks to the log's start (an empty map) and goes back to live (four objects);
// 4. checks that the page asked for nothing but URL's own host (no CDN).
// Prints one line per step; exits non-zero naming what was missing.
import fs from 'node:fs';
import { launchBrowser, openPage, sleep } from '../../daemons/viewer/web/launch_browser.mjs';

const [browserName, url, out] = process.argv.slice(2);
let session;
try {
  session = await launchBrowser(browserName);
} catch (e) {
  console.error(String(e.message || e));
  process.exit(2);
}
console.log('browser', await session.browser.version());
let failed = null;
try {
  const page = await openPage(session.browser, 1000, 700);
  const errors = [], foreign = [], local = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  const host = new URL(url).host;  // the page itself, its scripts and its WebSocket
  page.on('request', (r) => {
    const u = new URL(r.url());
    if (u.protocol === 'data:') return;
    if (u.host === host) local.push(u.pathname);
    else foreign.push(r.url());
  });
  await page.goto(url);
  const want = (s) => {
    const v = s && s.views && s.views[0];
    return v && v.objects === 3 && v.trajectories[0] === 20 && v.trajectories[1] === 10 && v.keypose &&
      v.instances > 0 && v.loops === 1 && v.rings === 2 && s.team[0] && s.team[0].linked.includes(1);
  };
  try {
    await page.waitForFunction(`(${want.toString()})(window.slideScene)`, { timeout: 60000, polling: 200 });
  } catch (e) {
    throw new Error(`scene not drawn: ${JSON.stringify(await page.evaluate(() => window.slideScene))}; errors: ${errors.join(' | ')}`);
  }
  console.log('scene', JSON.stringify(await page.evaluate(() => window.slideScene.views[0])));
  await sleep(500);  // a few frames
  await page.screenshot({ path: `${out}/viewer.png` });
  const sample = await page.evaluate(() => {
    const c = document.getElementById('view');
    const copy = document.createElement('canvas');
    copy.width = c.clientWidth;
    copy.height = c.clientHeight;
    const ctx = copy.getContext('2d');
    ctx.drawImage(c, 0, 0, copy.width, copy.height);
    const at = (x, y, z) => {
      const [px, py] = window.slideScreenOf(x, y, z);
      return Array.from(ctx.getImageData(Math.round(px), Math.round(py), 1, 1).data.slice(0, 3));
    };
    return { car: at(10, 5, 1.2), trunk: at(20, -5, 4.0) };
  });
  console.log('pixels', JSON.stringify(sample));
  const [r, g, b] = sample.car;
  if (!(r > g + 60 && r > b + 60)) throw new Error(`the car is not drawn red where it projects: ${sample.car}`);
  const [r2, g2, b2] = sample.trunk;
  if (!(g2 > r2 + 25 && g2 > b2 + 25)) throw new Error(`the trunk is not drawn green where it projects: ${sample.trunk}`);
  fs.writeFileSync(`${out}/phase1`, 'ok\n');
  try {
    await page.waitForFunction(() => window.slideScene.views[0] && window.slideScene.views[0].objects === 4 &&
      window.slideScene.views[0].classes[80] === 1, { timeout: 30000, polling: 200 });
  } catch (e) {
    throw new Error(`the pole sent after load never appeared: ${JSON.stringify(await page.evaluate(() => window.slideScene.views[0]))}`);
  }
  console.log('update after load: drawn');
  await page.screenshot({ path: `${out}/viewer_after.png` });
  // Replay controls: pause, jump to the log's start (nothing drawn yet there), then back to live.
  await page.click('#play');
  await page.waitForFunction(() => window.slideScene.status.replay.paused, { timeout: 10000, polling: 100 });
  await page.evaluate(() => {
    const s = document.getElementById('slider');
    s.value = 0;
    s.dispatchEvent(new Event('change'));
  });
  try {
    await page.waitForFunction(() => window.slideScene.views[0] && window.slideScene.views[0].objects === 0 &&
      window.slideScene.status.replay.position === window.slideScene.status.replay.start, { timeout: 10000, polling: 100 });
  } catch (e) {
    throw new Error(`seeking to the start did not clear the map: ${JSON.stringify(await page.evaluate(() => [window.slideScene.views[0], window.slideScene.status]))}`);
  }
  await page.click('#live');
  await page.waitForFunction(() => window.slideScene.views[0] && window.slideScene.views[0].objects === 4 &&
    window.slideScene.status.replay.live, { timeout: 10000, polling: 100 });
  console.log('replay controls: pause, seek to start, live');
  if (foreign.length) throw new Error(`the page asked for more than ${host}: ${foreign.join(' ')}`);
  if (!local.includes('/node_modules/three/build/three.module.min.js'))
    throw new Error(`the browser reported no request for three.js: ${local.join(' ')}`);
  console.log(`offline: every request went to ${host} (${local.length}: ${local.join(' ')})`);
  if (errors.length) throw new Error(`page errors: ${errors.join(' | ')}`);
} catch (e) {
  failed = e;
} finally {
  await session.close();
}
if (failed) {
  console.error(String(failed.message || failed));
  process.exit(1);
}
console.log('OK');

// Pictures of a running slide-viewer for reports: node screenshot.mjs URL OUT_PREFIX [SECONDS]
// waits up to SECONDS (default 20) for a scene, then writes OUT_PREFIX_robot<N>.png per robot
// (each in its own frame, framed to fit) and prints their paths. Needs Debian's chromium.
import { launchBrowser, openPage, sleep } from './launch_browser.mjs';

const [url, prefix, seconds = '20'] = process.argv.slice(2);
if (!url || !prefix) {
  console.error('usage: node screenshot.mjs URL OUT_PREFIX [SECONDS]');
  process.exit(2);
}
const session = await launchBrowser('chromium');
try {
  const page = await openPage(session.browser, 1280, 800);
  await page.goto(url);
  await page.waitForFunction(() => window.slideScene && Object.values(window.slideScene.views).some((v) => v.objects > 0),
    { timeout: Number(seconds) * 1000, polling: 250 });
  const robots = await page.evaluate(() => Object.keys(window.slideScene.views));
  for (const r of robots) {
    await page.evaluate((id) => {
      [...document.querySelectorAll('#robots button')].find((b) => b.textContent === `robot ${id}`).click();
      document.getElementById('fit').click();
    }, r);
    await sleep(400);
    await page.screenshot({ path: `${prefix}_robot${r}.png` });
    console.log(`${prefix}_robot${r}.png`);
  }
} finally {
  await session.close();
}

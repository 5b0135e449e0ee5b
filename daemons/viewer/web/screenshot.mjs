// Pictures of a running slide-viewer for reports: node screenshot.mjs URL OUT_PREFIX [SECONDS]
// waits up to SECONDS (default 20) for a scene, then writes OUT_PREFIX_robot<N>.png per robot
// (each in its own frame, framed to fit) and prints their paths. Needs Debian's chromium.
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const here = path.dirname(fileURLToPath(import.meta.url));
const { chromium } = createRequire(`${here}/package.json`)('playwright-core');
const [url, prefix, seconds = '20'] = process.argv.slice(2);
if (!url || !prefix) {
  console.error('usage: node screenshot.mjs URL OUT_PREFIX [SECONDS]');
  process.exit(2);
}
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true,
  args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
  await page.goto(url);
  await page.waitForFunction(() => window.slideScene && Object.values(window.slideScene.views).some((v) => v.objects > 0),
    null, { timeout: Number(seconds) * 1000, polling: 250 });
  const robots = await page.evaluate(() => Object.keys(window.slideScene.views));
  for (const r of robots) {
    await page.evaluate((id) => {
      [...document.querySelectorAll('#robots button')].find((b) => b.textContent === `robot ${id}`).click();
      document.getElementById('fit').click();
    }, r);
    await page.waitForTimeout(400);
    await page.screenshot({ path: `${prefix}_robot${r}.png` });
    console.log(`${prefix}_robot${r}.png`);
  }
} finally {
  await browser.close();
}

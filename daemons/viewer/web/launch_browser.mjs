// A real browser for the viewer's pictures (screenshot.mjs) and its browser test
// (tests/viewer/browser_check.mjs), driven by puppeteer-core from this folder's node_modules:
//   const b = await launchBrowser('chromium' | 'firefox');  ...  b.browser.newPage() ...  await b.close();
// chromium: Debian's chromium (CHROMIUM overrides the path), headless, over the DevTools protocol;
//   WebGL from SwiftShader.
// firefox: Debian's firefox-esr (FIREFOX overrides the path) over WebDriver BiDi, which Firefox
//   speaks natively (no geckodriver). Headless Firefox has no WebGL on Linux (Mozilla bug 1375585:
//   "Exhausted GL driver options" whatever the prefs), so it runs as a normal window on a private
//   Xvfb display (Debian's xvfb; Unix socket only, display number chosen by Xvfb) and draws with
//   Mesa's llvmpipe.
// Throws naming what to install when a browser or Xvfb is missing.
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const here = path.dirname(fileURLToPath(import.meta.url));
const puppeteer = createRequire(`${here}/package.json`)('puppeteer-core');

function need(file, what) {
  if (!fs.existsSync(file)) throw new Error(`no ${what} at ${file} (install Debian's packages: ./slide setup)`);
}

// Starts Xvfb on a free display; resolves to { display: ':N', stop() }.
function startXvfb() {
  need('/usr/bin/Xvfb', 'Xvfb');
  const x = spawn('/usr/bin/Xvfb', ['-displayfd', '3', '-nolisten', 'tcp', '-screen', '0', '1280x1024x24'],
    { stdio: ['ignore', 'ignore', 'pipe', 'pipe'] });
  let err = '';
  x.stderr.on('data', (d) => { err += d; });
  const stop = () => { if (x.exitCode === null) x.kill(); };
  process.on('exit', stop);
  return new Promise((resolve, reject) => {
    let out = '';
    x.stdio[3].on('data', (d) => {
      out += d;
      if (out.includes('\n')) resolve({ display: `:${out.trim()}`, stop });
    });
    x.on('exit', (code) => reject(new Error(`Xvfb exited (${code}) before giving a display: ${err.trim()}`)));
  });
}

export async function launchBrowser(name) {
  if (name === 'chromium') {
    const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';
    need(executablePath, 'Chromium');
    const browser = await puppeteer.launch({
      browser: 'chrome', executablePath, headless: true,
      args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
        '--disable-component-update', '--disable-sync', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
    });
    return { browser, close: () => browser.close() };
  }
  if (name === 'firefox') {
    const executablePath = process.env.FIREFOX || '/usr/bin/firefox-esr';
    need(executablePath, 'Firefox');
    const x = await startXvfb();
    try {
      const browser = await puppeteer.launch({
        browser: 'firefox', executablePath, headless: false, env: { ...process.env, DISPLAY: x.display },
        // Nothing but the page's own origin: no updates, telemetry or remote settings.
        extraPrefsFirefox: { 'network.dns.disableIPv6': true, 'app.normandy.enabled': false,
          'messaging-system.rsexperimentloader.enabled': false, 'services.settings.server': 'http://127.0.0.1:9/' },
      });
      return { browser, close: async () => { try { await browser.close(); } finally { x.stop(); } } };
    } catch (e) {
      x.stop();
      throw e;
    }
  }
  throw new Error(`unknown browser '${name}' (chromium or firefox)`);
}

// A page of `width` x `height` CSS pixels.
export async function openPage(browser, width, height) {
  const page = await browser.newPage();
  await page.setViewport({ width, height });
  return page;
}

export const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

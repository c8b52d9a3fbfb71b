// Opens the viewer in headless Chromium (Debian's /usr/bin/chromium, or CHROMIUM), waits until the
// nodes in view are loaded, screenshots it (far.png), moves the camera to 15% of its distance, waits
// again and screenshots (near.png), then moves it back and waits again; prints the viewer's state at
// the three and every error it logged as JSON.
// usage: node screenshot.mjs URL FOLDER   (serve.py --snapshots runs it)
import { chromium } from 'playwright-core';

const [url, folder] = process.argv.slice(2);
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader'],
});
try {
  const page = await browser.newPage({ viewport: { width: 800, height: 600 } });
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(url);
  const done = () => window.viewerState && (window.viewerState.ready || window.viewerState.errors.length > 0);
  async function settled() {  // ready twice, a moment apart: no load started by the last frame
    await page.waitForFunction(done, null, { timeout: 120000 });
    await page.waitForTimeout(500);
    await page.waitForFunction(done, null, { timeout: 120000 });
    return page.evaluate(() => ({ ...window.viewerState }));
  }
  const far = await settled();
  await page.screenshot({ path: `${folder}/far.png` });
  if (await page.evaluate(() => Boolean(window.viewer))) {
    await page.evaluate(() => window.viewer.zoom(0.15));
    const near = await settled();
    await page.screenshot({ path: `${folder}/near.png` });
    await page.evaluate(() => window.viewer.zoom(1 / 0.15));
    const back = await settled();
    console.log(JSON.stringify({ far, near, back, errors }));
  } else {  // it stopped before it could draw
    console.error(`the page stopped: ${[...far.errors, ...errors].join('; ')}`);
    process.exitCode = 1;
  }
} finally {
  await browser.close();
}

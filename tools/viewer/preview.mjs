// Renders a report page's contact sheet to PNG with headless Chromium (Debian's chromium, driven by
// playwright-core). Fails, with the reason on its last line, on any console error of the page.
//   node tools/viewer/preview.mjs PAGE.html OUT.png
import { chromium } from 'playwright-core';
import { existsSync, writeFileSync } from 'node:fs';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

export const CHROMIUM = process.env.OMSK_CHROMIUM || '/usr/bin/chromium';

/** Opens \p page in headless Chromium (software WebGL), waits for the viewer; returns {browser, page, errors}. */
export async function openReport(pagePath) {
  if (!existsSync(CHROMIUM)) throw new Error(`no Chromium at ${CHROMIUM} (apt-get install chromium, or set OMSK_CHROMIUM)`);
  const browser = await chromium.launch({
    executablePath: CHROMIUM,
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
  const page = await browser.newPage({ viewport: { width: 1600, height: 1000 } });
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.goto(pathToFileURL(resolve(pagePath)).href);
  await page.waitForFunction(() => window.omsk !== undefined, null, { timeout: 60000 });
  await page.evaluate(() => window.omsk.ready);
  return { browser, page, errors };
}

async function main() {
  const [pagePath, png] = process.argv.slice(2);
  if (!pagePath || !png) throw new Error('usage: node preview.mjs PAGE.html OUT.png');
  const { browser, page, errors } = await openReport(pagePath);
  try {
    const url = await page.evaluate(() => window.omsk.contactSheet());
    if (errors.length) throw new Error(`the page logged an error: ${errors[0]}`);
    writeFileSync(png, Buffer.from(url.replace(/^data:image\/png;base64,/, ''), 'base64'));
  } finally {
    await browser.close();
  }
}

if (import.meta.url === pathToFileURL(process.argv[1]).href) {
  main().catch((e) => {
    console.error(String(e.message ?? e).split('\n')[0]);
    process.exit(1);
  });
}

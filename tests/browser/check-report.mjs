// Opens a skinned-decimate report page in headless Chromium and checks what a user relies on: it loads with
// no console error, every view shows something, the scrubber and the wireframe switch change the picture.
//   node tests/browser/check-report.mjs PAGE.html EXPECTED_VIEWS
// Exit 0: all good; 1: a check failed (the reason on the last line); 77: no browser here (a skip).
import { existsSync } from 'node:fs';
import { CHROMIUM, openReport } from '../../tools/viewer/preview.mjs';

const [pagePath, expected] = process.argv.slice(2);
if (!existsSync(CHROMIUM)) {
  console.log(`no Chromium at ${CHROMIUM}: browser checks skipped`);
  process.exit(77);
}
const { browser, page, errors } = await openReport(pagePath);
const fail = async (msg) => {
  console.error(msg);
  await browser.close();
  process.exit(1);
};
// Per view: how many distinct colours its rectangle holds, and a hash of its pixels.
const views = () => page.evaluate(() => window.omsk.sections.flatMap((s) => s.views.map((v, i) => {
  s.render();
  const r = s.rect(i);
  const c = document.createElement('canvas');
  c.width = r.w;
  c.height = r.h;
  const g = c.getContext('2d');
  g.drawImage(s.canvas, r.x, r.y, r.w, r.h, 0, 0, r.w, r.h);
  const px = g.getImageData(0, 0, r.w, r.h).data;
  const colours = new Set();
  let hash = 0;
  for (let k = 0; k < px.length; k += 4) {
    colours.add((px[k] << 16) | (px[k + 1] << 8) | px[k + 2]);
    hash = (hash * 31 + px[k] + 7 * px[k + 1] + 13 * px[k + 2]) >>> 0;
  }
  return { label: v.spec.label, colours: colours.size, hash };
})));

await page.evaluate(() => window.omsk.setTime(0.1));
const before = await views();
if (errors.length) await fail(`console error: ${errors[0]}`);
if (expected && before.length !== Number(expected)) await fail(`${before.length} views, expected ${expected}`);
for (const v of before) if (v.colours < 20) await fail(`view "${v.label}" is blank (${v.colours} colours)`);

// The scrubber: the page's own input element, as a user drags it.
await page.evaluate(() => {
  const s = window.omsk.sections[0];
  s.scrubber.value = '600';
  s.scrubber.dispatchEvent(new Event('input'));
});
const scrubbed = await views();
if (scrubbed[0].hash === before[0].hash) await fail('moving the scrubber did not change the original view');
await page.click('#omsk-section-0 input.wireframe');
const wire = await views();
if (wire.every((v, i) => v.hash === scrubbed[i].hash)) await fail('the wireframe switch changed nothing');
if (errors.length) await fail(`console error: ${errors[0]}`);
await browser.close();
console.log(`ok: ${before.length} views`);

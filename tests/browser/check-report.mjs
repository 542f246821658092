// Opens a skinned-decimate report page in headless Chromium and checks what a user relies on: it loads with
// no console error, every view shows something and is framed whole over the clip, the scrubber and the
// wireframe switch change the picture, vertex colours and the heat map take turns.
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

// Framing: at times spread over the clip, no view's character touches its cell's border (it is all in the
// picture) and it fills a fair part of the cell (the camera is not framing something much larger).
const framing = () => page.evaluate(() => window.omsk.sections.flatMap((s) => s.views.map((v, i) => {
  s.render();
  const r = s.rect(i);
  const c = document.createElement('canvas');
  c.width = r.w;
  c.height = r.h;
  const g = c.getContext('2d');
  g.drawImage(s.canvas, r.x, r.y, r.w, r.h, 0, 0, r.w, r.h);
  const px = g.getImageData(0, 0, r.w, r.h).data;
  const at = (x, y) => 4 * (y * r.w + x);
  const bg = [px[0], px[1], px[2]];
  const fg = (x, y) => Math.max(...[0, 1, 2].map((k) => Math.abs(px[at(x, y) + k] - bg[k]))) > 6;
  let border = 0, x0 = r.w, x1 = -1, y0 = r.h, y1 = -1;
  for (let y = 0; y < r.h; ++y)
    for (let x = 0; x < r.w; ++x) {
      if (!fg(x, y)) continue;
      if (x < 2 || y < 2 || x >= r.w - 2 || y >= r.h - 2) ++border;
      x0 = Math.min(x0, x), x1 = Math.max(x1, x), y0 = Math.min(y0, y), y1 = Math.max(y1, y);
    }
  const fill = Math.max(x1 - x0 + 1, y1 - y0 + 1) / Math.min(r.w, r.h);
  return { label: v.spec.label, border, fill, time: s.time };
})));
for (const f of [0, 0.2, 0.4, 0.6, 0.8, 1]) {
  await page.evaluate((f) => window.omsk.sections.forEach((s) => { s.setPlaying(false); s.setTime(f * s.duration() * 0.999); }), f);
  for (const v of await framing()) {
    if (v.border > 0) await fail(`view "${v.label}" at ${v.time.toFixed(2)} s is cut off by its frame (${v.border} border pixels)`);
    if (v.fill < 0.3) await fail(`view "${v.label}" at ${v.time.toFixed(2)} s fills only ${(100 * v.fill).toFixed(0)}% of its frame`);
  }
}

await page.evaluate(() => window.omsk.setTime(0.1));
const before = await views();
if (errors.length) await fail(`console error: ${errors[0]}`);
if (expected && before.length !== Number(expected)) await fail(`${before.length} views, expected ${expected}`);
for (const v of before) if (v.colours < 20) await fail(`view "${v.label}" is blank (${v.colours} colours)`);

// Vertex colours: the heat map's in the error look, the LOD's own COLOR_0 (or none) as it looks.
const colourMixUps = await page.evaluate(() => {
  const bad = [];
  for (const s of window.omsk.sections) {
    const was = s.heat.checked;
    for (const heat of [false, true]) {
      s.heat.checked = heat;
      s.applyLook();
      for (const v of s.views)
        for (const m of v.meshes) {
          const want = heat && m.hasError ? m.heatColour : m.own;
          if ((m.object.geometry.getAttribute('color') ?? null) !== (want ?? null))
            bad.push(`view "${v.spec.label}" shows the wrong colours with the heat map ${heat ? 'on' : 'off'}`);
        }
    }
    s.heat.checked = was;
    s.applyLook();
  }
  return bad;
});
if (colourMixUps.length) await fail(colourMixUps[0]);

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
// The contact sheet: each LOD as it looks and, beside it, as its error; the two cells differ.
const sheet = await page.evaluate(async () => {
  const img = new Image();
  img.src = window.omsk.contactSheet(undefined, 120);
  await img.decode();
  const c = document.createElement('canvas');
  c.width = img.width;
  c.height = img.height;
  const g = c.getContext('2d');
  g.drawImage(img, 0, 0);
  const cell = (row, col) => {
    const px = g.getImageData(170 + col * 120, row * 138 + 18, 120, 120).data;
    let hash = 0, ink = 0;
    for (let k = 0; k < px.length; k += 4) {
      hash = (hash * 31 + px[k] + 7 * px[k + 1] + 13 * px[k + 2]) >>> 0;
      ink += px[k] + px[k + 1] + px[k + 2] < 3 * 235;
    }
    return { hash, ink };
  };
  const views = window.omsk.sections[0].views.length;
  return { width: img.width, rows: views, look: cell(1, 0), error: cell(1, 1) };
});
if (sheet.rows > 1) {
  if (sheet.look.ink < 100) await fail('the contact sheet shows no LOD as it looks');
  if (sheet.look.hash === sheet.error.hash) await fail('the contact sheet shows the LOD the same with and without its error');
}
if (errors.length) await fail(`console error: ${errors[0]}`);
await browser.close();
console.log(`ok: ${before.length} views`);

// Opens a batch's index.html in headless Chromium and checks what a pipeline engineer relies on: it loads
// with no console error, it shows one row per asset with its status, a failure's row shows its one-line reason,
// and every link of a row that did not fail leads to a file that exists.
//   node tests/browser/check-batch-index.mjs OUT_DIR/index.html OK FAILED SKIPPED
// Exit 0: all good; 1: a check failed (the reason on the last line); 77: no browser here (a skip).
import { existsSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { CHROMIUM } from '../../tools/viewer/preview.mjs';

// The pinned npm tools live in tools/node_modules, which Node does not search from tests/.
const { chromium } = createRequire(new URL('../../tools/package.json', import.meta.url))('playwright-core');

const [indexPath, ok, failed, skipped] = process.argv.slice(2);
if (!existsSync(CHROMIUM)) {
  console.log(`no Chromium at ${CHROMIUM}: browser checks skipped`);
  process.exit(77);
}
const browser = await chromium.launch({ executablePath: CHROMIUM });
const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
const errors = [];
page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
page.on('pageerror', (e) => errors.push(String(e)));
const fail = async (msg) => {
  console.error(msg);
  await browser.close();
  process.exit(1);
};
await page.goto(pathToFileURL(resolve(indexPath)).href);
const rows = await page.$$eval('tbody tr', (trs) => trs.map((tr) => {
  const box = tr.getBoundingClientRect();
  return {
    status: tr.className,
    name: tr.dataset.name,
    cells: [...tr.querySelectorAll('td')].map((td) => td.innerText),
    reason: tr.querySelector('td.reason')?.innerText ?? null,
    links: [...tr.querySelectorAll('a')].map((a) => a.href),
    shown: box.height > 0 && box.width > 0,
  };
}));
if (errors.length) await fail(`console errors: ${errors.join(' | ')}`);
const count = (s) => rows.filter((r) => r.status === s).length;
const want = { ok: Number(ok), failed: Number(failed), skipped: Number(skipped) };
for (const s of Object.keys(want))
  if (count(s) !== want[s]) await fail(`${count(s)} rows ${s}, expected ${want[s]}`);
if (rows.length !== want.ok + want.failed + want.skipped) await fail(`${rows.length} rows in all`);
for (const r of rows) {
  if (!r.shown) await fail(`row ${r.name} is not shown`);
  if (r.status === 'failed') {
    if (!r.reason || r.reason.trim() === '' || r.reason.includes('\n'))
      await fail(`failed row ${r.name}: reason ${JSON.stringify(r.reason)} is not one line`);
  } else {
    if (r.links.length < 3) await fail(`row ${r.name} links to ${r.links.length} files (LODs, report, log expected)`);
    for (const href of r.links)
      if (!existsSync(fileURLToPath(href))) await fail(`row ${r.name} links to ${href}, which does not exist`);
  }
}
const totals = await page.$eval('#totals', (p) => p.innerText);
if (!totals.startsWith(`${want.ok} ok, ${want.failed} failed, ${want.skipped} skipped`))
  await fail(`totals line says: ${totals}`);
console.log(JSON.stringify({ rows: rows.length, dir: dirname(resolve(indexPath)) }));
await browser.close();

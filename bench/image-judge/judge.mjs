// The image judge's driver (bench/image-judge.sh writes its job list): renders every character and its LODs in
// headless Chromium (page.js, three.js) at the held-out frames of our tool's report, prints one table row per
// character and ratio, and writes JSON lines and side-by-side PNGs when asked.
//   node bench/image-judge/judge.mjs JOBS.tsv [--size PX] [--frames K] [--jsonl FILE] [--images DIR]
// JOBS.tsv: character, original, ratio, gltfpack's triangles (0: it kept none), gltfpack's LOD, ours, our
// --report JSON and, optionally, the --report JSON whose held-out frames to render in instead; tab-separated, one
// line per character and ratio.
import { createRequire } from 'node:module';
import { existsSync, mkdirSync, readFileSync, writeFileSync, renameSync } from 'node:fs';
import { dirname, extname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { pool } from './metrics.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const tools = resolve(here, '../../tools');
// The pinned npm tools live in tools/node_modules, not on this file's resolution path.
const toolsRequire = createRequire(join(tools, 'package.json'));
const { chromium } = toolsRequire('playwright-core');
const { buildSync } = toolsRequire('esbuild');
const CHROMIUM = process.env.OMSK_CHROMIUM || '/usr/bin/chromium';
const ORIGIN = 'http://judge.invalid';
const DIRECTIONS = ['front', 'side', 'back', 'three-quarter above'];

function args(argv) {
  const o = { size: 384, frames: 4, jsonl: null, images: null, jobs: null };
  for (let i = 0; i < argv.length; ++i) {
    const a = argv[i], next = () => {
      if (i + 1 >= argv.length) throw new Error(`${a} needs a value`);
      return argv[++i];
    };
    if (a === '--size') o.size = Number(next());
    else if (a === '--frames') o.frames = Number(next());
    else if (a === '--jsonl') o.jsonl = next();
    else if (a === '--images') o.images = next();
    else if (!o.jobs) o.jobs = a;
    else throw new Error(`unexpected argument ${a}`);
  }
  if (!o.jobs) throw new Error('usage: node judge.mjs JOBS.tsv [--size PX] [--frames K] [--jsonl FILE] [--images DIR]');
  if (!(o.size >= 16 && o.size <= 2048)) throw new Error(`--size ${o.size}: give 16 to 2048 pixels`);
  if (!(Number.isInteger(o.frames) && o.frames >= 1)) throw new Error(`--frames ${o.frames}: give a whole number from 1`);
  return o;
}

function readJobs(path) {
  const characters = new Map();
  for (const line of readFileSync(path, 'utf8').split('\n')) {
    if (!line.trim()) continue;
    const [name, original, ratio, triangles, gp, ours, report, frames] = line.split('\t');
    if (!characters.has(name)) characters.set(name, { name, original, levels: [] });
    characters.get(name).levels.push({ ratio, gpTriangles: Number(triangles), gp, ours, report, frames });
  }
  return [...characters.values()];
}

// Evenly thinned, as the tool thins its own list (PoseSchedule's thin).
const thin = (v, n) => (v.length <= n ? v : Array.from({ length: n }, (_, i) => v[Math.floor((i * v.length) / n)]));

function page() {
  const js = buildSync({
    entryPoints: [join(here, 'page.js')], bundle: true, format: 'iife', target: 'es2020', write: false,
    nodePaths: [join(tools, 'node_modules')], logLevel: 'error',
  }).outputFiles[0].text;
  return `<!doctype html><html><body style="margin:0"><script>${js.replace(/<\/script/gi, '<\\/script')}</script></body></html>`;
}

const TYPES = { '.glb': 'model/gltf-binary', '.gltf': 'model/gltf+json', '.bin': 'application/octet-stream',
  '.png': 'image/png', '.jpg': 'image/jpeg', '.jpeg': 'image/jpeg', '.bmp': 'image/bmp', '.tga': 'image/x-tga' };
const url = (path) => ORIGIN + encodeURI(resolve(path));

const num = (x, d) => (x === null || x === undefined ? '-' : x === Infinity ? 'inf' : x.toFixed(d));

function row(c, level, gp, ours, note) {
  const cell = (a, b, d, w) => `${num(a, d).padStart(w)} ${num(b, d).padStart(w)}`;
  const mse = gp && ours && gp.all.mse > 0 ? (ours.all.mse / gp.all.mse).toFixed(2) : '-';
  const tris = `${level.gpTriangles}/${level.oursTriangles ?? '-'}`;
  return `${c.name.padEnd(12)} ${level.ratio.padStart(5)} ${tris.padStart(11)} | ` +
    `${cell(gp?.interior.psnr, ours?.interior.psnr, 2, 6)} | ${cell(gp?.silhouette.psnr, ours?.silhouette.psnr, 2, 6)} | ` +
    `${cell(gp?.interior.ssim, ours?.interior.ssim, 4, 6)} | ${cell(gp?.silhouette.ssim, ours?.silhouette.ssim, 4, 6)} | ` +
    `${mse.padStart(7)}${note ? `  ${note}` : ''}`;
}

const HEADER = `${'character'.padEnd(12)} ${'ratio'.padStart(5)} ${'triangles'.padStart(11)} | ` +
  `${'PSNR interior'.padStart(13)} | ${'PSNR silh.'.padStart(13)} | ${'SSIM interior'.padStart(13)} | ` +
  `${'SSIM silh.'.padStart(13)} | ${'MSE'.padStart(7)}\n${''.padEnd(30)} | ${'gp'.padStart(6)} ${'ours'.padStart(6)} | ` +
  `${'gp'.padStart(6)} ${'ours'.padStart(6)} | ${'gp'.padStart(6)} ${'ours'.padStart(6)} | ${'gp'.padStart(6)} ` +
  `${'ours'.padStart(6)} | ${'ours/gp'.padStart(7)}`;

const textureNote = (who, f) => (f && f.missing ? `${who}: ${f.missing} of ${f.textures} textures did not load` : '');

async function judgeCharacter(page, c, o, out) {
  const levels = c.levels.filter((l) => l.gpTriangles > 0);
  const none = (l) => `${c.name.padEnd(12)} ${l.ratio.padStart(5)}   gltfpack kept no triangle`;
  const noneLine = (l) => JSON.stringify({ character: c.name, ratio: Number(l.ratio), gltfpack: { triangles: 0 },
    notes: ['gltfpack kept no triangle'] });
  if (!levels.length) {
    for (const l of c.levels) out.rows.push(none(l)), out.jsonl.push(noneLine(l));
    return;
  }
  const reports = levels.map((l) => JSON.parse(readFileSync(l.report, 'utf8')));
  levels.forEach((l, i) => { l.oursTriangles = reports[i].lods[0].faces; });
  const framesReport = levels[0].frames ? JSON.parse(readFileSync(levels[0].frames, 'utf8')) : reports[0];
  const held = thin(framesReport.lods[0].heldout_times ?? [], o.frames);
  const job = {
    original: url(c.original), size: o.size, directions: DIRECTIONS, frames: held,
    lods: levels.flatMap((l) => [{ key: `gp ${l.ratio}`, url: url(l.gp) }, { key: `ours ${l.ratio}`, url: url(l.ours) }]),
    sheets: o.images ? levels.map((l) => [`gp ${l.ratio}`, `ours ${l.ratio}`]) : [],
  };
  const r = await page.evaluate((j) => window.judge.run(j), job);
  for (const l of c.levels) {
    if (l.gpTriangles === 0) {
      out.rows.push(none(l));
      out.jsonl.push(noneLine(l));
      continue;
    }
    const res = (k) => r.lods[`${k} ${l.ratio}`];
    const [gp, ours] = [res('gp'), res('ours')];
    const pooled = (x) => (x.error ? null : pool(x.views));
    const notes = [textureNote('original', r.original), textureNote('gltfpack', gp), textureNote('ours', ours),
      gp.error ? `gltfpack's LOD: ${gp.error}` : '', ours.error ? `our LOD: ${ours.error}` : ''].filter(Boolean);
    const [pg, po] = [pooled(gp), pooled(ours)];
    out.rows.push(row(c, l, pg, po, notes.join('; ')));
    out.jsonl.push(JSON.stringify({
      character: c.name, ratio: Number(l.ratio), frames: held, directions: DIRECTIONS, size: o.size,
      textures: r.original.textures, original_triangles: r.original.triangles,
      gltfpack: { triangles: l.gpTriangles, ...(pg ?? { error: gp.error }) },
      ours: { triangles: l.oursTriangles, ...(po ?? { error: ours.error }) }, notes,
    }, (k, v) => (v === Infinity ? 'inf' : v)));
  }
  if (o.images)
    for (const s of r.sheets) {
      const ratio = s.keys[0].split(' ')[1];
      const file = join(o.images, `${c.name}-${ratio}-frame${s.frame}.png`);
      writeFileSync(`${file}.tmp`, Buffer.from(s.png.replace(/^data:image\/png;base64,/, ''), 'base64'));
      renameSync(`${file}.tmp`, file);
    }
}

async function main() {
  const o = args(process.argv.slice(2));
  if (!existsSync(CHROMIUM)) throw new Error(`no Chromium at ${CHROMIUM} (scripts/setup installs it, or set OMSK_CHROMIUM)`);
  if (o.images) mkdirSync(o.images, { recursive: true });
  const html = page();
  const browser = await chromium.launch({
    executablePath: CHROMIUM, args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
  try {
    const p = await browser.newPage();
    const errors = [];
    p.on('pageerror', (e) => errors.push(String(e)));
    await p.route(`${ORIGIN}/**`, (route) => {
      const path = decodeURI(new URL(route.request().url()).pathname);
      if (path === '/index.html') return route.fulfill({ body: html, contentType: 'text/html' });
      if (!existsSync(path)) return route.fulfill({ status: 404, body: `${path} not found` });
      return route.fulfill({ body: readFileSync(path), contentType: TYPES[extname(path).toLowerCase()] ?? 'application/octet-stream' });
    });
    await p.goto(`${ORIGIN}/index.html`);
    await p.waitForFunction(() => window.judge !== undefined, null, { timeout: 60000 });
    console.log(HEADER);
    const out = { rows: [], jsonl: [] };
    for (const c of readJobs(o.jobs)) {
      const before = out.rows.length;
      try {
        await judgeCharacter(p, c, o, out);
      } catch (e) {
        const why = String(e.message ?? e).split('\n')[0].replace(/^page\.evaluate: (Error: )?/, '');
        out.rows.push(`${c.name.padEnd(12)} failed: ${why}`);
        out.jsonl.push(JSON.stringify({ character: c.name, error: why }));
      }
      for (const r of out.rows.slice(before)) console.log(r);
    }
    if (errors.length) console.log(`the page reported: ${errors[0]}`);
    if (o.jsonl) {
      writeFileSync(`${o.jsonl}.tmp`, out.jsonl.map((l) => `${l}\n`).join(''));
      renameSync(`${o.jsonl}.tmp`, o.jsonl);
    }
  } finally {
    await browser.close();
  }
}

main().catch((e) => {
  console.error(`image-judge: ${String(e.message ?? e).split('\n')[0]}`);
  process.exit(1);
});

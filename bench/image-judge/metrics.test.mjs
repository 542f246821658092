// The image judge's metrics on images whose answer is known: identical images, a uniform change of colour,
// a checkerboard of noise, a one-pixel shift of the mask. Run by ctest (image_judge_metrics).
//   node bench/image-judge/metrics.test.mjs
import assert from 'node:assert/strict';
import {
  regions, compareView, psnr, ssimMap, ssimSums, luma, pool, INTERIOR, SILHOUETTE, GAUSSIAN, SSIM_C1, SSIM_C2,
} from './metrics.mjs';

const W = 20, H = 20;
const image = (f) => {
  const px = new Uint8Array(4 * W * H);
  for (let y = 0; y < H; ++y)
    for (let x = 0; x < W; ++x) {
      const v = f(x, y);
      px.set([v, v, v, 255], 4 * (y * W + x));
    }
  return px;
};
const square = (x0, y0, side) => {
  const m = new Uint8Array(W * H);
  for (let y = y0; y < y0 + side; ++y) for (let x = x0; x < x0 + side; ++x) m[y * W + x] = 1;
  return m;
};
const count = (labels, l) => labels.reduce((s, v) => s + (v === l), 0);
// The sRGB transfer function written out again here, so that the table in metrics.mjs is checked too.
const linear = (v) => { const c = v / 255; return c <= 0.04045 ? c / 12.92 : Math.pow((c + 0.055) / 1.055, 2.4); };
const close = (a, b, tol, what) => assert.ok(Math.abs(a - b) <= tol, `${what}: ${a} against ${b}`);
let checks = 0;
const check = (name, fn) => { fn(); ++checks; console.log(`ok ${name}`); };

check('regions of two equal squares: interior eroded by one pixel, silhouette the band both sides', () => {
  const l = regions(square(5, 5, 10), square(5, 5, 10), W, H);
  assert.equal(count(l, INTERIOR), 8 * 8);
  assert.equal(count(l, SILHOUETTE), 12 * 12 - 8 * 8);
});

check('regions of a square and its one-pixel shift', () => {
  const l = regions(square(5, 5, 10), square(6, 5, 10), W, H);
  assert.equal(count(l, INTERIOR), 7 * 8);  // the overlap (9 x 10) eroded
  assert.equal(count(l, SILHOUETTE), 13 * 12 - 7 * 8);  // the union grown by one pixel, less the interior
});

check('identical images: infinite PSNR and SSIM 1 in both regions', () => {
  const a = image((x, y) => (x * 13 + y * 7) % 256), m = square(5, 5, 10);
  const r = pool([compareView(a, m, a, m, W, H)]);
  assert.equal(r.interior.psnr, Infinity);
  assert.equal(r.silhouette.psnr, Infinity);
  close(r.interior.ssim, 1, 1e-12, 'interior SSIM');
  close(r.silhouette.ssim, 1, 1e-12, 'silhouette SSIM');
});

check('a uniform change of colour inside the character: PSNR from the linear difference', () => {
  const m = square(5, 5, 10);
  const a = image(() => 100), b = image((x, y) => (m[y * W + x] ? 120 : 100));
  const d = linear(120) - linear(100);
  const r = pool([compareView(a, m, b, m, W, H)]);
  close(r.interior.psnr, -20 * Math.log10(d), 1e-9, 'interior PSNR');
  // The silhouette band: 36 of its 80 pixels lie inside the square (changed), 44 outside (the background).
  close(r.silhouette.psnr, -10 * Math.log10((36 / 80) * d * d), 1e-9, 'silhouette PSNR');
});

check('noise on half the pixels (a checkerboard) halves the error: +3.01 dB', () => {
  const m = square(0, 0, 20);
  const a = image(() => 100), b = image((x, y) => ((x + y) % 2 ? 120 : 100));
  const full = image(() => 120);
  const half = pool([compareView(a, m, b, m, W, H)]).interior.psnr;
  const all = pool([compareView(a, m, full, m, W, H)]).interior.psnr;
  close(half - all, 10 * Math.log10(2), 1e-9, 'PSNR gain');
});

check('pooled views: PSNR of the summed error, not the mean of the PSNRs', () => {
  const m = square(0, 0, 20), a = image(() => 100);
  const v1 = compareView(a, m, image(() => 120), m, W, H), v2 = compareView(a, m, a, m, W, H);
  const one = pool([v1]).interior.psnr;
  close(pool([v1, v2]).interior.psnr - one, 10 * Math.log10(2), 1e-9, 'pooled PSNR');
  assert.equal(psnr(0, 0), null);
});

check('SSIM of two flat images: the luminance term alone', () => {
  const a = luma(image(() => 128), W * H), b = luma(image(() => 64), W * H);
  const ma = 128 / 255, mb = 64 / 255;
  const want = (2 * ma * mb + SSIM_C1) / (ma * ma + mb * mb + SSIM_C1);
  for (const v of ssimMap(a, b, W, H)) close(v, want, 1e-9, 'SSIM');
});

check('SSIM of a flat image against checkerboard noise: the closed form away from the border', () => {
  const mu = 128 / 255, eps = 20 / 255;
  const a = luma(image(() => 128), W * H), b = luma(image((x, y) => ((x + y) % 2 ? 148 : 108)), W * H);
  const map = ssimMap(a, b, W, H);
  // The window's mean of the sign (-1)^(x+y) is s0 q^2, q the 1-D Gaussian's alternating mean.
  const q = GAUSSIAN.reduce((s, g, k) => s + g * (k % 2 ? -1 : 1), 0) / GAUSSIAN.reduce((s, g) => s + g, 0);
  for (const [x, y] of [[10, 10], [11, 10], [7, 12]]) {
    const s0 = (x + y) % 2 ? 1 : -1;
    const mb = mu + eps * s0 * q * q, vb = eps * eps * (1 - q ** 4);
    const want = ((2 * mu * mb + SSIM_C1) / (mu * mu + mb * mb + SSIM_C1)) * (SSIM_C2 / (vb + SSIM_C2));
    close(map[y * W + x], want, 1e-9, `SSIM at (${x}, ${y})`);
  }
});

check('SSIM on the cropped rectangle equals SSIM on the whole image at every counted pixel', () => {
  const a = image((x, y) => (x * 37 + y * 11) % 256), b = image((x, y) => (x * 37 + y * 13) % 256);
  const ma = square(8, 9, 6), mb = square(9, 8, 6);
  const v = compareView(a, ma, b, mb, W, H);
  const whole = ssimSums(ssimMap(luma(a, W * H), luma(b, W * H), W, H), regions(ma, mb, W, H));
  for (const [r, key] of [[INTERIOR, 'interior'], [SILHOUETTE, 'silhouette']]) {
    assert.equal(v[key].pixels, whole[r].n);
    close(v[key].ssim_sum, whole[r].sum, 1e-9, `${key} SSIM sum`);
  }
});

console.log(`${checks} checks passed`);

// The image judge's metrics, on two renders of one view (RGBA, 8-bit sRGB as the canvas shows them) and the
// two coverage masks (1 where the character covers the pixel). Pure functions, no browser: the page bundles
// this file and metrics.test.mjs checks it under Node.
//
// Regions: the interior is where both masks cover the whole 3x3 neighbourhood (both show the character, away
// from its outline); the silhouette is every other pixel within one pixel of either mask (the outline band of
// both, and where one shows the character and the other the background). Elsewhere both show the background,
// identically, and nothing is counted.

export const BACKGROUND = 0, INTERIOR = 1, SILHOUETTE = 2;

// 8-bit sRGB -> linear (IEC 61966-2-1), as a table.
export const SRGB_TO_LINEAR = new Float64Array(256).map((_, i) => {
  const c = i / 255;
  return c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4;
});

// A 3x3 minimum (erode) or maximum (dilate) of a 0/1 image, in two 1-D passes; outside the image counts as 0.
function filter3(src, w, h, dilate) {
  const tmp = new Uint8Array(w * h), out = new Uint8Array(w * h);
  const pass = (from, to, len, stride, lines, lineStride) => {
    for (let l = 0; l < lines; ++l) {
      const o = l * lineStride;
      for (let i = 0; i < len; ++i) {
        const m = from[o + i * stride], lo = i > 0 ? from[o + (i - 1) * stride] : 0;
        const hi = i + 1 < len ? from[o + (i + 1) * stride] : 0;
        to[o + i * stride] = dilate ? m | lo | hi : m & lo & hi;
      }
    }
  };
  pass(src, tmp, w, 1, h, w);
  pass(tmp, out, h, w, w, 1);
  return out;
}

/** Labels every pixel BACKGROUND, INTERIOR or SILHOUETTE from the two masks (Uint8Array, w*h, 0/1). */
export function regions(maskA, maskB, w, h) {
  const both = new Uint8Array(w * h), either = new Uint8Array(w * h);
  for (let p = 0; p < w * h; ++p) {
    both[p] = maskA[p] & maskB[p];
    either[p] = maskA[p] | maskB[p];
  }
  const inner = filter3(both, w, h, false), near = filter3(either, w, h, true);
  const labels = new Uint8Array(w * h);
  for (let p = 0; p < w * h; ++p) labels[p] = inner[p] ? INTERIOR : near[p] ? SILHOUETTE : BACKGROUND;
  return labels;
}

/** Per region: the sum of squared differences of linear RGB and the number of channel samples summed. */
export function squaredErrors(rgbaA, rgbaB, labels) {
  const out = { [INTERIOR]: { sse: 0, n: 0 }, [SILHOUETTE]: { sse: 0, n: 0 } };
  for (let p = 0; p < labels.length; ++p) {
    const r = out[labels[p]];
    if (!r) continue;
    for (let k = 0; k < 3; ++k) {
      const d = SRGB_TO_LINEAR[rgbaA[4 * p + k]] - SRGB_TO_LINEAR[rgbaB[4 * p + k]];
      r.sse += d * d;
    }
    r.n += 3;
  }
  return out;
}

/** PSNR in dB for values in [0, 1] from a sum of squared errors over n samples: Infinity when equal, null when
 *  there is nothing to compare. */
export function psnr(sse, n) {
  if (n === 0) return null;
  return sse === 0 ? Infinity : 10 * Math.log10(n / sse);
}

/** Luma of the display values (Rec. 709 weights on the sRGB-encoded channels, in [0, 1]): SSIM's input. */
export function luma(rgba, count) {
  const y = new Float64Array(count);
  for (let p = 0; p < count; ++p) y[p] = (0.2126 * rgba[4 * p] + 0.7152 * rgba[4 * p + 1] + 0.0722 * rgba[4 * p + 2]) / 255;
  return y;
}

// Wang et al. 2004: an 11x11 Gaussian window of sigma 1.5, C1 = (0.01 L)^2, C2 = (0.03 L)^2, L = 1.
export const SSIM_RADIUS = 5, SSIM_SIGMA = 1.5, SSIM_C1 = 0.01 ** 2, SSIM_C2 = 0.03 ** 2;
export const GAUSSIAN = (() => {
  const g = new Float64Array(2 * SSIM_RADIUS + 1);
  for (let i = -SSIM_RADIUS; i <= SSIM_RADIUS; ++i) g[i + SSIM_RADIUS] = Math.exp(-(i * i) / (2 * SSIM_SIGMA * SSIM_SIGMA));
  return g;
})();

// Separable Gaussian blur; the window is cut at the image's border and renormalised over what is left. The
// vertical pass adds whole rows (memory order).
function blur(src, w, h) {
  const tmp = new Float64Array(w * h), out = new Float64Array(w * h), r = SSIM_RADIUS, g = GAUSSIAN;
  const weights = (len) => Float64Array.from({ length: len }, (_, i) => {
    let ws = 0;
    for (let k = Math.max(-r, -i); k <= Math.min(r, len - 1 - i); ++k) ws += g[k + r];
    return ws;
  });
  const wx = weights(w), wy = weights(h);
  for (let y = 0; y < h; ++y)
    for (let x = 0, o = y * w; x < w; ++x) {
      const k0 = Math.max(-r, -x), k1 = Math.min(r, w - 1 - x);
      let s = 0;
      for (let k = k0; k <= k1; ++k) s += g[k + r] * src[o + x + k];
      tmp[o + x] = s / wx[x];
    }
  for (let y = 0; y < h; ++y) {
    const o = y * w, k1 = Math.min(r, h - 1 - y), ws = wy[y];
    for (let k = Math.max(-r, -y); k <= k1; ++k) {
      const gk = g[k + r] / ws, q = (y + k) * w;
      for (let x = 0; x < w; ++x) out[o + x] += gk * tmp[q + x];
    }
  }
  return out;
}

/** What SSIM needs of the reference image, computed once for every image compared with it: its luma and the
 *  window's mean of it and of its square. */
export function reference(rgba, w, h) {
  const y = luma(rgba, w * h);
  return { w, h, y, mean: blur(y, w, h), meanSq: blur(y.map((v) => v * v), w, h) };
}

// The SSIM map over the rectangle c of the image (cw x ch, row-major) between the reference and luma b.
function ssimOver(ref, b, c) {
  const cw = c.x1 - c.x0 + 1, ch = c.y1 - c.y0 + 1, n = cw * ch;
  const bc = cut(b, ref.w, c, 1), ac = cut(ref.y, ref.w, c, 1), ma = cut(ref.mean, ref.w, c, 1);
  const saa = cut(ref.meanSq, ref.w, c, 1);
  const bb = new Float64Array(n), ab = new Float64Array(n);
  for (let p = 0; p < n; ++p) {
    bb[p] = bc[p] * bc[p];
    ab[p] = ac[p] * bc[p];
  }
  const [mb, sbb, sab] = [bc, bb, ab].map((x) => blur(x, cw, ch));
  const map = new Float64Array(n);
  for (let p = 0; p < n; ++p) {
    const va = saa[p] - ma[p] * ma[p], vb = sbb[p] - mb[p] * mb[p], cov = sab[p] - ma[p] * mb[p];
    map[p] = ((2 * ma[p] * mb[p] + SSIM_C1) * (2 * cov + SSIM_C2)) /
      ((ma[p] * ma[p] + mb[p] * mb[p] + SSIM_C1) * (va + vb + SSIM_C2));
  }
  return map;
}

/** The SSIM map of two luma images (Float64Array, w*h). */
export function ssimMap(a, b, w, h) {
  const ref = { w, h, y: a, mean: blur(a, w, h), meanSq: blur(a.map((v) => v * v), w, h) };
  return ssimOver(ref, b, { x0: 0, y0: 0, x1: w - 1, y1: h - 1 });
}

/** Per region: the sum of the SSIM map and the number of pixels summed. */
export function ssimSums(map, labels) {
  const out = { [INTERIOR]: { sum: 0, n: 0 }, [SILHOUETTE]: { sum: 0, n: 0 } };
  for (let p = 0; p < labels.length; ++p) {
    const r = out[labels[p]];
    if (!r) continue;
    r.sum += map[p];
    ++r.n;
  }
  return out;
}

// The rectangle holding every counted pixel, grown by the SSIM window and cut to the image: SSIM computed on
// it equals SSIM on the whole image at every counted pixel (their windows lie inside it or are cut by the image).
function crop(labels, w, h) {
  let x0 = w, y0 = h, x1 = -1, y1 = -1;
  for (let y = 0; y < h; ++y)
    for (let x = 0; x < w; ++x)
      if (labels[y * w + x] !== BACKGROUND) {
        x0 = Math.min(x0, x), x1 = Math.max(x1, x), y0 = Math.min(y0, y), y1 = Math.max(y1, y);
      }
  if (x1 < 0) return null;
  const r = SSIM_RADIUS;
  return { x0: Math.max(0, x0 - r), y0: Math.max(0, y0 - r), x1: Math.min(w - 1, x1 + r), y1: Math.min(h - 1, y1 + r) };
}

function cut(a, w, c, channels) {
  const cw = c.x1 - c.x0 + 1, ch = c.y1 - c.y0 + 1, out = new a.constructor(cw * ch * channels);
  for (let y = 0; y < ch; ++y) out.set(a.subarray(((c.y0 + y) * w + c.x0) * channels, ((c.y0 + y) * w + c.x1 + 1) * channels), y * cw * channels);
  return out;
}

/** Everything the judge pools for one view: {interior, silhouette} each {sse, samples, ssim_sum, pixels},
 *  and the two masks' pixel counts. \p ref: reference(rgbaA, w, h), when A is compared with several images. */
export function compareView(rgbaA, maskA, rgbaB, maskB, w, h, ref = reference(rgbaA, w, h)) {
  const labels = regions(maskA, maskB, w, h);
  const se = squaredErrors(rgbaA, rgbaB, labels);
  const c = crop(labels, w, h) ?? { x0: 0, y0: 0, x1: 0, y1: 0 };
  const ss = ssimSums(ssimOver(ref, luma(rgbaB, w * h), c), cut(labels, w, c, 1));
  const region = (r) => ({ sse: se[r].sse, samples: se[r].n, ssim_sum: ss[r].sum, pixels: ss[r].n });
  let coveredA = 0, coveredB = 0;
  for (let p = 0; p < w * h; ++p) {
    coveredA += maskA[p];
    coveredB += maskB[p];
  }
  return { interior: region(INTERIOR), silhouette: region(SILHOUETTE), covered_a: coveredA, covered_b: coveredB };
}

/** Pools views' compareView results: PSNR from the summed squared errors, SSIM as the mean over all pixels. */
export function pool(views) {
  const total = (key) => {
    const s = { sse: 0, samples: 0, ssim_sum: 0, pixels: 0 };
    for (const v of views) for (const k of Object.keys(s)) s[k] += v[key][k];
    return s;
  };
  const summary = (s) => ({
    psnr: psnr(s.sse, s.samples),
    ssim: s.pixels ? s.ssim_sum / s.pixels : null,
    mse: s.samples ? s.sse / s.samples : null,
    pixels: s.pixels,
  });
  const i = total('interior'), s = total('silhouette');
  const all = { sse: i.sse + s.sse, samples: i.samples + s.samples, ssim_sum: i.ssim_sum + s.ssim_sum, pixels: i.pixels + s.pixels };
  return { interior: summary(i), silhouette: summary(s), all: summary(all), views: views.length };
}

// The report page's viewer: every character's original and LODs side by side, one shared orbit camera,
// one clip played in sync, the held-out error per vertex as a colour map. Bundled with three.js into the
// page by tools/viewer/build.mjs at build time: the page needs no network.
//
// The page holds <script id="omsk-data" type="application/json"> (written by skinned-decimate --html) and
// either base64 GLBs in it ("glb") or an assets script beside it that calls omskAsset(id, base64) ("asset").
// window.omsk is the handle the tests and the PNG preview drive the page with.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

// Filled by the assets script beside the page (omskAsset(id, base64), defined by the page before it).
const assets = () => window.omskAssets ?? {};

function bytes(base64) {
  const s = atob(base64);
  const out = new Uint8Array(s.length);
  for (let i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
  return out.buffer;
}

// Blue (0) through green and yellow to red (the legend's top and above).
const STOPS = [[0.0, [0.13, 0.24, 0.75]], [0.35, [0.1, 0.7, 0.55]], [0.65, [0.95, 0.85, 0.2]], [1.0, [0.85, 0.1, 0.1]]];
function colour(x) {
  x = Math.min(1, Math.max(0, x));
  for (let i = 1; i < STOPS.length; ++i) {
    if (x <= STOPS[i][0]) {
      const [a, ca] = STOPS[i - 1], [b, cb] = STOPS[i];
      const t = (x - a) / (b - a);
      return ca.map((c, k) => c + t * (cb[k] - c));
    }
  }
  return STOPS[STOPS.length - 1][1];
}
const GRADIENT = `linear-gradient(to right, ${STOPS.map(([x, c]) =>
  `rgb(${c.map((v) => Math.round(v * 255)).join(',')}) ${x * 100}%`).join(', ')})`;

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

class Section {
  constructor(spec, index, root) {
    this.spec = spec;
    this.index = index;
    this.time = 0;
    this.playing = true;
    this.cellW = 300;
    this.cellH = 340;
    this.views = [];
    const n = spec.views.length;
    this.canvas = el('canvas', { id: `omsk-canvas-${index}`, class: 'views' });
    this.canvas.width = this.cellW * n;
    this.canvas.height = this.cellH;
    this.canvas.style.width = `${this.cellW * n}px`;
    this.canvas.style.height = `${this.cellH}px`;
    this.renderer = new THREE.WebGLRenderer({ canvas: this.canvas, antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(1);
    this.renderer.setScissorTest(true);
    this.camera = new THREE.PerspectiveCamera(35, this.cellW / this.cellH, 0.01, 1000);
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.addEventListener('change', () => this.render());

    const labels = el('div', { class: 'labels' });
    labels.style.width = `${this.cellW * n}px`;
    for (const v of spec.views) {
      const err = v.rms === null || v.rms === undefined ? '' : ` · RMS ${v.rms.toFixed(3)}%`;
      labels.append(el('div', { class: 'label' }, `${v.label}`, el('br'), `${v.triangles} triangles${err}`));
    }
    const clipSelect = el('select', { class: 'clip', onchange: (e) => this.setClip(e.target.value) });
    for (const c of spec.clips) clipSelect.append(el('option', { value: c.name }, c.name));
    this.clipSelect = clipSelect;
    this.playButton = el('button', { class: 'play', onclick: () => this.setPlaying(!this.playing) }, 'pause');
    this.scrubber = el('input', { type: 'range', class: 'scrubber', min: '0', max: '1000', value: '0' });
    this.scrubber.addEventListener('input', () => {
      this.setPlaying(false);
      this.setTime((this.scrubber.value / 1000) * this.duration());
    });
    this.wire = el('input', { type: 'checkbox', class: 'wireframe', onchange: () => this.applyLook() });
    this.heat = el('input', { type: 'checkbox', class: 'heat', checked: '', onchange: () => this.applyLook() });
    const legend = el('div', { class: 'legend' },
      el('span', {}, '0'), el('span', { class: 'bar' }), el('span', {}, `${spec.error_scale.toPrecision(2)}% of the diagonal`));
    legend.querySelector('.bar').style.background = GRADIENT;
    const controls = el('div', { class: 'controls' },
      spec.clips.length ? clipSelect : '', this.playButton, this.scrubber,
      el('label', {}, this.wire, ' wireframe'), el('label', {}, this.heat, ' held-out error (max per vertex)'), legend);
    const table = el('table', {}, el('tr', {}, ...['view', 'triangles', 'vertices', 'joints', 'keys', 'max infl',
      'held-out RMS %', 'held-out Hausdorff %', 'seconds'].map((h) => el('th', {}, h))));
    for (const v of spec.views) {
      const f = (x, d) => (x === null || x === undefined ? '–' : Number(x).toFixed(d));
      table.append(el('tr', {}, ...[v.label, v.triangles, v.vertices, v.joints, v.keys, v.max_influences ?? '–',
        f(v.rms, 4), f(v.hausdorff, 4), f(v.seconds, 2)].map((c) => el('td', {}, String(c)))));
    }
    root.append(el('section', { id: `omsk-section-${index}` }, el('h2', {}, spec.title), this.canvas, labels, controls,
      table));
  }

  async load() {
    const loader = new GLTFLoader();
    for (const v of this.spec.views) {
      const base64 = v.glb ?? assets()[v.asset];
      if (!base64) throw new Error(`omsk: no data for the view ${v.label} (asset ${v.asset} missing beside the page?)`);
      const gltf = await loader.parseAsync(bytes(base64), '');
      const scene = new THREE.Scene();
      scene.background = new THREE.Color(0xf4f4f4);
      scene.add(new THREE.HemisphereLight(0xffffff, 0x8899aa, 2.2));
      const sun = new THREE.DirectionalLight(0xffffff, 1.8);
      sun.position.set(1, 2, 3);
      scene.add(sun);
      scene.add(gltf.scene);
      const meshes = [];
      gltf.scene.traverse((o) => {
        if (!o.isMesh) return;
        o.frustumCulled = false;  // skinned bounds do not follow the pose
        const err = o.geometry.getAttribute('_error');
        // The heat map and the LOD's own COLOR_0 take turns as the 'color' attribute (applyLook).
        const own = o.geometry.getAttribute('color');
        let heatColour = null;
        if (err) {
          const c = new Float32Array(err.count * 3);
          for (let i = 0; i < err.count; ++i) c.set(colour(err.getX(i) / this.spec.error_scale), 3 * i);
          heatColour = new THREE.BufferAttribute(c, 3);
        }
        const mats = Array.isArray(o.material) ? o.material : [o.material];
        meshes.push({
          object: o, materials: mats, hasError: !!err, maps: mats.map((m) => m.map), own, heatColour,
          ownVertexColors: mats.map((m) => m.vertexColors),
        });
      });
      const mixer = new THREE.AnimationMixer(gltf.scene);
      this.views.push({ spec: v, scene, gltf, mixer, meshes, actions: new Map() });
    }
    this.setClip(this.spec.clips.length ? this.spec.clips[0].name : null);
    this.applyLook();
  }

  // Frames the views' posed bounds over the whole clip (the rest pose without one), seen from the camera's
  // current direction: a rest-pose box misses characters whose root is rotated or scaled (a Mixamo rig in
  // centimetres shows only the top of its head) and every move that leaves it. Every view shares the camera.
  frameClip() {
    const box = new THREE.Box3();
    const d = this.duration(), samples = d > 0 ? 12 : 1;
    for (let k = 0; k < samples; ++k) {
      for (const v of this.views) {
        v.mixer.setTime(d > 0 ? (d * k) / (samples - 1) : 0);
        v.gltf.scene.updateMatrixWorld(true);
        v.gltf.scene.traverse((o) => { if (o.isSkinnedMesh) o.computeBoundingBox(); });
        box.expandByObject(v.gltf.scene);
      }
    }
    for (const v of this.views) v.mixer.setTime(this.time);
    if (box.isEmpty()) return;
    const sphere = box.getBoundingSphere(new THREE.Sphere());
    const r = sphere.radius || 1;
    const vfov = THREE.MathUtils.degToRad(this.camera.fov);
    const hfov = 2 * Math.atan(Math.tan(vfov / 2) * this.camera.aspect);
    const distance = (1.05 * r) / Math.sin(Math.min(vfov, hfov) / 2);
    const dir = this.framed ? this.camera.position.clone().sub(this.controls.target).normalize()
      : new THREE.Vector3(0.35, 0.25, 1).normalize();
    this.camera.near = distance / 100;
    this.camera.far = distance * 100;
    this.camera.position.copy(sphere.center).addScaledVector(dir, distance);
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(sphere.center);
    this.controls.update();
    this.framed = true;
  }

  duration() {
    const c = this.spec.clips.find((x) => x.name === this.clip);
    return c ? c.duration : 0;
  }

  setClip(name) {
    this.clip = name;
    if (this.clipSelect.value !== name && name) this.clipSelect.value = name;
    for (const v of this.views) {
      v.mixer.stopAllAction();
      const clip = v.gltf.animations.find((a) => a.name === name);
      if (clip) v.mixer.clipAction(clip).play();
    }
    this.time = 0;
    this.frameClip();
    this.setTime(0);
  }

  setTime(t) {
    const d = this.duration();
    this.time = d > 0 ? ((t % d) + d) % d : 0;
    for (const v of this.views) v.mixer.setTime(this.time);
    if (d > 0) this.scrubber.value = String(Math.round((this.time / d) * 1000));
    this.render();
  }

  setPlaying(on) {
    this.playing = on;
    this.playButton.textContent = on ? 'pause' : 'play';
  }

  applyLook() {
    for (const v of this.views)
      for (const m of v.meshes)
        m.materials.forEach((mat, i) => {
          const heat = this.heat.checked && m.hasError;
          const geometry = m.object.geometry;
          const colours = heat ? m.heatColour : m.own;
          if (colours) geometry.setAttribute('color', colours);
          else geometry.deleteAttribute('color');
          mat.vertexColors = heat || (!!m.own && m.ownVertexColors[i]);
          mat.map = heat ? null : m.maps[i];
          mat.wireframe = this.wire.checked;
          mat.needsUpdate = true;
        });
    this.render();
  }

  // The view's rectangle in canvas pixels (origin top-left).
  rect(i) {
    return { x: i * this.cellW, y: 0, w: this.cellW, h: this.cellH };
  }

  render() {
    this.views.forEach((v, i) => {
      const r = this.rect(i);
      this.renderer.setViewport(r.x, 0, r.w, r.h);
      this.renderer.setScissor(r.x, 0, r.w, r.h);
      this.renderer.render(v.scene, this.camera);
    });
  }
}

const sections = [];
let last = performance.now();
function frame(now) {
  const dt = (now - last) / 1000;
  last = now;
  for (const s of sections) if (s.playing && s.duration() > 0) s.setTime(s.time + dt);
  requestAnimationFrame(frame);
}

async function main() {
  const data = JSON.parse(document.getElementById('omsk-data').textContent);
  const root = document.getElementById('omsk-app');
  root.append(el('h1', {}, data.title));
  data.sections.forEach((spec, i) => sections.push(new Section(spec, i, root)));
  for (const s of sections) await s.load();
  requestAnimationFrame(frame);
}

// A contact sheet: for every section, one row per view, and for each frame (by default the section's
// preview frames, held-out {clip, time}; or the given times in the current clip) two cells: the view as it
// looks (its materials and textures) and, beside it, its held-out error (blank for the original, the
// reference). A PNG data URL.
function contactSheet(times, cell = 200) {
  const timesOf = (s) =>
    times ? times.map((t) => ({ clip: s.clip, time: t })) : (s.spec.preview.length ? s.spec.preview : [{ clip: s.clip, time: 0 }]);
  const rows = sections.reduce((n, s) => n + s.views.length, 0);
  const cols = 2 * Math.max(1, ...sections.map((s) => timesOf(s).length));
  const label = 18, left = 170;
  const out = document.createElement('canvas');
  out.width = cell * cols + left;
  out.height = (cell + label) * rows;
  const g = out.getContext('2d');
  g.fillStyle = '#ffffff';
  g.fillRect(0, 0, out.width, out.height);
  g.font = '13px sans-serif';
  let row = 0;
  for (const s of sections) {
    const playing = s.playing, clip = s.clip, heat = s.heat.checked;
    s.setPlaying(false);
    timesOf(s).forEach(({ clip: c, time: t }, frame) => {
      if (c !== s.clip) s.setClip(c);
      s.setTime(t);
      [false, true].forEach((withError) => {
        s.heat.checked = withError;
        s.applyLook();
        const col = 2 * frame + (withError ? 1 : 0);
        s.views.forEach((v, i) => {
          const r = s.rect(i);
          const side = Math.min(r.w, r.h);
          const y = (row + i) * (cell + label);
          const x = left + col * cell;
          g.fillStyle = '#222';
          if (withError && !v.meshes.some((m) => m.hasError)) {
            g.fillText(i === 0 ? '(the reference)' : '(error not measured)', x + 4, y + label + cell / 2);
          } else {
            g.drawImage(s.canvas, r.x + (r.w - side) / 2, (r.h - side) / 2, side, side, x, y + label, cell, cell);
          }
          if (col === 0) {
            g.fillText(`${s.spec.title}`.slice(0, 22), 4, y + label + cell / 2 - 16);
            g.fillText(`${v.spec.label}`.slice(0, 22), 4, y + label + cell / 2);
            g.fillText(`${v.spec.triangles} triangles`, 4, y + label + cell / 2 + 16);
          }
          if (i === 0) {
            const what = withError ? 'held-out error' : `${s.clip ?? 'rest pose'} @ ${t.toFixed(2)} s`;
            g.fillText(what, x + 4, y + 13);
          }
        });
      });
    });
    row += s.views.length;
    s.heat.checked = heat;
    s.applyLook();
    if (clip !== s.clip) s.setClip(clip);
    s.setPlaying(playing);
  }
  return out.toDataURL('image/png');
}

const ready = main();
window.omsk = {
  ready,
  sections,
  setTime: (t) => sections.forEach((s) => { s.setPlaying(false); s.setTime(t); }),
  setPlaying: (on) => sections.forEach((s) => s.setPlaying(on)),
  contactSheet,
};
ready.catch((e) => {
  console.error(e);
  document.body.append(el('pre', { class: 'error' }, String(e)));
});

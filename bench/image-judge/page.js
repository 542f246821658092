// The image judge's page: loads a character and its LODs with three.js's GLTFLoader, poses each by three.js's
// own skinning and morphing at the given frames, renders them the same way (the file's PBR materials and
// textures, one light rig, one environment, one camera per frame and direction framed on the original's posed
// bounds) and compares every LOD's render with the original's (metrics.mjs). Bundled by judge.mjs.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { RoomEnvironment } from 'three/addons/environments/RoomEnvironment.js';
import { compareView, reference } from './metrics.mjs';

// Named view directions (from the character's centre towards the camera; glTF's +Y up, +Z front).
const DIRECTIONS = {
  front: [0, 0, 1], side: [1, 0, 0], back: [0, 0, -1], 'three-quarter above': [0.62, 0.55, 0.56],
};
const FOV = 30;

let renderer, stage, camera, maskMaterial, background, black;

function setup(size) {
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = size;
  document.body.append(canvas);
  renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(size, size, false);
  renderer.toneMapping = THREE.NeutralToneMapping;  // Khronos PBR Neutral: glTF's materials as authored
  stage = new THREE.Scene();
  stage.environment = new THREE.PMREMGenerator(renderer).fromScene(new RoomEnvironment(), 0.04).texture;
  stage.environmentIntensity = 0.6;
  const key = new THREE.DirectionalLight(0xffffff, 2);
  key.position.set(1, 2, 3);  // fixed in the world: the same light on every file
  stage.add(key);
  background = new THREE.Color().setRGB(0.5, 0.5, 0.5, THREE.SRGBColorSpace);
  black = new THREE.Color(0, 0, 0);
  maskMaterial = new THREE.MeshBasicMaterial({ color: 0xffffff, toneMapped: false, side: THREE.DoubleSide });
  camera = new THREE.PerspectiveCamera(FOV, 1, 0.01, 1000);
}

// A file's textures that did not load (GLTFLoader logs them and goes on without them).
async function load(url) {
  const gltf = await new GLTFLoader().loadAsync(url);
  const textures = await gltf.parser.getDependencies('texture');
  const missing = textures.filter((t) => !t || !t.image).length;
  let triangles = 0;
  gltf.scene.traverse((o) => {
    if (!o.isMesh) return;
    o.frustumCulled = false;  // skinned bounds do not follow the pose
    triangles += (o.geometry.index ? o.geometry.index.count : o.geometry.attributes.position.count) / 3;
  });
  return { gltf, mixer: new THREE.AnimationMixer(gltf.scene), textures: textures.length, missing, triangles };
}

// Clips are matched by name. Our tool names an unnamed clip clip<index>, GLTFLoader animation_<index>.
function clipOf(file, frame) {
  const anims = file.gltf.animations;
  const exact = anims.find((a) => a.name === frame.clip);
  if (exact) return exact;
  const m = /^clip(\d+)$/.exec(frame.clip);
  return m && anims[Number(m[1])]?.name === `animation_${m[1]}` ? anims[Number(m[1])] : undefined;
}

// Frees a file's GPU buffers and textures: one page judges every character in turn.
function dispose(file) {
  file.mixer.stopAllAction();
  file.gltf.scene.traverse((o) => {
    if (!o.isMesh) return;
    o.geometry.dispose();
    for (const m of Array.isArray(o.material) ? o.material : [o.material]) {
      for (const v of Object.values(m)) if (v && v.isTexture) v.dispose();
      m.dispose();
    }
  });
}

function pose(file, frame) {
  file.mixer.stopAllAction();
  if (frame) {
    const clip = clipOf(file, frame);
    if (!clip) throw new Error(`no animation named "${frame.clip}"`);
    file.mixer.clipAction(clip).play();
    file.mixer.setTime(frame.time);
  }
  file.gltf.scene.updateMatrixWorld(true);
}

// The posed vertices' bounds, skinning and morph targets applied as the shaders apply them.
function posedBox(root) {
  const box = new THREE.Box3(), v = new THREE.Vector3();
  root.traverse((o) => {
    if (!o.isMesh) return;
    for (let i = 0, n = o.geometry.attributes.position.count; i < n; ++i)
      box.expandByPoint(o.getVertexPosition(i, v).applyMatrix4(o.matrixWorld));
  });
  return box;
}

// Looks along -dir at the box's centre from as near as keeps all eight corners inside 95% of the view.
function aim(box, dir) {
  const d = new THREE.Vector3(...dir).normalize(), c = box.getCenter(new THREE.Vector3());
  camera.up.set(0, 1, 0);
  camera.position.copy(c).add(d);
  camera.lookAt(c);
  camera.updateMatrixWorld();
  const right = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
  const up = new THREE.Vector3().setFromMatrixColumn(camera.matrixWorld, 1);
  const t = 0.95 * Math.tan(THREE.MathUtils.degToRad(FOV) / 2);
  let dist = 0, reach = 0;
  for (let k = 0; k < 8; ++k) {
    const p = new THREE.Vector3(k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y, k & 4 ? box.max.z : box.min.z).sub(c);
    dist = Math.max(dist, p.dot(d) + Math.max(Math.abs(p.dot(right)), Math.abs(p.dot(up))) / t);
    reach = Math.max(reach, p.length());
  }
  dist = dist || 1;
  camera.position.copy(c).addScaledVector(d, dist);
  camera.near = Math.max(dist - 1.05 * reach, dist / 1000);
  camera.far = dist + 1.05 * reach;
  camera.updateProjectionMatrix();
}

function read(size) {
  const gl = renderer.getContext();
  const px = new Uint8Array(4 * size * size);
  gl.readPixels(0, 0, size, size, gl.RGBA, gl.UNSIGNED_BYTE, px);
  return px;
}

// The file's render (RGBA) and its coverage mask (1 where the character is) from the current camera.
function render(file, size) {
  stage.add(file.gltf.scene);
  stage.background = background;
  stage.overrideMaterial = null;
  renderer.render(stage, camera);
  const rgba = read(size);
  stage.background = black;
  stage.overrideMaterial = maskMaterial;
  renderer.render(stage, camera);
  const m = read(size), mask = new Uint8Array(size * size);
  for (let p = 0; p < mask.length; ++p) mask[p] = m[4 * p] > 127 ? 1 : 0;
  stage.overrideMaterial = null;
  stage.remove(file.gltf.scene);
  return { rgba, mask };
}

// One PNG: a row per direction, columns the renders given (each RGBA, bottom-up as GL reads them).
function sheet(rows, size) {
  const c = document.createElement('canvas');
  c.width = size * rows[0].length;
  c.height = size * rows.length;
  const g = c.getContext('2d');
  rows.forEach((row, j) => row.forEach((rgba, i) => {
    const img = g.createImageData(size, size);
    for (let y = 0; y < size; ++y) img.data.set(rgba.subarray(4 * size * (size - 1 - y), 4 * size * (size - y)), 4 * size * y);
    g.putImageData(img, i * size, j * size);
  }));
  return c.toDataURL('image/png');
}

/** job: {original, lods: [{key, url}], frames: [{clip, time}], directions: [names], size, sheets: [[keys]]}.
 *  Returns {original: {textures, missing, triangles}, lods: {key: {views, textures, missing, triangles} or
 *  {error}}, sheets: [{frame, keys, png}]} (sheets only when asked: each lists the columns after the original). */
async function run(job) {
  if (!renderer) setup(job.size);
  const original = await load(job.original).catch((e) => {
    throw new Error(`three.js could not load the original: ${String(e.message ?? e).split('\n')[0]}`);
  });
  const lods = {};
  for (const l of job.lods) {
    try {
      lods[l.key] = await load(l.url);
    } catch (e) {
      lods[l.key] = { error: `three.js could not load it: ${String(e.message ?? e).split('\n')[0]}` };
    }
  }
  const results = {};
  for (const [key, f] of Object.entries(lods))
    results[key] = f.error ? { error: f.error } : { views: [], textures: f.textures, missing: f.missing, triangles: f.triangles };
  const sheets = [];
  const frames = job.frames.length ? job.frames : [null];
  for (const [fi, frame] of frames.entries()) {
    try {
      pose(original, frame);
    } catch (e) {
      throw new Error(`the original: ${e.message}`);
    }
    for (const [key, f] of Object.entries(lods)) {
      if (f.error) continue;
      try {
        pose(f, frame);
      } catch (e) {
        results[key] = { error: String(e.message ?? e) };
        f.error = results[key].error;
      }
    }
    const box = posedBox(original.gltf.scene);
    const renders = {};
    for (const dir of job.directions) {
      aim(box, DIRECTIONS[dir]);
      const o = render(original, job.size);
      const ref = reference(o.rgba, job.size, job.size);
      renders[dir] = { original: o.rgba };
      for (const [key, f] of Object.entries(lods)) {
        if (f.error) continue;
        const r = render(f, job.size);
        renders[dir][key] = r.rgba;
        results[key].views.push(compareView(o.rgba, o.mask, r.rgba, r.mask, job.size, job.size, ref));
      }
    }
    for (const keys of job.sheets ?? []) {
      const blank = new Uint8Array(4 * job.size * job.size);
      const rows = job.directions.map((d) => [renders[d].original, ...keys.map((k) => renders[d][k] ?? blank)]);
      sheets.push({ frame: fi, keys, png: sheet(rows, job.size) });
    }
  }
  for (const f of [original, ...Object.values(lods)]) if (f.gltf) dispose(f);
  return {
    original: { textures: original.textures, missing: original.missing, triangles: original.triangles },
    lods: results,
    sheets,
  };
}

window.judge = { run, directions: Object.keys(DIRECTIONS) };

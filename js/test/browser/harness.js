// What the browser tests run inside Chromium: WebGL renders (depth-buffered ID colours,
// translucent meshes with and without ExactTransparency), SVG rasterised by the browser,
// and three.js's SVGRenderer. Images come back as base64 RGBA, row-major from the top.
import * as THREE from 'three';
import { SVGRenderer } from 'three/addons/renderers/SVGRenderer.js';
import { mergeGeometries } from 'three/addons/utils/BufferGeometryUtils.js';

import { ExactTransparency, certifyInWorker, exportSVG, gatherTriangles } from '/js/src/index.js';
import { cameraMatrices } from '/js/src/scene.js';
import { SPOT_OBJ, makeCamera, makeScene } from '/js/test/scenes.js';

THREE.ColorManagement.enabled = false;

let spotText;
async function scene(name, material) {
  if (name === 'spot' && spotText === undefined) spotText = await (await fetch(`/${SPOT_OBJ}`)).text();
  return makeScene(name, { material, objText: spotText });
}

function base64(bytes) {
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(s);
}

const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
renderer.setPixelRatio(1);

/** `scene` rendered by WebGL into an RGBA8 target, top row first. */
function webgl(root, camera, width, height, background) {
  const target = new THREE.WebGLRenderTarget(width, height, { depthBuffer: true });
  renderer.setSize(width, height);
  renderer.setRenderTarget(target);
  renderer.setClearColor(new THREE.Color(background[0] / 255, background[1] / 255, background[2] / 255), background[3] / 255);
  renderer.clear();
  renderer.render(root, camera);
  const pixels = new Uint8Array(4 * width * height);
  renderer.readRenderTargetPixels(target, 0, 0, width, height, pixels);
  renderer.setRenderTarget(null);
  target.dispose();
  const flipped = new Uint8Array(pixels.length);
  const row = 4 * width;
  for (let y = 0; y < height; y++) flipped.set(pixels.subarray((height - 1 - y) * row, (height - y) * row), y * row);
  return flipped;
}

/** The ID colour of triangle `id - 1` as three bytes. */
function idBytes(id) {
  return [(id >> 16) & 255, (id >> 8) & 255, id & 255];
}

/**
 * The test's own reading of the ID convention (not the package's): meshes in
 * traverseVisible order, an InstancedMesh's instances in order, triangles in index order;
 * each triangle one flat ID colour, drawn by WebGL with the mesh's culling.
 */
function idScene(root) {
  root.updateMatrixWorld(true);
  const out = new THREE.Scene();
  let next = 1;
  const add = (mesh, geometry, matrix) => {
    const flat = geometry.index ? geometry.toNonIndexed() : geometry.clone();
    const n = flat.getAttribute('position').count;
    const colours = new Uint8Array(3 * n);
    for (let v = 0; v < n - (n % 3); v++) colours.set(idBytes(next + Math.floor(v / 3)), 3 * v);
    next += Math.floor(n / 3);
    flat.setAttribute('color', new THREE.BufferAttribute(colours, 3, true));
    const material = new THREE.MeshBasicMaterial({ vertexColors: true, side: mesh.material.side });
    const copy = new THREE.Mesh(flat, material);
    copy.matrixAutoUpdate = false;
    copy.matrix.copy(matrix);
    out.add(copy);
  };
  root.traverseVisible((o) => {
    if (!o.isMesh) return;
    if (o.isInstancedMesh) {
      const m = new THREE.Matrix4();
      for (let i = 0; i < o.count; i++) {
        o.getMatrixAt(i, m);
        const world = o.matrixWorld.clone().multiply(m);
        // three.js culls an instance by its object's winding, not the instance's.
        add(o, world.determinant() < 0 === o.matrixWorld.determinant() < 0 ? o.geometry : flipped(o.geometry), world);
      }
    } else {
      add(o, o.geometry, o.matrixWorld);
    }
  });
  out.updateMatrixWorld(true);
  return out;
}

/** A geometry with every triangle's winding turned (so a mirrored copy culls as three.js's
 * instancing does). */
function flipped(geometry) {
  const g = geometry.index ? geometry.toNonIndexed() : geometry.clone();
  const p = g.getAttribute('position');
  for (let t = 0; t + 2 < p.count; t += 3) {
    const x = p.getX(t + 1), y = p.getY(t + 1), z = p.getZ(t + 1);
    p.setXYZ(t + 1, p.getX(t + 2), p.getY(t + 2), p.getZ(t + 2));
    p.setXYZ(t + 2, x, y, z);
  }
  return g;
}

/** `ids` with each triangle its own mesh in its ID colour: SVGRenderer paints a face in its
 * material's colour (not its vertex colours). */
function perTriangle(ids) {
  const out = new THREE.Scene();
  ids.traverse((o) => {
    if (!o.isMesh) return;
    const p = o.geometry.getAttribute('position');
    const c = o.geometry.getAttribute('color');
    for (let v = 0; v + 2 < p.count; v += 3) {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(Float32Array.from(p.array.slice(3 * v, 3 * v + 9)), 3));
      const colour = new THREE.Color(c.getX(v), c.getY(v), c.getZ(v));
      const mesh = new THREE.Mesh(g, new THREE.MeshBasicMaterial({ color: colour, side: o.material.side }));
      mesh.matrixAutoUpdate = false;
      mesh.matrix.copy(o.matrix);
      out.add(mesh);
    }
  });
  out.updateMatrixWorld(true);
  return out;
}

/** Everything the SVG check needs for one scene and camera. */
export async function svgCase({ name, kind, yaw, pitch, distance, width, height, hidden }) {
  const root = await scene(name);
  const camera = makeCamera(root, kind, yaw, pitch, distance, width, height);
  const started = performance.now();
  const svg = exportSVG(root, camera, { width, height, ids: true, hidden });
  const exportMs = performance.now() - started;
  const ids = idScene(root);
  const truth = webgl(ids, camera, width, height, [0, 0, 0, 255]);
  const svgRenderer = new SVGRenderer();
  svgRenderer.setSize(width, height);
  svgRenderer.setClearColor(0x000000, 1);
  svgRenderer.render(perTriangle(ids), camera);
  const { positions, indices } = gatherTriangles(root);
  const { view, projection } = cameraMatrices(camera);
  return {
    scene: { positions: [...positions], indices: [...indices], view: [...view], projection: [...projection], width, height, cull: 'back' },
    webgl: base64(truth),
    svg,
    svgRenderer: new XMLSerializer().serializeToString(svgRenderer.domElement),
    exportMs,
  };
}

/** One mesh of translucent crossing boxes (merged, so that one order serves them). */
function crossingMerged(material) {
  const parts = [];
  makeScene('crossing').traverse((o) => {
    if (!o.isMesh) return;
    const g = o.geometry.clone().applyMatrix4(o.matrixWorld);
    const n = g.getAttribute('position').count;
    const c = o.material.color;
    const colours = new Float32Array(3 * n);
    for (let v = 0; v < n; v++) colours.set([c.r, c.g, c.b], 3 * v);
    g.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    parts.push(g);
  });
  const scene = new THREE.Scene();
  scene.add(new THREE.Mesh(mergeGeometries(parts), material(0xffffff, true)));
  return scene;
}

/** One colour per triangle in bands along the mesh's height, so that the order of
 * overlapping layers shows (a translucent mesh of one colour hides most order errors). */
function bandedColours(mesh) {
  const g = mesh.geometry.index ? mesh.geometry.toNonIndexed() : mesh.geometry;
  const p = g.getAttribute('position');
  g.computeBoundingBox();
  const { min, max } = g.boundingBox;
  const palette = [[0.85, 0.3, 0.25], [0.25, 0.7, 0.35], [0.25, 0.4, 0.85], [0.9, 0.75, 0.2]];
  const colours = new Float32Array(3 * p.count);
  for (let v = 0; v + 2 < p.count; v += 3) {
    const y = (p.getY(v) + p.getY(v + 1) + p.getY(v + 2)) / 3;
    const band = Math.min(3, Math.floor((4 * (y - min.y)) / (max.y - min.y)));
    for (let k = 0; k < 3; k++) colours.set(palette[band], 3 * (v + k));
  }
  g.setAttribute('color', new THREE.BufferAttribute(colours, 3));
  mesh.geometry = g;
}

const built = new Map();

/** A translucent scene, with ExactTransparency (`exact`) or as three.js draws it. */
async function translucent(name, exact) {
  const material = (hex, vertexColors = false) => new THREE.MeshBasicMaterial({ color: hex, transparent: true, opacity: 0.55, vertexColors });
  const root = name === 'crossing' ? crossingMerged(material) : await scene(name, (hex) => material(hex, true));
  const meshes = [];
  root.traverse((o) => o.isMesh && meshes.push(o));
  if (name !== 'crossing') meshes.forEach(bandedColours);
  const buildMs = [];
  if (exact) {
    for (const [k, mesh] of meshes.entries()) {
      const started = performance.now();
      const key = `${name}/${k}`;
      // spot's certificate comes from a worker (as bytes), the others' from this thread.
      const bytes = built.get(key) ?? (name === 'spot' ? await certifyInWorker(mesh) : undefined);
      const exactMesh = new ExactTransparency(mesh, bytes ? { bytes } : {});
      if (!built.has(key)) built.set(key, exactMesh.toBytes());
      buildMs.push(performance.now() - started);
      mesh.userData.exact = exactMesh;
    }
  }
  return { root, meshes, buildMs };
}

/** The transparency check's images for a list of views of one scene. */
export async function transparencyCase({ name, kind, views, width, height }) {
  const background = [255, 255, 255, 255];
  const plain = await translucent(name, false);
  const exact = await translucent(name, true);
  const out = [];
  for (const { yaw, pitch, distance } of views) {
    const camera = makeCamera(plain.root, kind, yaw, pitch, distance, width, height);
    const { positions, indices, colours } = gatherTriangles(plain.root);
    const { view, projection } = cameraMatrices(camera);
    const exactImage = webgl(exact.root, camera, width, height, background);
    const meshes = exact.meshes.map((m) => m.userData.exact);
    out.push({
      scene: { positions: [...positions], indices: [...indices], colours: [...colours], view: [...view], projection: [...projection], width, height, cull: 'back', background },
      exact: base64(exactImage),
      three: base64(webgl(plain.root, camera, width, height, background)),
      fellBack: meshes.some((m) => m.fellBack),
      fallbackFrames: meshes.reduce((s, m) => s + m.fallbackFrames, 0),
      frames: meshes.reduce((s, m) => s + m.frames, 0),
    });
  }
  return { views: out, buildMs: exact.buildMs };
}

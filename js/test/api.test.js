// The package's API in Node: arguments, errors, IDs, fallbacks and certificates. Pictures
// are checked in browser.test.js.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import * as THREE from 'three';

import { ExactTransparency, certify, exportSVG, gatherTriangles, plotEdges } from '../src/index.js';
import { makeCamera, makeScene } from './scenes.js';

const SIZE = { width: 200, height: 150 };

function cameraFor(scene, kind = 'perspective') {
  return makeCamera(scene, kind, 30, 20, 3, SIZE.width, SIZE.height);
}

test('exportSVG writes an SVG of the image size, and its ID mode uses triangle IDs only', () => {
  const scene = makeScene('crossing');
  const svg = exportSVG(scene, cameraFor(scene), SIZE);
  assert.match(svg, /^<svg[^>]* width="200" height="150"/);
  const ids = exportSVG(scene, cameraFor(scene, 'orthographic'), { ...SIZE, ids: true });
  const triangles = gatherTriangles(scene).indices.length / 3;
  const used = [...ids.matchAll(/fill="#([0-9a-f]{6})"/g)].map((m) => parseInt(m[1], 16));
  assert.ok(used.length > 0, 'the ID SVG paints faces');
  for (const id of used) assert.ok(id >= 1 && id <= triangles, `ID ${id} is not a triangle of ${triangles}`);
});

test('triangles are numbered in traverse order, instances in order, winding kept', () => {
  const scene = new THREE.Scene();
  const box = new THREE.Mesh(new THREE.BoxGeometry(), new THREE.MeshBasicMaterial());
  const copies = new THREE.InstancedMesh(new THREE.BoxGeometry(), new THREE.MeshBasicMaterial(), 3);
  for (let i = 0; i < 3; i++) copies.setMatrixAt(i, new THREE.Matrix4().makeTranslation(2 * i + 2, 0, 0));
  const hidden = new THREE.Mesh(new THREE.BoxGeometry(), new THREE.MeshBasicMaterial());
  hidden.visible = false;
  scene.add(box, copies, hidden);
  const { positions, indices } = gatherTriangles(scene);
  assert.equal(indices.length / 3, 12 + 3 * 12, 'the invisible mesh counts no triangle');
  // Triangle 12 + 12k is instance k's first triangle, moved by its matrix.
  for (let k = 0; k < 3; k++) {
    const v = indices[3 * (12 + 12 * k)];
    const first = box.geometry.index.getX(0);
    assert.equal(positions[3 * v], box.geometry.getAttribute('position').getX(first) + 2 * k + 2);
  }
});

test('bad input is a thrown Error that names it', () => {
  const scene = makeScene('crossing');
  const camera = cameraFor(scene);
  assert.throws(() => exportSVG(scene, camera, { width: 0, height: 10 }), /width and height/);
  assert.throws(() => exportSVG(scene, {}, SIZE), /camera: not a three.js Camera/);
  assert.throws(() => exportSVG(scene, camera, { width: 200, height: 100 }), /aspect ratio/);
  assert.throws(() => exportSVG(new THREE.Scene(), camera, SIZE), /no visible mesh/);
  const broken = new THREE.BufferGeometry();
  broken.setAttribute('position', new THREE.Float32BufferAttribute([0, 0, 0, 1, NaN, 0, 0, 1, 0], 3));
  const bad = new THREE.Scene().add(new THREE.Mesh(broken, new THREE.MeshBasicMaterial()));
  assert.throws(() => exportSVG(bad, camera, SIZE), /vertex 1 has a NaN/);
  const mixed = makeScene('crossing');
  mixed.children[0].children[0].material.side = THREE.DoubleSide;
  assert.throws(() => exportSVG(mixed, camera, SIZE), /mix sides/);
  assert.throws(() => plotEdges(scene, camera, { ...SIZE, crease: 200 }), /crease/);
});

test('translucent faces keep what lies behind them, and removal is refused for them', () => {
  const scene = makeScene('crossing', { material: (hex) => new THREE.MeshBasicMaterial({ color: hex, transparent: true, opacity: 0.5 }) });
  const camera = cameraFor(scene);
  assert.match(exportSVG(scene, camera, SIZE), /fill-opacity/);
  assert.throws(() => exportSVG(scene, camera, { ...SIZE, hidden: 'remove' }), /translucent: use "keep"/);
});

test('plotEdges draws strokes', () => {
  const scene = makeScene('interlocking');
  const svg = plotEdges(scene, cameraFor(scene), { ...SIZE, crease: 40, stroke: 0.5 });
  assert.match(svg, /stroke-width="0.5"/);
  assert.ok((svg.match(/<path /g) ?? []).length > 10);
});

/** Per source triangle, the area of the front-facing triangles a frame draws for the viewer
 * at `p` (w = 1) or in direction `p` (w = 0): a cycle's fragments tile its pieces, so the
 * areas say whether every front-facing part is drawn once. */
function frontArea(exact, viewer) {
  const c = exact.certificate;
  const index = exact.geometry.index.array;
  const from = c.vertexTriangles;
  const p = exact.geometry.getAttribute('position');
  const v = (i) => new THREE.Vector3().fromBufferAttribute(p, i);
  const area = new Map();
  for (let k = c.start; k < c.start + c.count; k += 3) {
    const [a, b, d] = [index[k], index[k + 1], index[k + 2]].map(v);
    const n = b.clone().sub(a).cross(d.clone().sub(a));
    const toward = viewer.w === 0 ? viewer.p : viewer.p.clone().sub(a);
    if (n.dot(toward) > 1e-6 * n.length() * toward.length()) {
      const face = from[index[k]];
      area.set(face, (area.get(face) ?? 0) + n.length() / 2);
    }
  }
  return area;
}

test('ExactTransparency draws every front-facing piece once, and says when it falls back', () => {
  const mesh = new THREE.Mesh(new THREE.TorusKnotGeometry(1, 0.3, 48, 6), new THREE.MeshBasicMaterial({ transparent: true, opacity: 0.5 }));
  const exact = new ExactTransparency(mesh);
  assert.ok(exact.orders > 1, 'a knot needs more than one order');
  const c = exact.certificate;
  // Every piece once: the fallback's list (by centroid) holds each piece of the cut mesh.
  c.frame(0, 0, 0.1, 1);
  assert.equal(c.fellBack, true);
  assert.match(c.fallbackReason, /nearer than min_eye_distance/);
  assert.equal(exact.fallbackFrames, 1);
  for (let k = 0; k < 20; k++) {
    const direction = new THREE.Vector3(Math.sin(k), Math.cos(3 * k), Math.sin(7 * k + 1)).normalize();
    for (const viewer of [{ p: direction, w: 0 }, { p: direction.clone().multiplyScalar(6), w: 1 }]) {
      c.frame(viewer.p.x, viewer.p.y, viewer.p.z, viewer.w);
      assert.equal(c.fellBack, false);
      if (c.rewritten) exact.geometry.index.array.set(c.scratch(), c.scratchStart);
      const drawn = frontArea(exact, viewer);
      c.frame(0, 0, 0.1, 1);
      exact.geometry.index.array.set(c.scratch(), c.scratchStart);
      const all = frontArea(exact, viewer);
      assert.deepEqual([...drawn.keys()].sort(), [...all.keys()].sort(), 'every front-facing triangle drawn');
      for (const [face, area] of all) assert.ok(Math.abs(drawn.get(face) - area) <= 1e-5 * area, `triangle ${face}: area ${drawn.get(face)} drawn of ${area}`);
    }
  }
  assert.equal(exact.fallbackFrames, 41);
  exact.dispose();
  assert.ok(mesh.geometry.isBufferGeometry && mesh.geometry.index.count === new THREE.TorusKnotGeometry(1, 0.3, 48, 6).index.count);
});

test('a certificate round-trips through bytes, and hostile bytes are an Error', () => {
  const mesh = new THREE.Mesh(new THREE.TorusKnotGeometry(1, 0.3, 32, 5), new THREE.MeshBasicMaterial({ transparent: true }));
  const built = certify(mesh).certificate;
  const bytes = built.toBytes();
  const loaded = certify(mesh, { bytes }).certificate;
  for (let k = 0; k < 10; k++) {
    const d = [Math.sin(k), Math.cos(2 * k), 0.3 * k - 1];
    built.frame(...d, 0);
    loaded.frame(...d, 0);
    assert.deepEqual([loaded.start, loaded.count], [built.start, built.count]);
    assert.deepEqual(loaded.scratch(), built.scratch());
  }
  const hostile = bytes.slice();
  hostile[hostile.length >> 1] ^= 0xff;
  assert.throws(() => certify(mesh, { bytes: hostile.subarray(0, 40) }), /bytes/);
  assert.throws(() => certify(mesh, { bytes: new Uint8Array([1, 2, 3]) }), /bytes/);
  const other = new THREE.Mesh(new THREE.BoxGeometry(), mesh.material);
  assert.throws(() => certify(other, { bytes }), /bytes/);
});

test('ExactTransparency refuses what it cannot order', () => {
  const material = new THREE.MeshBasicMaterial({ transparent: true, side: THREE.DoubleSide });
  assert.throws(() => new ExactTransparency(new THREE.Mesh(new THREE.BoxGeometry(), material)), /FrontSide/);
  const instanced = new THREE.InstancedMesh(new THREE.BoxGeometry(), new THREE.MeshBasicMaterial(), 2);
  assert.throws(() => new ExactTransparency(instanced), /static Mesh/);
  const mesh = new THREE.Mesh(new THREE.BoxGeometry(), new THREE.MeshBasicMaterial());
  assert.throws(() => certify(mesh, { maxBuildMs: -1 }), /maxBuildMs/);
});

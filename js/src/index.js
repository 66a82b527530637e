// facesort-three: exact painter's order for three.js scenes (module docs in README.md).
import { BufferAttribute, BufferGeometry, DynamicDrawUsage, FrontSide, Matrix4, Vector3 } from 'three';

import { bindings, memory } from './wasm.js';
import { cameraMatrices, gatherTriangles, triangleIndices } from './scene.js';

export { gatherTriangles } from './scene.js';

function size(options) {
  const { width, height } = options;
  if (!Number.isInteger(width) || !Number.isInteger(height) || width <= 0 || height <= 0) {
    throw new Error(`options: width and height must be positive integers, got ${width} x ${height}`);
  }
  return { width, height };
}

/**
 * The exact SVG of `scene` seen by `camera`: faces split where they pass through each
 * other, drawn far to near in an exact order, hidden parts removed.
 *
 * @param {import('three').Object3D} scene
 * @param {import('three').Camera} camera
 * @param {{width: number, height: number, hidden?: 'remove' | 'keep', ids?: boolean}} options
 * @returns {string}
 */
export function exportSVG(scene, camera, options) {
  const { width, height } = size(options);
  const { positions, indices, colours, cull } = gatherTriangles(scene);
  const { view, projection } = cameraMatrices(camera);
  const ids = options.ids === true;
  let hidden = options.hidden;
  if (hidden === undefined) {
    // Removal treats faces as opaque: keep what lies behind translucent faces.
    hidden = ids || colours.every((c, k) => k % 4 !== 3 || c === 255) ? 'remove' : 'keep';
  }
  return bindings.exportSvg(positions, indices, colours, view, projection, width, height, cull, hidden, ids);
}

/**
 * The visible edges of `scene` seen by `camera` as SVG strokes, for pen plotters:
 * outlines, creases (faces at least `crease` degrees apart, default 30) and the lines
 * where faces pass through each other, each clipped to what can be seen.
 *
 * @param {import('three').Object3D} scene
 * @param {import('three').Camera} camera
 * @param {{width: number, height: number, crease?: number, stroke?: number}} options
 * @returns {string}
 */
export function plotEdges(scene, camera, options) {
  const { width, height } = size(options);
  const { positions, indices, cull } = gatherTriangles(scene);
  const { view, projection } = cameraMatrices(camera);
  return bindings.plotEdges(positions, indices, view, projection, width, height, cull, options.crease ?? 30, options.stroke ?? 1);
}

/** A mesh's own triangles (model space), for certifying. */
function meshTriangles(mesh) {
  if (!mesh || !mesh.isMesh || mesh.isInstancedMesh || mesh.isSkinnedMesh) {
    throw new Error('ExactTransparency: needs a static Mesh (not instanced, not skinned)');
  }
  if (Array.isArray(mesh.material)) throw new Error('ExactTransparency: needs one material, not an array');
  if (mesh.material.side !== FrontSide) {
    throw new Error('ExactTransparency: the material must have side = FrontSide (the order leaves back faces to the GPU\'s culling)');
  }
  const geometry = mesh.geometry;
  const indices = triangleIndices(geometry, 'ExactTransparency');
  const position = geometry.getAttribute('position');
  const positions = new Float64Array(3 * position.count);
  for (let v = 0; v < position.count; v++) {
    positions[3 * v] = position.getX(v);
    positions[3 * v + 1] = position.getY(v);
    positions[3 * v + 2] = position.getZ(v);
  }
  return { positions, indices };
}

/**
 * Certifies a mesh's triangles: plain data for any engine. `positions` (x, y, z per
 * vertex) and `indices` draw every certified order; `orders` holds per order
 * `[start, count, cycles]`; `certificate.frame(x, y, z, w)` finds the viewer's order.
 *
 * @param {import('three').Mesh} mesh
 * @param {{minEyeDistance?: number, maxBuildMs?: number, bytes?: Uint8Array}} [options]
 */
export function certify(mesh, options = {}) {
  const { positions, indices } = meshTriangles(mesh);
  const certificate = options.bytes
    ? bindings.Certificate.fromBytes(positions, indices, options.bytes)
    : new bindings.Certificate(positions, indices, options.minEyeDistance ?? 1.5, options.maxBuildMs ?? 120000);
  return { certificate, source: { positions, indices } };
}

/** Weights of `p` in triangle `a, b, c` (its projection onto the triangle's plane). */
function barycentric(p, a, b, c, out) {
  const v0 = b.clone().sub(a);
  const v1 = c.clone().sub(a);
  const v2 = p.clone().sub(a);
  const d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
  const den = d00 * d11 - d01 * d01;
  const v = den === 0 ? 0 : (d11 * d20 - d01 * d21) / den;
  const w = den === 0 ? 0 : (d00 * d21 - d01 * d20) / den;
  out[0] = 1 - v - w;
  out[1] = v;
  out[2] = w;
  return out;
}

/** The certified geometry: pieces' corners, each attribute of the source (normals,
 * colours, uvs) carried over by its triangle's weights; the orders as one index buffer. */
function certifiedGeometry(source, certificate, original) {
  const positions = certificate.positions;
  const from = certificate.vertexTriangles;
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(positions, 3));
  const corner = [new Vector3(), new Vector3(), new Vector3()];
  const p = new Vector3();
  const weights = [0, 0, 0];
  const carried = Object.keys(original.attributes).filter((name) => name !== 'position');
  const out = Object.fromEntries(carried.map((name) => [name, new Float32Array(from.length * original.attributes[name].itemSize)]));
  for (let v = 0; v < from.length; v++) {
    const t = from[v];
    const tri = [source.indices[3 * t], source.indices[3 * t + 1], source.indices[3 * t + 2]];
    tri.forEach((i, k) => corner[k].fromArray(source.positions, 3 * i));
    barycentric(p.fromArray(positions, 3 * v), corner[0], corner[1], corner[2], weights);
    for (const name of carried) {
      const a = original.attributes[name];
      for (let c = 0; c < a.itemSize; c++) {
        let sum = 0;
        for (let k = 0; k < 3; k++) sum += weights[k] * a.getComponent(tri[k], c);
        out[name][v * a.itemSize + c] = sum;
      }
    }
  }
  for (const name of carried) {
    geometry.setAttribute(name, new BufferAttribute(out[name], original.attributes[name].itemSize));
  }
  const index = new BufferAttribute(certificate.indices, 1);
  index.setUsage(DynamicDrawUsage);
  geometry.setIndex(index);
  geometry.computeBoundingBox();
  geometry.computeBoundingSphere();
  return geometry;
}

/**
 * Exact transparency for a static mesh: its certificate is built once (here, or in a
 * worker: pass `bytes` from `certifyInWorker`), its orders uploaded as one index buffer,
 * and before each render the viewer's region picks its range (`onBeforeRender`). Small
 * cycles are ordered per frame; views the certificate does not cover (an eye nearer than
 * `minEyeDistance` bounding radii) are drawn by centroid and counted in
 * `fallbackFrames`, with `fellBack` set for the last frame.
 */
export class ExactTransparency {
  /**
   * @param {import('three').Mesh} mesh
   * @param {{minEyeDistance?: number, maxBuildMs?: number, bytes?: Uint8Array}} [options]
   */
  constructor(mesh, options = {}) {
    const { certificate, source } = certify(mesh, options);
    this.mesh = mesh;
    this.certificate = certificate;
    this.originalGeometry = mesh.geometry;
    this.geometry = certifiedGeometry(source, certificate, mesh.geometry);
    this.scratchStart = certificate.scratchStart;
    this.fellBack = false;
    const toLocal = new Matrix4();
    const viewer = new Vector3();
    const index = this.geometry.index;
    mesh.geometry = this.geometry;
    this.previousOnBeforeRender = mesh.onBeforeRender;
    mesh.onBeforeRender = (renderer, scene, camera, geometry) => {
      toLocal.copy(mesh.matrixWorld).invert();
      if (camera.isOrthographicCamera) {
        // Toward the viewer: the camera's +Z, as a direction of the mesh's space.
        viewer.setFromMatrixColumn(camera.matrixWorld, 2).transformDirection(toLocal);
        certificate.frame(viewer.x, viewer.y, viewer.z, 0);
      } else {
        viewer.setFromMatrixPosition(camera.matrixWorld).applyMatrix4(toLocal);
        certificate.frame(viewer.x, viewer.y, viewer.z, 1);
      }
      const count = certificate.count;
      if (certificate.rewritten) {
        // Straight from the module's memory: no copy of the order on the way.
        index.array.set(new Uint32Array(memory.buffer, certificate.scratchPointer, count), this.scratchStart);
        index.clearUpdateRanges();
        index.addUpdateRange(this.scratchStart, count);
        index.needsUpdate = true;
      }
      this.fellBack = certificate.fellBack;
      geometry.setDrawRange(certificate.start, count);
    };
  }

  /** Frames drawn so far. */
  get frames() {
    return this.certificate.frames;
  }

  /** Frames outside the certificate so far (drawn by centroid, not exact). */
  get fallbackFrames() {
    return this.certificate.fallbackFrames;
  }

  /** Certified orders. */
  get orders() {
    return this.certificate.orderCount;
  }

  /** The certificate as bytes, to keep or to hand between threads. */
  toBytes() {
    return this.certificate.toBytes();
  }

  /** Puts the mesh's own geometry and `onBeforeRender` back and frees the certificate. */
  dispose() {
    this.mesh.geometry = this.originalGeometry;
    this.mesh.onBeforeRender = this.previousOnBeforeRender;
    this.geometry.dispose();
    this.certificate.free();
  }
}

/**
 * Certifies `mesh` in a module worker, off the page's thread; resolves to the bytes that
 * `new ExactTransparency(mesh, { bytes })` loads.
 *
 * @param {import('three').Mesh} mesh
 * @param {{minEyeDistance?: number, maxBuildMs?: number}} [options]
 * @returns {Promise<Uint8Array>}
 */
export function certifyInWorker(mesh, options = {}) {
  const { positions, indices } = meshTriangles(mesh);
  const worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
  return new Promise((resolve, reject) => {
    worker.onmessage = ({ data }) => {
      worker.terminate();
      if (data.error) reject(new Error(data.error));
      else resolve(data.bytes);
    };
    worker.onerror = (e) => {
      worker.terminate();
      reject(new Error(`certifyInWorker: ${e.message}`));
    };
    worker.postMessage({ positions, indices, minEyeDistance: options.minEyeDistance ?? 1.5, maxBuildMs: options.maxBuildMs ?? 120000 }, [positions.buffer, indices.buffer]);
  });
}

// The adapter from three.js objects to the arrays the WebAssembly module takes: triangles
// in world space, one colour per triangle, the camera's matrices, and which faces are drawn.
import { BackSide, Color, DoubleSide, FrontSide, Matrix4, SRGBColorSpace, Vector3 } from 'three';

const CULL = new Map([
  [FrontSide, 'back'],
  [BackSide, 'front'],
  [DoubleSide, 'none'],
]);

/** Which faces a material draws, as the module names it. */
export function cullOf(material, where) {
  const cull = CULL.get(material.side);
  if (cull === undefined) throw new Error(`${where}: material.side ${material.side} is not FrontSide, BackSide or DoubleSide`);
  return cull;
}

/** Vertex indices of a geometry's triangles: its index, or 0, 1, 2, ... */
export function triangleIndices(geometry, where) {
  const position = geometry.getAttribute('position');
  if (!position) throw new Error(`${where}: the geometry has no position attribute`);
  if (geometry.index) {
    const index = geometry.index;
    const out = new Uint32Array(index.count - (index.count % 3));
    for (let k = 0; k < out.length; k++) out[k] = index.getX(k);
    return out;
  }
  const n = position.count - (position.count % 3);
  const out = new Uint32Array(n);
  for (let k = 0; k < n; k++) out[k] = k;
  return out;
}

/** The material of each triangle (a material array follows the geometry's groups). */
function materialOf(mesh, triangles, where) {
  const m = mesh.material;
  if (!Array.isArray(m)) return () => m;
  const groups = mesh.geometry.groups;
  if (groups.length === 0) throw new Error(`${where}: a material array needs geometry groups`);
  const per = new Int32Array(triangles).fill(-1);
  for (const g of groups) {
    const first = Math.floor(g.start / 3);
    const last = Math.min(triangles, Math.floor((g.start + g.count) / 3));
    for (let t = first; t < last; t++) per[t] = g.materialIndex;
  }
  return (t) => (per[t] >= 0 ? m[per[t]] : undefined);
}

const scratch = { colour: new Color(), vertex: new Color(), srgb: { r: 0, g: 0, b: 0 } };

/** sRGB RGBA bytes of triangle `t`: the material's colour, times the mean of its vertex
 * colours when the material uses them, times the instance colour; alpha is the material's
 * opacity when it is transparent. */
function colourOf(material, geometry, tri, instanceColour, out, at) {
  const c = scratch.colour;
  if (material.color) c.copy(material.color);
  else c.setRGB(1, 1, 1);
  const colours = geometry.getAttribute('color');
  if (material.vertexColors && colours) {
    const v = scratch.vertex.setRGB(0, 0, 0);
    for (const i of tri) {
      v.r += colours.getX(i) / 3;
      v.g += colours.getY(i) / 3;
      v.b += colours.getZ(i) / 3;
    }
    c.multiply(v);
  }
  if (instanceColour) c.multiply(instanceColour);
  c.getRGB(scratch.srgb, SRGBColorSpace);
  const byte = (x) => Math.max(0, Math.min(255, Math.round(x * 255)));
  out[at] = byte(scratch.srgb.r);
  out[at + 1] = byte(scratch.srgb.g);
  out[at + 2] = byte(scratch.srgb.b);
  out[at + 3] = material.transparent ? byte(material.opacity) : 255;
}

/**
 * Every visible mesh under `root` in `traverse` order as world-space triangles: an
 * `InstancedMesh` gives its instances in order, each all of the mesh's triangles; a
 * mesh's triangles follow its index buffer, or its positions when it has none. Triangle
 * `i` of the result has ID colour `i + 1`.
 */
export function gatherTriangles(root) {
  root.updateMatrixWorld(true);
  const positions = [];
  const indices = [];
  const colours = [];
  const culls = new Set();
  const world = new Matrix4();
  const instance = new Matrix4();
  const p = new Vector3();
  const instanceColour = new Color();
  root.traverseVisible((object) => {
    if (!object.isMesh) return;
    const where = `mesh ${JSON.stringify(object.name || object.uuid)}`;
    const geometry = object.geometry;
    const tris = triangleIndices(geometry, where);
    const material = materialOf(object, tris.length / 3, where);
    const position = geometry.getAttribute('position');
    const copies = object.isInstancedMesh ? object.count : 1;
    for (let copy = 0; copy < copies; copy++) {
      world.copy(object.matrixWorld);
      if (object.isInstancedMesh) world.multiply(object.getMatrixAt(copy, instance));
      // three.js turns the front face for a mirroring object (not for a mirroring instance
      // matrix: such an instance shows its back faces there too).
      const mirrored = object.matrixWorld.determinant() < 0;
      const first = positions.length / 3;
      for (let v = 0; v < position.count; v++) {
        p.fromBufferAttribute(position, v).applyMatrix4(world);
        positions.push(p.x, p.y, p.z);
      }
      const tint = object.isInstancedMesh && object.instanceColor ? object.getColorAt(copy, instanceColour) : null;
      for (let t = 0; t < tris.length / 3; t++) {
        const m = material(t);
        const tri = [tris[3 * t], tris[3 * t + 1], tris[3 * t + 2]];
        // A mirroring placement turns the winding; three.js flips its front face for it.
        if (mirrored) indices.push(first + tri[0], first + tri[2], first + tri[1]);
        else indices.push(first + tri[0], first + tri[1], first + tri[2]);
        const at = colours.length;
        colours.push(0, 0, 0, 0);
        if (m === undefined) {
          // A triangle outside every group: three.js does not draw it; kept for the IDs
          // and painted fully transparent.
          continue;
        }
        culls.add(cullOf(m, where));
        colourOf(m, geometry, tri, tint, colours, at);
      }
    }
  });
  if (indices.length === 0) throw new Error('scene: no visible mesh with a triangle');
  if (culls.size > 1) {
    throw new Error(`scene: materials mix sides (${[...culls].join(', ')}); one export culls one way`);
  }
  return {
    positions: Float64Array.from(positions),
    indices: Uint32Array.from(indices),
    colours: Uint8Array.from(colours),
    cull: culls.values().next().value ?? 'back',
  };
}

/** The camera's view and projection matrices, column-major, after updating them. */
export function cameraMatrices(camera) {
  if (!camera || !camera.isCamera) throw new Error('camera: not a three.js Camera');
  camera.updateMatrixWorld(true);
  return {
    view: Float64Array.from(camera.matrixWorldInverse.elements),
    projection: Float64Array.from(camera.projectionMatrix.elements),
  };
}

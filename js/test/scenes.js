// Test scenes and cameras shared by the Node and browser tests.
import * as THREE from 'three';
import { OBJLoader } from 'three/addons/loaders/OBJLoader.js';

export const SPOT_OBJ = 'assets/models/keenan-crane/spot/spot_triangulated.obj';

/** Two boxes passing through each other and a long thin slab through both. */
function crossing(material) {
  const group = new THREE.Group();
  const a = new THREE.Mesh(new THREE.BoxGeometry(2.4, 0.5, 0.5), material(0xd04040));
  const b = new THREE.Mesh(new THREE.BoxGeometry(0.5, 2.4, 0.5), material(0x40a040));
  b.rotation.set(0.35, 0.2, 0.1);
  const c = new THREE.Mesh(new THREE.BoxGeometry(3.0, 0.08, 1.6), material(0x4060d0));
  c.rotation.set(0.25, -0.3, 0.5);
  group.add(a, b, c);
  return group;
}

/** Two linked rings. */
function interlocking(material) {
  const group = new THREE.Group();
  const a = new THREE.Mesh(new THREE.TorusGeometry(1, 0.25, 10, 28), material(0xc08020));
  const b = new THREE.Mesh(new THREE.TorusGeometry(1, 0.25, 10, 28), material(0x2080c0));
  b.position.x = 1;
  b.rotation.x = Math.PI / 2;
  group.add(a, b);
  return group;
}

/** An InstancedMesh of a box, its instances turned, scaled and overlapping; one mirrored. */
function instanced(material) {
  const group = new THREE.Group();
  const mesh = new THREE.InstancedMesh(new THREE.BoxGeometry(1, 0.3, 0.6), material(0x8060c0), 5);
  const m = new THREE.Matrix4();
  const q = new THREE.Quaternion();
  for (let i = 0; i < 5; i++) {
    q.setFromEuler(new THREE.Euler(0.3 * i, 0.7 * i, 0.2 * i));
    const s = i === 3 ? new THREE.Vector3(-1, 1.2, 1) : new THREE.Vector3(1 + 0.1 * i, 1, 1);
    m.compose(new THREE.Vector3(0.35 * i - 0.7, 0.15 * i - 0.3, 0.1 * i), q, s);
    mesh.setMatrixAt(i, m);
  }
  mesh.position.set(0.1, 0, 0);
  mesh.rotation.z = 0.2;
  group.add(mesh);
  return group;
}

/** Keenan Crane's spot (CC0), from its OBJ text. */
function spot(material, objText) {
  const group = new THREE.Group();
  const loaded = new OBJLoader().parse(objText);
  loaded.traverse((o) => {
    if (o.isMesh) group.add(new THREE.Mesh(o.geometry, material(0xe0a060)));
  });
  return group;
}

export const SCENES = { crossing, interlocking, instanced, spot };

/**
 * The scene `name`, each mesh in `material(hex)` (default: opaque MeshLambertMaterial).
 * @param {string} name
 * @param {{material?: (hex: number) => THREE.Material, objText?: string}} [options]
 */
export function makeScene(name, options = {}) {
  const material = options.material ?? ((hex) => new THREE.MeshLambertMaterial({ color: hex }));
  const scene = new THREE.Scene();
  scene.add(SCENES[name](material, options.objText));
  scene.updateMatrixWorld(true);
  return scene;
}

/** The bounding sphere of everything under `root`. */
export function sphereOf(root) {
  return new THREE.Box3().setFromObject(root).getBoundingSphere(new THREE.Sphere());
}

/**
 * A camera looking at `root`'s centre from the direction (yaw, pitch) in degrees, at
 * `distance` bounding radii: perspective (45° field of view) or orthographic (framing the
 * sphere), for a `width` × `height` image.
 */
export function makeCamera(root, kind, yaw, pitch, distance, width, height) {
  const sphere = sphereOf(root);
  const r = sphere.radius;
  const aspect = width / height;
  const camera = kind === 'orthographic'
    ? new THREE.OrthographicCamera(-1.1 * r * aspect, 1.1 * r * aspect, 1.1 * r, -1.1 * r, 0.1 * r, (distance + 2) * r)
    : new THREE.PerspectiveCamera(45, aspect, (distance - 1.05) * r, (distance + 1.05) * r);
  const y = THREE.MathUtils.degToRad(yaw);
  const p = THREE.MathUtils.degToRad(pitch);
  const dir = new THREE.Vector3(Math.sin(y) * Math.cos(p), Math.sin(p), Math.cos(y) * Math.cos(p));
  camera.position.copy(sphere.center).addScaledVector(dir, distance * r);
  camera.lookAt(sphere.center);
  camera.updateMatrixWorld(true);
  camera.updateProjectionMatrix();
  return camera;
}

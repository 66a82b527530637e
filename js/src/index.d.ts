// Types of facesort-three (src/index.js).
import type { BufferGeometry, Camera, Mesh, Object3D } from 'three';

/** The WebAssembly certificate of a mesh (see `certify`). */
export interface Certificate {
  /** Vertex positions (x, y, z per vertex, model space): every piece's corners. */
  readonly positions: Float32Array;
  /** Per vertex, the input triangle its piece comes from. */
  readonly vertexTriangles: Uint32Array;
  /** Every certified order without cycles, then the scratch tail. */
  readonly indices: Uint32Array;
  /** Per certified order `[start, count, cycles]`; `cycles` 1: ordered per frame. */
  readonly orders: Uint32Array;
  /** Where the scratch tail of `indices` begins. */
  readonly scratchStart: number;
  /** Certified orders. */
  readonly orderCount: number;
  /** Finds the order for a viewer at `(x, y, z, w)` in model space: `w = 1` an eye, `w = 0` a direction toward the viewer. */
  frame(x: number, y: number, z: number, w: number): void;
  /** The last frame's first index and index count. */
  readonly start: number;
  readonly count: number;
  /** Whether the last frame rewrote the scratch tail (upload `scratch()` at `scratchStart`). */
  readonly rewritten: boolean;
  /** The scratch tail's indices of the last frame, copied. */
  scratch(): Uint32Array;
  /** Byte offset of those indices in the module's memory (valid until the next call into it). */
  readonly scratchPointer: number;
  /** Whether the last frame was outside the certificate (drawn far to near by centroid, not exact), and why. */
  readonly fellBack: boolean;
  readonly fallbackReason: string | undefined;
  /** Frames so far, and those outside the certificate. */
  readonly frames: number;
  readonly fallbackFrames: number;
  /** The certificate as bytes (versioned; validated when loaded). */
  toBytes(): Uint8Array;
  /** Frees the WebAssembly memory. */
  free(): void;
}

export interface Size {
  /** Image width in pixels (the camera's aspect ratio must match). */
  width: number;
  /** Image height in pixels. */
  height: number;
}

export interface SvgOptions extends Size {
  /** Parts nobody can see: removed (default when every face is opaque) or kept (default otherwise; removal is refused for translucent faces). */
  hidden?: 'remove' | 'keep';
  /** Paint every triangle in its ID colour (triangle index + 1 as 24-bit RGB), no background, for checking. */
  ids?: boolean;
}

export interface PlotOptions extends Size {
  /** Edges between faces at least this many degrees apart are drawn (default 30). */
  crease?: number;
  /** Stroke width in pixels (default 1). */
  stroke?: number;
}

export interface CertifyOptions {
  /** Eyes at least this many bounding radii from the mesh's centre are certified (default 1.5; above 1). */
  minEyeDistance?: number;
  /** Build budget in milliseconds (default 120000): beyond it the build stops with an Error. */
  maxBuildMs?: number;
  /** A certificate from `toBytes` or `certifyInWorker` for the same mesh, loaded instead of built. */
  bytes?: Uint8Array;
}

/** The exact SVG of `scene` seen by `camera`: faces split where they pass through each other, ordered exactly, hidden parts removed. */
export function exportSVG(scene: Object3D, camera: Camera, options: SvgOptions): string;

/** The visible edges of `scene` seen by `camera`, as SVG strokes for pen plotters. */
export function plotEdges(scene: Object3D, camera: Camera, options: PlotOptions): string;

/** Every visible mesh under `root` as world-space triangles, in ID order, with sRGB RGBA colours and the faces drawn. */
export function gatherTriangles(root: Object3D): {
  positions: Float64Array;
  indices: Uint32Array;
  colours: Uint8Array;
  cull: 'back' | 'front' | 'none';
};

/** Certifies a static mesh's triangles: the certificate as plain data for any engine. */
export function certify(mesh: Mesh, options?: CertifyOptions): {
  certificate: Certificate;
  source: { positions: Float64Array; indices: Uint32Array };
};

/** Certifies a static mesh in a module worker; resolves to bytes for `new ExactTransparency(mesh, { bytes })`. */
export function certifyInWorker(mesh: Mesh, options?: Omit<CertifyOptions, 'bytes'>): Promise<Uint8Array>;

/** Exact transparency for a static mesh whose material has `side = FrontSide`. */
export class ExactTransparency {
  constructor(mesh: Mesh, options?: CertifyOptions);
  readonly mesh: Mesh;
  readonly certificate: Certificate;
  /** The certified geometry that replaced the mesh's own. */
  readonly geometry: BufferGeometry;
  /** The mesh's own geometry, put back by `dispose`. */
  readonly originalGeometry: BufferGeometry;
  /** Whether the last frame was outside the certificate (drawn by centroid, not exact). */
  readonly fellBack: boolean;
  /** Frames drawn so far. */
  readonly frames: number;
  /** Frames outside the certificate so far. */
  readonly fallbackFrames: number;
  /** Certified orders. */
  readonly orders: number;
  /** The certificate as bytes. */
  toBytes(): Uint8Array;
  /** Puts the mesh's own geometry and `onBeforeRender` back and frees the certificate. */
  dispose(): void;
}

// The module worker of `certifyInWorker`: certifies triangles and posts the bytes back.
import { bindings } from './wasm.js';

self.onmessage = ({ data }) => {
  try {
    const certificate = new bindings.Certificate(data.positions, data.indices, data.minEyeDistance, data.maxBuildMs);
    const bytes = certificate.toBytes();
    certificate.free();
    self.postMessage({ bytes }, [bytes.buffer]);
  } catch (e) {
    self.postMessage({ error: String(e.message ?? e) });
  }
};

// The module worker of `certifyInWorker`: certifies triangles and posts the bytes back.
// The handler is installed before the WebAssembly module loads, so that no message posted
// meanwhile is lost.
const ready = import('./wasm.js');

self.onmessage = async ({ data }) => {
  try {
    const { bindings } = await ready;
    const certificate = new bindings.Certificate(data.positions, data.indices, data.minEyeDistance, data.maxBuildMs);
    const bytes = certificate.toBytes();
    certificate.free();
    self.postMessage({ bytes }, [bytes.buffer]);
  } catch (e) {
    self.postMessage({ error: String(e?.message ?? e) });
  }
};

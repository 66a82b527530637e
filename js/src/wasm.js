// Loads the WebAssembly module once, in a browser (fetched beside this file) or in Node
// (read from disk), before any export of the package runs.
import init, * as bindings from '../pkg/facesort_wasm.js';

const url = new URL('../pkg/facesort_wasm_bg.wasm', import.meta.url);
let exports;
if (url.protocol === 'file:') {
  const { readFile } = await import('node:fs/promises');
  exports = await init({ module_or_path: await readFile(url) });
} else {
  exports = await init({ module_or_path: url });
}

/** The module's memory (read `memory.buffer` anew: it is replaced when the memory grows). */
const memory = exports.memory;

export { bindings, memory };
